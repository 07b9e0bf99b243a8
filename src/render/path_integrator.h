// holoray/render: the path integrator, one text for both devices (issue 70):
// unidirectional path tracing with next-event estimation and multiple
// importance sampling (Veach 1997, ch. 9; pbrt-v4's PathIntegrator), Russian
// roulette from the third vertex. Compiled as C++ by render/path_tracer.cpp
// (hr_real, hr_vec3 in double: render/path_compat.hpp) and as GLSL by the
// GPU kernel (gpu/shaders/path.glsl, in float), in the subset
// shading/common.h describes. What it calls per vertex (the BSDF, its
// sampling, the lights' falloff and shapes, the sampler) is shading/.
//
// Each device defines, before including this header, how it reaches its
// scene (the hooks), in namespace holoray::shading on the CPU:
//
//   struct HrPathDevice   its state: the scene, the ray counts, where the
//                         first hit goes (AOVs)
//   struct HrPathHit      what a ray met, read through hr_path_hit_t(h) (the
//                         distance along the ray), hr_path_hit_p(h) (the
//                         point), hr_path_hit_ng(h) and hr_path_hit_ns(h)
//                         (geometric and shading normals, unit, as the
//                         surface faces)
//   bool hr_path_trace(d, o, dir, tmin, tmax, depth, out h)   the closest
//                         hit on o + t dir over (tmin, tmax), its surface
//                         (the first's, depth 1, recorded for the AOVs)
//   hr_vec3 hr_path_unblocked(d, from, dir, tmax, term)   `term` where
//                         nothing lies on the shadow ray's (0, tmax), else
//                         0 (a wavefront returns 0 and adds `term` once its
//                         own pass finds the ray unblocked)
//   void hr_path_count(d, HR_PATH_RAY_*)        one ray more of that kind
//   hr_real hr_path_epsilon(d), int hr_path_max_depth(d)
//   bool hr_path_light_sphere(d, h, out colour)  h is a light's own sphere
//                         (Tachyon's): seen, it shows `colour` unshaded
//   hr_vec3 hr_path_emission(d, h, dir, specular, last_pdf)  the emission
//                         met at h along dir, MIS-weighted against the
//                         emitters' sampling unless the bounce was a delta
//                         lobe (`specular`); 0 where h does not emit
//   HrBsdf hr_path_bsdf(d, h, cos_o, entering)  the BSDF at h
//   int hr_path_light_count(d), HrPathLight hr_path_light(d, l)
//   int hr_path_area_light_count(d), HrPathAreaLight hr_path_area_light(d, a)
//   hr_vec3 hr_path_escape(d, dir)     what a ray leaving the scene sees
//   bool hr_path_env_lights(d)         the environment is light-sampled
//   float hr_path_env_pdf(d, dir)      the density of its sampling of dir
//   hr_vec3 hr_path_env_sample(d, u_cell, u, out dir, out pdf)  a direction
//                         drawn by the light it brings, and that light
//   bool hr_path_has_emitters(d)
//   bool hr_path_emitter_sample(d, u_pick, u_emit, p, out dir, out dist,
//                         out le, out pdf)  a point of the emissive
//                         surfaces seen from p: false where it cannot light
//                         p; else le its radiance over its density pdf
//                         (solid angle at p)
#ifndef HOLORAY_RENDER_PATH_INTEGRATOR_H
#define HOLORAY_RENDER_PATH_INTEGRATOR_H

#include "render/path_records.h"

// Russian roulette starts after this many bounces (pbrt-v4's depth 1 of
// its 0-based count is our third vertex: the eye's, and two more).
#define HR_PATH_ROULETTE_DEPTH 3

// The integrator's functions: in C++ local to the file that includes them
// (render/path_tracer.cpp), inlined where the compiler finds it pays, as the
// CPU's light sampling was before it was shared (always_inline, HR_FN's,
// would paste next-event estimation whole into the bounce loop).
// HR_PATH_IN(T): a record read, not changed (by reference in C++).
#ifdef __cplusplus
#define HR_PATH_FN static inline
#define HR_PATH_IN(T) const T&
#else
#define HR_PATH_FN
#define HR_PATH_IN(T) T
#endif

HR_BEGIN

/// One light sample's share at vertex `v`: light arriving along `dir`
/// (world, unit) from `dist` away, `le` its radiance over the density it
/// was drawn with (solid angle; `pdf` 0 for a delta light, which nothing
/// else can draw), MIS-weighted against the BSDF's own sampling of `dir`.
/// Zero when the light is behind the surface (unless it transmits, rough:
/// then from behind, on that side of the shading normal too) or blocked.
HR_PATH_FN hr_vec3 hr_path_light_sample(HR_INOUT(HrPathDevice) d, HR_PATH_IN(HrPathVertex) v, hr_vec3 dir, hr_real dist, hr_vec3 le,
                                   hr_real pdf) {
  bool behind = dot(dir, v.ng) <= 0.0;
  if (behind && !(v.bsdf.transmit_alpha > 0.0f)) return hr_vec3(0.0, 0.0, 0.0);
  vec3 wi = hr_to_local(hr_f3(dir), v.t, v.b, v.n);
  if (behind != (wi.z < 0.0f)) return hr_vec3(0.0, 0.0, 0.0);
  vec3 f = hr_bsdf_eval(v.bsdf, v.wo, wi);
  if (!hr_path_positive(f)) return hr_vec3(0.0, 0.0, 0.0);
  hr_path_count(d, HR_PATH_RAY_SHADOW);
  hr_vec3 from = behind ? v.below : v.above;
  hr_real w = pdf > 0.0 ? hr_real(hr_power_heuristic(float(pdf), hr_bsdf_pdf(v.bsdf, v.wo, wi))) : hr_real(1.0);
  return hr_path_unblocked(d, from, dir, isinf(dist) ? HR_PATH_INF : dist - 2.0 * hr_path_epsilon(d), hr_mul3(hr_d3(f), le) * w);
}

/// Next-event estimation at `v`: every point, spot and directional light
/// (one point of a soft one), every area light (one point each), one
/// direction of the environment, one point of the emissive surfaces. Each
/// draws its numbers whether or not it lights `v`, so that the sampler's
/// dimensions stay aligned between pixels.
HR_PATH_FN hr_vec3 hr_path_direct_light(HR_INOUT(HrPathDevice) d, HR_PATH_IN(HrPathVertex) v, HR_INOUT(HrSampler) rng) {
  hr_real eps = hr_path_epsilon(d);
  hr_vec3 sum = hr_vec3(0.0, 0.0, 0.0);
  int n_lights = hr_path_light_count(d);
  for (int l = 0; l < n_lights; ++l) {
    HrPathLight L = hr_path_light(d, l);
    if (L.skip) continue;
    vec2 u = hr_next2(rng);  // a pair for each light, soft or not
    hr_vec3 dir = -L.direction;
    hr_vec3 from = L.position;
    hr_real dist = HR_PATH_INF;
    hr_real cos_l = 1.0;
    if (L.kind == HR_LIGHT_KIND_DIRECTIONAL) {
      if (L.cos_half_angle < 1.0) {
        // Uniform over the sun's cone: radiance S / cone, so the estimate
        // is f S, as a delta light's (Cycles' disk: within 0.01 %).
        vec3 ct;
        vec3 cb;
        vec3 axis = hr_f3(dir);
        hr_frame(axis, ct, cb);
        dir = normalize(hr_d3(hr_to_world(hr_uniform_cone(u, float(L.cos_half_angle)), ct, cb, axis)));
      }
    } else {
      if (L.radius > 0.0) {
        // A disk facing the point (Cycles' sphere light): drawn uniformly,
        // its radiance I / (pi r^2) makes the estimate f I cos_l / d^2.
        hr_vec3 facing = normalize(v.p - L.position);
        from = hr_d3(hr_disk_light_point(hr_f3(L.position), hr_f3(facing), float(L.radius), u));
        cos_l = abs(dot(facing, normalize(v.p - from)));
      }
      dir = from - v.p;
      dist = length(dir);
      if (!(dist > eps)) continue;
      dir = dir / dist;
    }
    float falloff = hr_light_falloff(L.falloff, hr_f3(dir), float(dist));
    if (falloff > 0.0f)
      sum += hr_path_light_sample(d, v, dir, dist, L.intensity * (HR_PATH_PI * hr_real(falloff) * cos_l), 0.0);
  }
  int n_areas = hr_path_area_light_count(d);
  for (int a = 0; a < n_areas; ++a) {
    HrPathAreaLight A = hr_path_area_light(d, a);
    vec2 u = hr_next2(rng);
    hr_vec3 dir = hr_d3(hr_area_light_point(hr_f3(A.centre), hr_f3(A.axis_u), hr_f3(A.axis_v), A.ellipse, u)) - v.p;
    hr_real dist2 = dot(dir, dir);
    hr_real dist = sqrt(dist2);
    if (!(dist > eps)) continue;
    dir = dir / dist;
    hr_real cos_l = -dot(dir, A.normal);  // one-sided: it lights the side its normal faces
    if (!(cos_l > 0.0)) continue;
    hr_real pdf = dist2 / (cos_l * A.area);
    sum += hr_path_light_sample(d, v, dir, dist, A.radiance * (hr_real(1.0) / pdf), pdf);
  }
  // The environment and the emitters draw their dimensions only where the
  // render has them (fixed per render: the streams stay aligned).
  if (hr_path_env_lights(d)) {
    vec2 u_cell = hr_next2(rng);
    vec2 u_env = hr_next2(rng);
    hr_vec3 dir;
    hr_real pdf;
    hr_vec3 le = hr_path_env_sample(d, u_cell.x, u_env, dir, pdf);
    if (pdf > 0.0) sum += hr_path_light_sample(d, v, dir, HR_PATH_INF, le * (hr_real(1.0) / pdf), pdf);
  }
  if (hr_path_has_emitters(d)) {
    vec2 u_pick = hr_next2(rng);
    vec2 u_emit = hr_next2(rng);
    hr_vec3 dir;
    hr_vec3 le;
    hr_real dist;
    hr_real pdf;
    if (hr_path_emitter_sample(d, u_pick, u_emit, v.p, dir, dist, le, pdf))
      sum += hr_path_light_sample(d, v, dir, dist, le, pdf);
  }
  return sum;
}

/// The area lights the ray o + t dir meets before `t_max`, seen from their
/// lit side (not by the eye, as Blender's by default: the caller skips the
/// eye ray), each weighted against its light sampling's density unless the
/// bounce was a delta lobe (`specular`).
HR_PATH_FN hr_vec3 hr_path_area_lights_met(HR_INOUT(HrPathDevice) d, hr_vec3 o, hr_vec3 dir, hr_real t_max, bool specular,
                                      float last_pdf) {
  hr_vec3 sum = hr_vec3(0.0, 0.0, 0.0);
  int n_areas = hr_path_area_light_count(d);
  for (int a = 0; a < n_areas; ++a) {
    HrPathAreaLight A = hr_path_area_light(d, a);
    float t = hr_area_light_hit(hr_f3(o), hr_f3(dir), float(min(t_max, hr_real(3.0e38))), hr_f3(A.centre), hr_f3(A.axis_u),
                                hr_f3(A.axis_v), hr_f3(A.normal), A.ellipse);
    hr_real cos_l = -dot(dir, A.normal);
    if (!(t > 0.0f) || !(cos_l > 0.0)) continue;
    float pdf_light = hr_area_to_solid_angle(float(hr_real(1.0) / A.area), t * t, float(cos_l));
    sum += A.radiance * (specular ? hr_real(1.0) : hr_real(hr_power_heuristic(last_pdf, pdf_light)));
  }
  return sum;
}

/// The vertex at `h`, met along `dir`: its normals turned to the side the
/// path came from (a shading normal turned away from it by interpolation
/// gives way to the geometric one), its frame, and its BSDF.
HR_PATH_FN HrPathVertex hr_path_vertex(HR_INOUT(HrPathDevice) d, HR_PATH_IN(HrPathHit) h, hr_vec3 dir) {
  HrPathVertex v;
  v.p = hr_path_hit_p(h);
  hr_vec3 view = -dir;
  hr_vec3 ng = hr_path_hit_ng(h);
  bool front = dot(ng, view) >= 0.0;
  v.ng = front ? ng : -ng;
  hr_vec3 ns = front ? hr_path_hit_ns(h) : -hr_path_hit_ns(h);
  if (dot(ns, view) <= 0.0) ns = v.ng;
  v.n = hr_f3(ns);
  hr_frame(v.n, v.t, v.b);
  v.wo = hr_to_local(hr_f3(view), v.t, v.b, v.n);
  v.bsdf = hr_path_bsdf(d, h, v.wo.z, front);
  hr_real eps = hr_path_epsilon(d);
  v.above = v.p + v.ng * eps;
  v.below = v.p - v.ng * eps;
  return v;
}

/// A path starting along the eye ray o + t dir, t in (tmin, tmax) (world).
HR_PATH_FN HrPathState hr_path_start(hr_vec3 o, hr_vec3 dir, hr_real tmin, hr_real tmax) {
  HrPathState s;
  s.o = o;
  s.dir = dir;
  s.tmin = tmin;
  s.tmax = tmax;
  s.radiance = hr_vec3(0.0, 0.0, 0.0);
  s.throughput = hr_vec3(1.0, 1.0, 1.0);
  s.specular = true;  // no bounce yet: no MIS on what the eye ray meets
  s.last_pdf = 0.0f;
  s.depth = 1;
  return s;
}

/// One vertex of the path `s`: its ray traced (hr_path_trace, into `h`),
/// the light met on the way and at the vertex added, next-event estimation
/// at it (through hr_path_unblocked), and the next ray drawn from its BSDF
/// with Russian roulette. False: the path has ended (`s.radiance` is then
/// its light, but for what hr_path_unblocked deferred).
HR_PATH_FN bool hr_path_step(HR_INOUT(HrPathDevice) d, HR_INOUT(HrPathState) s, HR_INOUT(HrPathHit) h, HR_INOUT(HrSampler) rng) {
  // max_depth counts the eye ray as 1 (pbrt's maxDepth; Cycles' bounces
  // plus 1): a vertex past it only shows its emission, which completes the
  // MIS of the vertex before.
  int max_depth = hr_path_max_depth(d);
  int depth = s.depth;
  bool found = hr_path_trace(d, s.o, s.dir, s.tmin, s.tmax, depth, h);
  if (depth > 1)
    s.radiance += hr_mul3(s.throughput, hr_path_area_lights_met(d, s.o, s.dir, found ? hr_path_hit_t(h) : HR_PATH_INF, s.specular, s.last_pdf));
  if (!found) {
    hr_real w = 1.0;
    if (!s.specular && hr_path_env_lights(d)) w = hr_real(hr_power_heuristic(s.last_pdf, hr_path_env_pdf(d, s.dir)));
    s.radiance += hr_mul3(s.throughput, hr_path_escape(d, s.dir)) * w;
    return false;
  }
  hr_vec3 sphere;
  if (hr_path_light_sphere(d, h, sphere)) {
    s.radiance += hr_mul3(s.throughput, sphere);
    return false;
  }
  s.radiance += hr_mul3(s.throughput, hr_path_emission(d, h, s.dir, s.specular, s.last_pdf));
  if (depth > max_depth) return false;

  HrPathVertex v = hr_path_vertex(d, h, s.dir);
  if (hr_path_positive(v.bsdf.diffuse) || v.bsdf.alpha > 0.0f) s.radiance += hr_mul3(s.throughput, hr_path_direct_light(d, v, rng));

  // The next direction, from the BSDF.
  vec2 u_lobe = hr_next2(rng);
  vec2 u_dir = hr_next2(rng);
  vec3 wi;
  vec3 weight;
  float pdf;
  bool delta;
  bool through;
  if (!hr_bsdf_sample(v.bsdf, v.wo, u_lobe.x, u_dir, wi, weight, pdf, delta, through)) return false;
  hr_vec3 next = normalize(hr_d3(hr_to_world(wi, v.t, v.b, v.n)));
  // A reflected direction below the geometric surface (the shading
  // normal's tilt) would leave from inside: the path ends there; so does
  // rough transmission back above it, mirrored.
  if (!through && dot(next, v.ng) <= 0.0) return false;
  if (through && !delta && dot(next, v.ng) >= 0.0) return false;
  s.throughput = hr_mul3(s.throughput, hr_d3(weight));
  s.specular = delta;
  s.last_pdf = pdf;
  hr_path_count(d, through ? HR_PATH_RAY_REFRACTED : HR_PATH_RAY_REFLECTED);
  s.o = through ? v.below : v.above;
  s.dir = next;
  s.tmin = 0.0;
  s.tmax = HR_PATH_INF;
  s.depth = depth + 1;
  // Russian roulette (pbrt-v4's): a path whose throughput has fallen
  // below 1 goes on with that probability, weighted up to stay unbiased.
  hr_real keep = max(s.throughput.x, max(s.throughput.y, s.throughput.z));
  if (depth >= HR_PATH_ROULETTE_DEPTH && keep < 1.0) {
    if (!(u_lobe.y < keep)) return false;
    s.throughput = s.throughput * (hr_real(1.0) / keep);
  }
  return true;
}

/// Radiance (linear RGB) arriving along the eye ray o + t dir, t in
/// (tmin, tmax) (world; one sample of a pixel), its random numbers from
/// `sampler`, whose first pair placed the sample in its pixel.
HR_PATH_FN hr_vec3 hr_path_radiance(HR_INOUT(HrPathDevice) d, hr_vec3 o, hr_vec3 dir, hr_real tmin, hr_real tmax,
                               HR_INOUT(HrSampler) rng) {
  HrPathState s = hr_path_start(o, dir, tmin, tmax);
  HrPathHit h;  // one for the path: on the CPU it holds the hit's surface, not built anew each bounce
  bool more = true;
  while (more) more = hr_path_step(d, s, h, rng);  // the loop's one exit in its condition (design/gpu.md: lavapipe and loops)
  return s.radiance;
}

HR_END

#endif
