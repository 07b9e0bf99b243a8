// holoray/shading: the GGX (Trowbridge-Reitz) microfacet distribution with
// Smith's separable masking-shadowing, and the sampling of its visible
// normals (Heitz 2018, "Sampling the GGX Distribution of Visible Normals",
// JCGT 7(4)). Local frame: the shading normal is +z. `alpha` is glTF's
// roughness squared. Shared by both devices.
#ifndef HOLORAY_SHADING_MICROFACET_H
#define HOLORAY_SHADING_MICROFACET_H

#include "shading/common.h"

HR_BEGIN

/// Below this alpha the lobe is a mirror to float precision: alpha is held
/// there (a mirror's highlight then spans about 0.1 degree).
#define HR_MIN_ALPHA 1.0e-3f

/// D(h) = alpha^2 / (pi ((n.h)^2 (alpha^2 - 1) + 1)^2), glTF Appendix B.3.2.
HR_FN float hr_ggx_d(float n_dot_h, float alpha) {
  float a2 = alpha * alpha;
  float t = n_dot_h * n_dot_h * (a2 - 1.0f) + 1.0f;
  return n_dot_h > 0.0f ? a2 / (HR_PI * t * t) : 0.0f;
}

/// Smith's masking of one direction whose cosine to the normal is `c`:
/// 2 c / (c + sqrt(alpha^2 + (1 - alpha^2) c^2)), 0 below the surface.
HR_FN float hr_smith_g1(float c, float alpha) {
  if (c <= 0.0f) return 0.0f;
  float a2 = alpha * alpha;
  return 2.0f * c / (c + sqrt(a2 + (1.0f - a2) * c * c));
}

/// Schlick's Fresnel: f0 + (1 - f0) (1 - cos)^5, per channel and scalar.
HR_FN float hr_schlick(float f0, float c) {
  float m = clamp(1.0f - c, 0.0f, 1.0f);
  float m2 = m * m;
  return f0 + (1.0f - f0) * m2 * m2 * m;
}
HR_FN vec3 hr_schlick3(vec3 f0, float c) {
  float m = clamp(1.0f - c, 0.0f, 1.0f);
  float m2 = m * m;
  return f0 + (vec3(1.0f) - f0) * (m2 * m2 * m);
}

/// A microfacet normal seen from `wo` (local, wo.z > 0), with density
/// D_wo(h) = G1(wo) max(0, wo.h) D(h) / wo.z (Heitz 2018, listing 1).
HR_FN vec3 hr_ggx_sample_visible(vec3 wo, float alpha, vec2 u) {
  vec3 vh = normalize(vec3(alpha * wo.x, alpha * wo.y, wo.z));
  float len2 = vh.x * vh.x + vh.y * vh.y;
  vec3 t1 = len2 > 0.0f ? vec3(-vh.y, vh.x, 0.0f) / sqrt(len2) : vec3(1.0f, 0.0f, 0.0f);
  vec3 t2 = cross(vh, t1);
  float r = sqrt(u.x);
  float phi = 2.0f * HR_PI * u.y;
  float p1 = r * cos(phi);
  float p2 = r * sin(phi);
  float s = 0.5f * (1.0f + vh.z);
  p2 = (1.0f - s) * sqrt(max(0.0f, 1.0f - p1 * p1)) + s * p2;
  vec3 nh = t1 * p1 + t2 * p2 + vh * sqrt(max(0.0f, 1.0f - p1 * p1 - p2 * p2));
  return normalize(vec3(alpha * nh.x, alpha * nh.y, max(1.0e-6f, nh.z)));
}

/// The density of `wi` = reflect(-wo, h) under hr_ggx_sample_visible:
/// D_wo(h) / (4 wo.h) = G1(wo) D(h) / (4 wo.z).
HR_FN float hr_ggx_reflection_pdf(vec3 wo, vec3 wi, float alpha) {
  if (wo.z <= 0.0f || wi.z <= 0.0f) return 0.0f;
  vec3 h = normalize(wo + wi);
  return hr_smith_g1(wo.z, alpha) * hr_ggx_d(h.z, alpha) / (4.0f * wo.z);
}

HR_END

#endif
