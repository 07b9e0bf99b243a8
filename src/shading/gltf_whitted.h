// holoray/shading: glTF 2.0's metallic-roughness BRDF (the specification's
// Appendix B) as Whitted's integrator uses it, for both devices: the light
// a point or directional light reflects, and the weights of the one mirror
// ray and the one transmitted ray each hit casts (render/models/
// gltf_model.cpp; gpu/shaders/trace.comp). The path integrator samples the
// same BRDF as lobes (bsdf.h). Units: the terms are pi f cos, so that a
// light of colour I gives I times them (lights.h).
#ifndef HOLORAY_SHADING_GLTF_WHITTED_H
#define HOLORAY_SHADING_GLTF_WHITTED_H

#include "shading/common.h"

HR_BEGIN

/// (1 - cos)^5, cos clamped to [0, 1]: Schlick's Fresnel weight.
HR_FN float hr_schlick_weight(float cos_theta) {
  float m = 1.0f - clamp(cos_theta, 0.0f, 1.0f);
  float m2 = m * m;
  return m2 * m2 * m;
}

/// Smith's G1 term for GGX as Appendix B.3.2 writes it, times 1 / (2 |N.X|):
/// the two factors multiply to V = G / (4 |N.L| |N.V|).
HR_FN float hr_smith_half(float n_dot_x, float a2) { return 1.0f / (n_dot_x + sqrt(a2 + (1.0f - a2) * n_dot_x * n_dot_x)); }

/// pi f(l, v) max(0, N.L) of a surface of base colour `base`, `metallic`,
/// `roughness`, dielectric reflectance `f0` and KHR transmission
/// `transmission`, seen along `view` and lit along `to_light` (world,
/// unit; `n` the shading normal). An interpolated normal may face away from
/// the viewer: the specification's implementation takes |N.V| there.
HR_FN vec3 hr_gltf_direct(vec3 base, float metallic, float roughness, float f0, float transmission, vec3 n, vec3 view,
                          vec3 to_light) {
  float n_dot_l = dot(n, to_light);
  if (!(n_dot_l > 0.0f)) return vec3(0.0f);
  float n_dot_v = max(abs(dot(n, view)), 1.0e-6f);
  vec3 h = normalize(to_light + view);
  float n_dot_h = max(dot(n, h), 0.0f);
  float v_dot_h = abs(dot(view, h));
  float a = roughness * roughness;
  float a2 = max(a * a, 1.0e-12f);  // a perfect mirror's highlight: a point light's is a point
  // (N.H)^2 (a^2 - 1) + 1 as sin^2 + cos^2 a^2, the sine from N x H: the
  // first form loses a sharp highlight's peak to cancellation in float.
  vec3 nxh = cross(n, h);
  float d_denom = n_dot_h > 0.0f ? dot(nxh, nxh) + n_dot_h * n_dot_h * a2 : 1.0f;
  float specular = a2 / (HR_PI * d_denom * d_denom) * hr_smith_half(n_dot_l, a2) * hr_smith_half(n_dot_v, a2);
  float w = hr_schlick_weight(v_dot_h);
  float f_d = f0 + (1.0f - f0) * w;
  vec3 f_m = base + (vec3(1.0f) - base) * w;
  float m = clamp(metallic, 0.0f, 1.0f);
  // pi * f: the Lambertian 1/pi cancels.
  vec3 dielectric = base * ((1.0f - f_d) * (1.0f - clamp(transmission, 0.0f, 1.0f))) + vec3(f_d * specular * HR_PI);
  return (dielectric * (1.0f - m) + f_m * (specular * HR_PI * m)) * n_dot_l;
}

/// The mirror ray's weight: the Fresnel mix at N.V (dielectric f_d, metal
/// f_m), for a surface smoother than gltf_brdf.hpp's kMirrorRoughness.
HR_FN vec3 hr_gltf_mirror_weight(vec3 base, float metallic, float f0, float n_dot_v) {
  float w = hr_schlick_weight(abs(n_dot_v));
  float f_d = f0 + (1.0f - f0) * w;
  float m = clamp(metallic, 0.0f, 1.0f);
  return vec3(f_d) * (1.0f - m) + (base + (vec3(1.0f) - base) * w) * m;
}

/// The transmitted ray's weight (thin-walled KHR_materials_transmission):
/// the dielectric's share not reflected, tinted by the base colour.
HR_FN vec3 hr_gltf_transmit_weight(vec3 base, float metallic, float f0, float transmission, float n_dot_v) {
  float f_d = f0 + (1.0f - f0) * hr_schlick_weight(abs(n_dot_v));
  return base * ((1.0f - clamp(metallic, 0.0f, 1.0f)) * clamp(transmission, 0.0f, 1.0f) * (1.0f - f_d));
}

HR_END

#endif
