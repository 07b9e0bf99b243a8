// holoray/shading: the path tracer's BSDF, one record for every material
// model holoray reads, evaluated, sampled and given its density in the
// local frame of the shading normal (+z, on the side the path came from:
// wo.z > 0). Shared by both devices. Lobes:
//
//   diffuse   Lambert, albedo `diffuse` (NFF's Kd C, Tachyon's diffuse C;
//             for glTF (1 - metallic)(1 - T) c, times 1 - F(wo.h) as the
//             specification's Appendix B mixes it under the specular layer;
//             with `principled`, Blender 3.x's Principled BSDF instead:
//             Burley's diffuse with its retro-reflection (Burley 2015, as
//             Cycles' principled_diffuse), whole under the specular layer)
//   glossy    glTF's GGX layer (Appendix B): dielectric F_d D V over it,
//             metal F_m D V, V Smith's separable term / (4 |n.l| |n.v|)
//   mirror    a delta reflection of weight `mirror` (NFF's Ks, Tachyon's
//             specular): a perfect mirror, as Whitted's ray
//   transmit  a transmission of weight `transmit`: a delta lobe refracted
//             by `eta` (NFF's T and ior; 1: straight on, Tachyon's opacity
//             and glTF's thin-walled KHR_materials_transmission when
//             smooth); or, rough (`transmit_alpha` > 0), glTF's thin-walled
//             specular BTDF: the GGX reflection lobe mirrored through the
//             surface, centred on the straight-on direction, with the
//             specification's D V (KHR_materials_transmission, "Transmission
//             BTDF"; the sample viewer mirrors the light the same way)
//
// hr_bsdf_eval and hr_bsdf_pdf cover the non-delta lobes (what light
// sampling can reach: below the surface, wi.z < 0, only rough
// transmission); hr_bsdf_sample picks any lobe.
#ifndef HOLORAY_SHADING_BSDF_H
#define HOLORAY_SHADING_BSDF_H

#include "shading/microfacet.h"
#include "shading/warp.h"

HR_BEGIN

struct HrBsdf {
  vec3 diffuse;   ///< Lambert albedo (linear RGB)
  vec3 base;      ///< glTF base colour c (linear RGB)
  float metallic; ///< glTF metallic
  float alpha;    ///< glTF roughness^2 (>= HR_MIN_ALPHA); 0: no glossy lobe
  float f0;       ///< the dielectric's reflectance at normal incidence
  vec3 mirror;    ///< delta reflection weight
  vec3 transmit;  ///< delta transmission weight
  float eta;      ///< incident over transmitted index for `transmit`; 1: unbent
  float transmit_alpha;  ///< 0: `transmit` is a delta lobe; else its GGX alpha (thin-walled rough transmission)
  float principled;  ///< 1: the diffuse lobe as Blender's Principled BSDF (above), with `roughness`; 0: glTF's
  float roughness;   ///< the surface's roughness, for the principled diffuse's retro-reflection
};

/// Blender 3.x's Principled diffuse (Cycles' bsdf_principled_diffuse, after
/// Burley 2015): f pi / base at cosines `cl`, `cv` and the half-vector's
/// cosine to the light `lh`: (1 - FL/2)(1 - FV/2) + RR (FL + FV + FL FV (RR - 1)),
/// RR = 2 roughness lh^2, F = (1 - cos)^5.
HR_FN float hr_principled_diffuse(float cl, float cv, float lh, float roughness) {
  float ml = clamp(1.0f - cl, 0.0f, 1.0f);
  float mv = clamp(1.0f - cv, 0.0f, 1.0f);
  float fl = ml * ml * ml * ml * ml;
  float fv = mv * mv * mv * mv * mv;
  float rr = 2.0f * roughness * lh * lh;
  return (1.0f - 0.5f * fl) * (1.0f - 0.5f * fv) + rr * (fl + fv + fl * fv * (rr - 1.0f));
}

/// Lobe selection probabilities at `wo`: diffuse, glossy, mirror, transmit
/// (x, y, z of `a`, and `t`), summing to 1, each proportional to the
/// luminance of what its lobe returns (the glossy lobe's by its Fresnel).
HR_FN void hr_bsdf_lobes(HrBsdf b, vec3 wo, HR_OUT(vec3) a, HR_OUT(float) t) {
  float fr = hr_schlick(b.f0, wo.z);
  float wd = hr_luminance(b.diffuse) * (b.alpha > 0.0f && b.principled == 0.0f ? 1.0f - fr : 1.0f);
  float wg = 0.0f;
  if (b.alpha > 0.0f) wg = (1.0f - b.metallic) * fr + b.metallic * hr_luminance(hr_schlick3(b.base, wo.z));
  float wm = hr_luminance(b.mirror);
  float wt = hr_luminance(b.transmit);
  float sum = wd + wg + wm + wt;
  if (!(sum > 0.0f)) {
    a = vec3(0.0f);
    t = 0.0f;
    return;
  }
  a = vec3(wd, wg, wm) / sum;
  t = wt / sum;
}

/// f(wo, wi) |wi.z| of the diffuse and glossy lobes (local frame); zero
/// unless both directions are above the surface.
HR_FN vec3 hr_bsdf_eval(HrBsdf b, vec3 wo, vec3 wi) {
  if (wo.z <= 0.0f) return vec3(0.0f);
  if (wi.z < 0.0f && b.transmit_alpha > 0.0f) {
    // The reflection lobe at wi mirrored above the surface, wm:
    // transmit D G1(wo) G1(wm) / (4 wo.z wm.z), times |wi.z| = wm.z.
    vec3 wm = vec3(wi.x, wi.y, -wi.z);
    vec3 h = normalize(wo + wm);
    float ta = b.transmit_alpha;
    return b.transmit * (hr_ggx_d(h.z, ta) * hr_smith_g1(wo.z, ta) * hr_smith_g1(wm.z, ta) / (4.0f * wo.z));
  }
  if (wi.z <= 0.0f) return vec3(0.0f);
  if (!(b.alpha > 0.0f)) return b.diffuse * (HR_INV_PI * wi.z);
  vec3 h = normalize(wo + wi);
  float voh = max(dot(wo, h), 0.0f);
  float fd = hr_schlick(b.f0, voh);
  float dv = hr_ggx_d(h.z, b.alpha) * hr_smith_g1(wo.z, b.alpha) * hr_smith_g1(wi.z, b.alpha) / (4.0f * wo.z * wi.z);
  vec3 fm = hr_schlick3(b.base, voh);
  float diffuse = b.principled > 0.0f ? hr_principled_diffuse(wi.z, wo.z, dot(wi, h), b.roughness) : 1.0f - fd;
  vec3 f = b.diffuse * (diffuse * HR_INV_PI) + vec3((1.0f - b.metallic) * fd * dv) + fm * (b.metallic * dv);
  return f * wi.z;
}

/// hr_bsdf_pdf with the lobes' probabilities `a` and `t` (hr_bsdf_lobes) given.
HR_FN float hr_bsdf_pdf_of_lobes(HrBsdf b, vec3 wo, vec3 wi, vec3 a, float t) {
  if (wo.z <= 0.0f) return 0.0f;
  if (wi.z < 0.0f && b.transmit_alpha > 0.0f)
    return t * hr_ggx_reflection_pdf(wo, vec3(wi.x, wi.y, -wi.z), b.transmit_alpha);
  if (wi.z <= 0.0f) return 0.0f;
  float p = a.x * hr_cosine_pdf(wi.z);
  if (b.alpha > 0.0f) p += a.y * hr_ggx_reflection_pdf(wo, wi, b.alpha);
  return p;
}

/// The density (solid angle) with which hr_bsdf_sample returns `wi` through
/// its diffuse and glossy lobes, their selection included.
HR_FN float hr_bsdf_pdf(HrBsdf b, vec3 wo, vec3 wi) {
  vec3 a;
  float t;
  hr_bsdf_lobes(b, wo, a, t);
  return hr_bsdf_pdf_of_lobes(b, wo, wi, a, t);
}

/// Refracts `wo` (local, wo.z > 0) through the surface: `wt` below it, for
/// eta = n_incident / n_transmitted; false on total internal reflection.
HR_FN bool hr_refract(vec3 wo, float eta, HR_OUT(vec3) wt) {
  float c = wo.z;
  float s2 = eta * eta * max(0.0f, 1.0f - c * c);
  if (s2 >= 1.0f) return false;
  wt = -wo * eta + vec3(0.0f, 0.0f, eta * c - sqrt(1.0f - s2));
  return true;
}

/// Draws a lobe with `u_lobe` and a direction with `u`: `wi` (local), its
/// throughput weight f |wi.z| / pdf, its density `pdf` (0 for the delta
/// lobes, whose `delta` is true) and whether it passes through the surface.
/// False when nothing is returned (no lobe, or below the surface).
HR_FN bool hr_bsdf_sample(HrBsdf b, vec3 wo, float u_lobe, vec2 u, HR_OUT(vec3) wi, HR_OUT(vec3) weight,
                          HR_OUT(float) pdf, HR_OUT(bool) delta, HR_OUT(bool) through) {
  vec3 a;
  float t;
  hr_bsdf_lobes(b, wo, a, t);
  delta = false;
  through = false;
  pdf = 0.0f;
  weight = vec3(0.0f);
  wi = vec3(0.0f, 0.0f, 1.0f);
  if (wo.z <= 0.0f) return false;
  if (u_lobe < a.x + a.y) {
    if (u_lobe < a.x) {
      wi = hr_cosine_hemisphere(u);
    } else {
      vec3 h = hr_ggx_sample_visible(wo, b.alpha, u);
      wi = reflect(-wo, h);
    }
    if (wi.z <= 0.0f) return false;
    pdf = hr_bsdf_pdf_of_lobes(b, wo, wi, a, t);
    if (!(pdf > 0.0f)) return false;
    weight = hr_bsdf_eval(b, wo, wi) / pdf;
    return true;
  }
  if (u_lobe < a.x + a.y + a.z) {
    delta = true;
    wi = vec3(-wo.x, -wo.y, wo.z);
    weight = b.mirror / a.z;
    return true;
  }
  if (!(t > 0.0f)) return false;
  through = true;
  if (b.transmit_alpha > 0.0f) {  // a reflected microfacet direction, mirrored below
    vec3 h = hr_ggx_sample_visible(wo, b.transmit_alpha, u);
    vec3 r = reflect(-wo, h);
    if (r.z <= 0.0f) return false;
    wi = vec3(r.x, r.y, -r.z);
    pdf = hr_bsdf_pdf_of_lobes(b, wo, wi, a, t);
    if (!(pdf > 0.0f)) return false;
    weight = hr_bsdf_eval(b, wo, wi) / pdf;
    return true;
  }
  delta = true;
  weight = b.transmit / t;
  if (b.eta == 1.0f) {
    wi = -wo;
    return true;
  }
  if (!hr_refract(wo, b.eta, wi)) {
    // Total internal reflection: the transmitted share is reflected, as
    // Whitted's second mirror ray.
    wi = vec3(-wo.x, -wo.y, wo.z);
    through = false;
  }
  return true;
}

/// A glTF metallic-roughness material as an HrBsdf (Appendix B; T the
/// KHR_materials_transmission factor, thin-walled: the transmitted share,
/// (1 - metallic) T c (1 - F(wo.z)), goes on unbent when smooth, as the
/// Whitted path's, and spread by the roughness's GGX lobe when rough).
HR_FN HrBsdf hr_gltf_bsdf(vec3 base, float metallic, float roughness, float f0, float transmission, float cos_o) {
  HrBsdf b;
  b.base = base;
  b.metallic = clamp(metallic, 0.0f, 1.0f);
  b.alpha = max(roughness * roughness, HR_MIN_ALPHA);
  b.f0 = f0;
  b.diffuse = base * ((1.0f - b.metallic) * (1.0f - transmission));
  b.mirror = vec3(0.0f);
  b.transmit = base * ((1.0f - b.metallic) * transmission * (1.0f - hr_schlick(f0, cos_o)));
  b.eta = 1.0f;
  // Rough where the glossy lobe is: below HR_MIN_ALPHA a delta, as before.
  b.transmit_alpha = roughness * roughness > HR_MIN_ALPHA ? b.alpha : 0.0f;
  b.principled = 0.0f;
  b.roughness = roughness;
  return b;
}

/// hr_gltf_bsdf as Blender 3.x's Principled BSDF layers it (HrBsdf::
/// principled): what Cycles renders of the .blend a glTF file came from.
HR_FN HrBsdf hr_principled_bsdf(vec3 base, float metallic, float roughness, float f0, float transmission, float cos_o) {
  HrBsdf b = hr_gltf_bsdf(base, metallic, roughness, f0, transmission, cos_o);
  b.principled = 1.0f;
  return b;
}

/// A Whitted-style material (NFF, MTL, Tachyon) as an HrBsdf: Lambert of
/// albedo `diffuse`, a mirror of weight `mirror`, a transmission of weight
/// `transmit` refracted by `eta`.
HR_FN HrBsdf hr_plain_bsdf(vec3 diffuse, vec3 mirror, vec3 transmit, float eta) {
  HrBsdf b;
  b.diffuse = diffuse;
  b.base = vec3(0.0f);
  b.metallic = 0.0f;
  b.alpha = 0.0f;
  b.f0 = 0.0f;
  b.mirror = mirror;
  b.transmit = transmit;
  b.eta = eta;
  b.transmit_alpha = 0.0f;
  b.principled = 0.0f;
  b.roughness = 1.0f;
  return b;
}

HR_END

#endif
