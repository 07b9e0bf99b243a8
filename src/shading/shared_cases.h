// holoray/shading: one test case of every shared function, the same text on
// both devices (shared_functions.comp on the GPU, tests/test_shading.cpp on
// the CPU): 16 inputs in, 32 outputs out, laid out below. The test compares
// the two devices' outputs to float rounding.
#ifndef HOLORAY_SHADING_SHARED_CASES_H
#define HOLORAY_SHADING_SHARED_CASES_H

#include "shading/bsdf.h"
#include "shading/environment.h"
#include "shading/gltf_whitted.h"
#include "shading/lights.h"
#include "shading/sampler.h"

HR_BEGIN

/// r[k], r[k + 1], r[k + 2] = v.
HR_FN void hr_put3(HR_ARRAY_INOUT(r, 32), uint k, vec3 v) {
  r[k] = v.x;
  r[k + 1u] = v.y;
  r[k + 2u] = v.z;
}

/// Inputs: a[0..2] wo, a[3..5] wi (normalised here; wo lifted above the
/// surface), a[6..7] a 2D uniform, a[8] the lobe's uniform, a[9..11] the
/// base colour, a[12] metallic, a[13] roughness, a[14] transmission, a[15]
/// a sample index (from 32 on, the material is Blender's principled one). Outputs: r[0..2] eval, r[3] pdf, r[4..6] sampled wi,
/// r[7..9] its weight, r[10] its pdf, r[11] delta, r[12..13] the Sobol
/// point, r[14..16] a cosine direction, r[17..19] a cone direction,
/// r[20..21] equirect uv of wi, r[22..24] the direction back (odd cases:
/// through a turned environment, and a direction drawn in a texel), r[25] a spot's
/// falloff, r[26] D, r[27] G1, r[28] the power heuristic (cases 2 mod 4:
/// r[26..28] Whitted's glTF term, hr_gltf_direct), r[29..31] the
/// frame's tangent.
HR_FN void hr_run_case(uint c, HR_ARRAY_IN(a, 16), HR_ARRAY_OUT(r, 32)) {
  vec3 wo = normalize(vec3(a[0], a[1], abs(a[2]) + 0.05f));
  vec3 wi = normalize(vec3(a[3], a[4], a[5]));
  vec2 u = vec2(a[6], a[7]);
  HrBsdf b = hr_gltf_bsdf(vec3(a[9], a[10], a[11]), a[12], a[13], 0.04f, a[14], wo.z);
  if (a[15] >= 32.0f) b = hr_principled_bsdf(vec3(a[9], a[10], a[11]), a[12], a[13], 0.04f, a[14], wo.z);
  hr_put3(r, 0u, hr_bsdf_eval(b, wo, wi));
  r[3] = hr_bsdf_pdf(b, wo, wi);
  vec3 si;
  vec3 sw;
  float sp;
  bool delta;
  bool through;
  bool ok = hr_bsdf_sample(b, wo, a[8], u, si, sw, sp, delta, through);
  hr_put3(r, 4u, ok ? si : vec3(9.0f));
  hr_put3(r, 7u, ok ? sw : vec3(0.0f));
  r[10] = ok ? sp : 0.0f;
  r[11] = delta ? 1.0f : 0.0f;
  HrSampler s = hr_sampler(hr_pixel_seed(c, c * 7u, 3u), uint(a[15]));
  vec2 q = hr_next2(s);
  q = hr_next2(s);
  r[12] = q.x;
  r[13] = q.y;
  hr_put3(r, 14u, hr_cosine_hemisphere(u));
  hr_put3(r, 17u, hr_uniform_cone(u, 0.9f));
  vec2 uv = hr_equirect_uv(wi);
  vec3 back = hr_equirect_direction(uv);
  if (c % 2u == 1u) {  // the environment turned (a[6] of a turn) and its up axis +y or +z, and a texel's direction
    float turn = a[6] * 2.0f * HR_PI;
    bool up_y = a[8] < 0.5f;
    uv = hr_equirect_uv(hr_env_from_world(wi, cos(turn), sin(turn), up_y));
    // A texel picked from the colour inputs (hr_env_texel_of of a texel's edge may fall either side).
    back = hr_env_to_world(hr_env_texel_direction(int(a[9] * 63.0f), int(a[10] * 31.0f), 64, 32, u), cos(turn), sin(turn), up_y);
  }
  r[20] = uv.x;
  r[21] = uv.y;
  hr_put3(r, 22u, back);
  HrLightFalloff l;
  l.kind = HR_LIGHT_KIND_SPOT;
  l.direction = -wo;
  l.kc = 1.0f;
  l.kl = 0.0f;
  l.kq = 1.0f;
  l.range = 4.0f;
  l.fall_start = 0.3f;
  l.fall_end = 0.6f;
  l.cos_fall_start = cos(0.3f);
  l.cos_fall_end = cos(0.6f);
  l.smooth_cone = a[8] < 0.5f;
  l.unit = false;
  r[25] = hr_light_falloff(l, wi, 1.0f + a[6]);
  r[26] = hr_ggx_d(wo.z, max(a[13] * a[13], HR_MIN_ALPHA));
  r[27] = hr_smith_g1(wi.z, max(a[13] * a[13], HR_MIN_ALPHA));
  r[28] = hr_power_heuristic(a[6], a[7]);
  if (c % 4u == 2u)  // Whitted's glTF term instead, lit along wi and seen along wo
    hr_put3(r, 26u, hr_gltf_direct(vec3(a[9], a[10], a[11]), a[12], a[13], 0.04f, a[14], vec3(0.0f, 0.0f, 1.0f), wo, wi));
  vec3 t;
  vec3 bt;
  hr_frame(wi, t, bt);
  hr_put3(r, 29u, t);
}

HR_END

#endif
