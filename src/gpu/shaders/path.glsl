// holoray/gpu: the path integrator on the device (trace.comp's kPath):
// render/path_tracer.cpp's estimator step for step (next-event estimation
// with MIS, Russian roulette after the third vertex), over the GPU path's
// scene arrays, with the same shared shading/ headers for the BSDFs, the
// lights, the environment's mapping and the sampler. One sample of each
// pixel a pass (band.sample_index), added to the passes before: an
// invocation's loops stay inside lavapipe's 65535 iterations whatever the
// samples per pixel (shared/docs/gpu-notes.md). Included by trace.comp,
// whose traversal, camera lines and surfaces it calls.
#include "shading/sampler.h"
#include "shading/bsdf.h"
#include "shading/lights.h"
#include "shading/environment.h"

layout(std430, binding = 22) readonly buffer AreaLightBlock { GpuAreaLight area_lights[]; };
layout(std430, binding = 23) readonly buffer EnvironmentBlock { GpuEnvTexel env_texels[]; };
layout(std430, binding = 24) readonly buffer EmitterBlock { GpuEmitter emitters[]; };

// Russian roulette starts at this vertex (path_tracer.cpp, kRouletteDepth).
const int kRouletteDepth = 3;

// ---- the environment (render/environment.cpp) ----

vec3 env_texel(int x, int y) { return env_texels[y * F.path_counts.z + x].radiance_share.xyz; }

vec2 env_uv(vec3 d) { return hr_equirect_uv(hr_env_from_world(d, F.env_turn.x, F.env_turn.y, F.path_flags.x != 0)); }

// What a ray leaving the scene along `d` sees (path_escape): the image,
// bilinear, or the constant.
vec3 path_escape(vec3 d) {
  int w = F.path_counts.z, h = F.path_counts.w;
  if (w == 0) return F.env_constant.xyz;
  ivec4 q;
  vec2 t;
  hr_env_bilinear(env_uv(d), w, h, q, t);
  return (env_texel(q.x, q.y) * (1.0 - t.x) + env_texel(q.z, q.y) * t.x) * (1.0 - t.y) +
         (env_texel(q.x, q.w) * (1.0 - t.x) + env_texel(q.z, q.w) * t.x) * t.y;
}

// The density env_sample gives direction `d` (solid angle).
float env_pdf(vec3 d) {
  int w = F.path_counts.z, h = F.path_counts.w;
  if (w == 0) return 1.0 / (4.0 * kPi);
  ivec2 t = hr_env_texel_of(env_uv(d), w, h);
  return env_texels[t.y * w + t.x].radiance_share.w / hr_env_texel_solid_angle(t.y, w, h);
}

// A direction drawn in proportion to the light it brings: a texel by the
// alias table, a point in it uniform over its solid angle.
vec3 env_sample(float u_cell, vec2 u, out vec3 dir, out float pdf) {
  int w = F.path_counts.z, h = F.path_counts.w;
  if (w == 0) {
    dir = hr_uniform_sphere(u);
    pdf = 1.0 / (4.0 * kPi);
    return F.env_constant.xyz;
  }
  float rest;
  uint cell = hr_alias_cell(u_cell, uint(w * h), rest);
  if (rest >= env_texels[cell].keep_alias.x) cell = floatBitsToUint(env_texels[cell].keep_alias.y);
  int x = int(cell % uint(w)), y = int(cell / uint(w));
  dir = normalize(hr_env_to_world(hr_env_texel_direction(x, y, w, h, u), F.env_turn.x, F.env_turn.y, F.path_flags.x != 0));
  pdf = env_texels[cell].radiance_share.w / hr_env_texel_solid_angle(y, w, h);
  return path_escape(dir);
}

// ---- a path's vertex (path_tracer.cpp, Vertex and bsdf_of) ----

struct PathVertex {
  vec3 p, ng, above, below;
  vec3 t, b, n, wo;  // the shading frame (n toward the side the path came from), the way back in it
  HrBsdf bsdf;
};

// A vertex's BSDF from its material, colour `c` and glTF parameters `pbr`
// (metallic, roughness, transmission, F0), maps applied; `entering`: the
// ray met the outward side.
HrBsdf path_bsdf(GpuMaterial m, vec3 c, vec4 pbr, float cos_o, bool entering) {
  int model = int(m.emission_model.w);
  vec3 diffuse = c * m.colour_kd.w, mirror = vec3(m.ks_shine_t_ior.x), transmit = vec3(m.ks_shine_t_ior.z);
  if (model == HR_MODEL_GLTF)
    return F.path_flags.y != 0 ? hr_principled_bsdf(c, pbr.x, pbr.y, pbr.w, pbr.z, cos_o) : hr_gltf_bsdf(c, pbr.x, pbr.y, pbr.w, pbr.z, cos_o);
  if (model == HR_MODEL_TACHYON) return hr_plain_bsdf(diffuse, mirror, transmit, 1.0);  // its transparency goes straight on
  float ior = m.ks_shine_t_ior.w > 0.0 ? m.ks_shine_t_ior.w : 1.0;
  return hr_plain_bsdf(diffuse, mirror, transmit, entering ? 1.0 / ior : ior);
}

bool any_positive(vec3 c) { return c.x > 0.0 || c.y > 0.0 || c.z > 0.0; }

// ---- light sampling (path_tracer.cpp, light_sample and direct_light) ----

// One light sample's share at `v`: light along `dir` (unit) from `dist`
// away, `le` its radiance over its density `pdf` (0: a delta light),
// MIS-weighted against the BSDF's sampling; 0 when behind the surface
// (unless it transmits, rough) or blocked.
vec3 light_sample(PathVertex v, vec3 dir, float dist, vec3 le, float pdf, inout uint shadow_rays) {
  bool behind = dot(dir, v.ng) <= 0.0;
  if (behind && !(v.bsdf.transmit_alpha > 0.0)) return vec3(0.0);
  vec3 wi = hr_to_local(dir, v.t, v.b, v.n);
  if (behind != (wi.z < 0.0)) return vec3(0.0);
  vec3 f = hr_bsdf_eval(v.bsdf, v.wo, wi);
  if (!any_positive(f)) return vec3(0.0);
  ++shadow_rays;
  log_kind = 0x80u;
  Hit blocker;
  if (trace_ray(behind ? v.below : v.above, dir, 0.0, isinf(dist) ? kInf : dist - 2.0 * F.extent.w, true, blocker))
    return vec3(0.0);
  float w = pdf > 0.0 ? hr_power_heuristic(pdf, hr_bsdf_pdf(v.bsdf, v.wo, wi)) : 1.0;
  return f * le * w;
}

// Emission of triangle `k` at barycentrics `b`, its map read at a
// footprint `dist` away (RenderScene::emission).
vec3 emission_at(uint k, GpuMaterial m, vec2 b, float dist) {
  vec3 e = m.emission_model.xyz;
  if (kMeshTextures && m.maps.w >= 0) {
    int uv_at = floatBitsToInt(tris[k].v0.w);
    vec4 texel;
    if (uv_at >= 0 && texel_at(m.maps.w, uv_at, b.x, b.y, F.footprint.x + F.footprint.y * dist, texel)) e *= texel.rgb;
  }
  return e;
}

// Next-event estimation at `v`: every point, spot and directional light,
// every area light, one direction of the environment, one point of the
// emitters; each draws its pair of numbers whether or not it lights `v`.
vec3 direct_light(PathVertex v, inout HrSampler rng, inout uint shadow_rays) {
  float eps = F.extent.w;
  vec3 sum = vec3(0.0);
  for (int l = 0; l < F.counts.x; ++l) {
    GpuLight L = lights[l];
    if (L.flags.y != 0 && F.path_flags.z != 0) continue;
    vec2 u = hr_next2(rng);
    vec3 dir = -L.direction.xyz, from = L.position_kind.xyz;
    float dist = kInf, cos_l = 1.0;
    if (int(L.position_kind.w) == HR_LIGHT_DIRECTIONAL) {
      if (L.direction.w < 1.0) {  // the sun's cone, uniformly
        vec3 ct, cb;
        hr_frame(dir, ct, cb);
        dir = normalize(hr_to_world(hr_uniform_cone(u, L.direction.w), ct, cb, dir));
      }
    } else {
      if (L.direction.w > 0.0) {  // a disk of the light's radius facing the point
        vec3 facing = normalize(v.p - from);
        from = hr_disk_light_point(from, facing, L.direction.w, u);
        cos_l = abs(dot(facing, normalize(v.p - from)));
      }
      dir = from - v.p;
      dist = length(dir);
      if (!(dist > eps)) continue;
      dir /= dist;
    }
    float falloff = hr_light_falloff(falloff_params(L), dir, dist);
    if (falloff > 0.0) sum += light_sample(v, dir, dist, L.intensity_unit.xyz * (kPi * falloff * cos_l), 0.0, shadow_rays);
  }
  for (int a = 0; a < F.path_counts.x; ++a) {
    GpuAreaLight A = area_lights[a];
    vec2 u = hr_next2(rng);
    vec3 dir = hr_area_light_point(A.centre_ellipse.xyz, A.axis_u_area.xyz, A.axis_v.xyz, A.centre_ellipse.w != 0.0, u) - v.p;
    float dist2 = dot(dir, dir), dist = sqrt(dist2);
    if (!(dist > eps)) continue;
    dir /= dist;
    float cos_l = -dot(dir, A.normal.xyz);  // one-sided
    if (!(cos_l > 0.0)) continue;
    float pdf = dist2 / (cos_l * A.axis_u_area.w);
    sum += light_sample(v, dir, dist, A.radiance.xyz * (1.0 / pdf), pdf, shadow_rays);
  }
  if (F.path_flags.w != 0) {
    vec2 u_cell = hr_next2(rng), u_env = hr_next2(rng);
    vec3 dir;
    float pdf;
    vec3 le = env_sample(u_cell.x, u_env, dir, pdf);
    if (pdf > 0.0) sum += light_sample(v, dir, kInf, le * (1.0 / pdf), pdf, shadow_rays);
  }
  int n = F.path_counts.y;
  if (n > 0) {
    vec2 u_pick = hr_next2(rng), u_emit = hr_next2(rng);
    // The first emitter whose running sum passes u_pick (upper_bound).
    int lo = 0, hi = n;
    while (lo < hi) {
      int mid = (lo + hi) / 2;
      if (emitters[mid].cdf_tri_pick_area.x > u_pick.x) hi = mid;
      else lo = mid + 1;
    }
    vec4 e = emitters[min(lo, n - 1)].cdf_tri_pick_area;
    uint k = floatBitsToUint(e.y);
    GpuTriangle tri = tris[k];
    vec2 b = hr_uniform_triangle(u_emit);
    vec3 e1 = tri.v1.xyz - tri.v0.xyz, e2 = tri.v2.xyz - tri.v0.xyz;
    vec3 dir = tri.v0.xyz + e1 * b.x + e2 * b.y - v.p;
    float dist2 = dot(dir, dir), dist = sqrt(dist2);
    dir /= dist;
    float cos_l = abs(dot(normalize(cross(e1, e2)), dir));  // emission is two-sided
    if (dist > 2.0 * eps && cos_l > 0.0) {
      float pdf = e.z / e.w * dist2 / cos_l;
      GpuMaterial m = materials[object_material[floatBitsToInt(tri.ng.w)]];
      sum += light_sample(v, dir, dist, emission_at(k, m, b, dist) * (1.0 / pdf), pdf, shadow_rays);
    }
  }
  return sum;
}

// The area lights the ray o + t d meets before `t_max` from their lit
// side, each weighted against its light sampling unless the bounce was a
// delta lobe (area_lights_met).
vec3 area_lights_met(vec3 o, vec3 d, float t_max, bool specular, float last_pdf) {
  vec3 sum = vec3(0.0);
  for (int a = 0; a < F.path_counts.x; ++a) {
    GpuAreaLight A = area_lights[a];
    float t = hr_area_light_hit(o, d, min(t_max, 3.0e38), A.centre_ellipse.xyz, A.axis_u_area.xyz, A.axis_v.xyz, A.normal.xyz,
                                A.centre_ellipse.w != 0.0);
    float cos_l = -dot(d, A.normal.xyz);
    if (!(t > 0.0) || !(cos_l > 0.0)) continue;
    float pdf_light = hr_area_to_solid_angle(1.0 / A.axis_u_area.w, t * t, cos_l);
    sum += A.radiance.xyz * (specular ? 1.0 : hr_power_heuristic(last_pdf, pdf_light));
  }
  return sum;
}

// ---- the path (path_tracer.cpp, path_radiance) ----

// Radiance along the eye ray `e` of pixel (i, j); its first hit's AOVs
// written when `aovs_now` (sample 0). Counts rays into `rays` (eye,
// shadow, reflected, refracted).
vec3 path_radiance(int i, int j, EyeRay e, inout HrSampler rng, bool aovs_now, inout uvec4 rays, out bool first_hit) {
  float eps = F.extent.w;
  int max_depth = F.counts.z;
  vec3 radiance = vec3(0.0), throughput = vec3(1.0);
  vec3 ro = e.o, rd = e.d;
  float tmin = e.tmin, tmax = e.tmax;
  bool specular = true;  // the last bounce was a delta lobe (or there was none): no MIS on what it meets
  float last_pdf = 0.0;
  first_hit = false;
  // max_depth counts the eye ray as 1: a vertex past it only shows its
  // emission, which completes the MIS of the vertex before.
  for (int depth = 1; depth <= max_depth + 1; ++depth) {
    log_kind = uint(depth);
    Hit h;
    bool found = trace_ray(ro, rd, tmin, tmax, false, h);
    if (depth > 1) radiance += throughput * area_lights_met(ro, rd, found ? h.t : kInf, specular, last_pdf);
    if (!found) {
      float w = !specular && F.path_flags.w != 0 ? hr_power_heuristic(last_pdf, env_pdf(rd)) : 1.0;
      radiance += throughput * path_escape(rd) * w;
      break;
    }
    bool primary = depth == 1;
    float optic = h.t + (primary ? e.optic0 : 0.0);  // along the eye's way, as the CPU measures it
    Surface s = surface_of(ro, rd, h);
    GpuMaterial m = materials[s.material];
    MappedMaterial mm = mapped_material(m, h, optic, s);
    if (primary) {
      first_hit = true;
      if (aovs_now) write_hit_aovs(i, j, e.line_dir, s, m, mm, e.t_sign * h.t);
    }
    vec3 colour = mm.colour;
    if (kTachyon && int(m.emission_model.w) == HR_MODEL_TACHYON) {
      colour = tachyon_colour(m, h, s.p, colour, optic);
      if (m.tachyon.w != 0.0) {  // a light's sphere: its colour, unshaded
        radiance += throughput * colour;
        break;
      }
    }
    if (any_positive(m.emission_model.xyz)) {
      float w = 1.0;
      if (!specular && F.path_counts.y > 0 && (h.ref >> HR_PRIM_SHIFT) == HR_PRIM_TRIANGLE) {
        // The emitters draw a point with area density luminance / their power.
        float pdf_area = hr_luminance(m.emission_model.xyz) * F.env_constant.w;
        w = hr_power_heuristic(last_pdf, hr_area_to_solid_angle(pdf_area, h.t * h.t, abs(dot(s.ng, rd))));
      }
      radiance += throughput * mm.emission * w;
    }
    if (depth > max_depth) break;

    PathVertex v;
    v.p = s.p;
    vec3 view = -rd;
    bool front = dot(s.ng, view) >= 0.0;
    v.ng = front ? s.ng : -s.ng;
    vec3 ns = front ? s.ns : -s.ns;
    if (dot(ns, view) <= 0.0) ns = v.ng;  // a shading normal turned away from the viewer by interpolation
    v.n = ns;
    hr_frame(v.n, v.t, v.b);
    v.wo = hr_to_local(view, v.t, v.b, v.n);
    v.bsdf = path_bsdf(m, colour, mm.pbr, v.wo.z, front);
    v.above = s.p + v.ng * eps;
    v.below = s.p - v.ng * eps;
    if (any_positive(v.bsdf.diffuse) || v.bsdf.alpha > 0.0) radiance += throughput * direct_light(v, rng, rays.y);

    // The next direction, from the BSDF.
    vec2 u_lobe = hr_next2(rng), u_dir = hr_next2(rng);
    vec3 wi, weight;
    float pdf;
    bool delta, through;
    if (!hr_bsdf_sample(v.bsdf, v.wo, u_lobe.x, u_dir, wi, weight, pdf, delta, through)) break;
    vec3 dir = normalize(hr_to_world(wi, v.t, v.b, v.n));
    if (!through && dot(dir, v.ng) <= 0.0) break;  // below the geometric surface: it would leave from inside
    if (through && !delta && dot(dir, v.ng) >= 0.0) break;  // rough transmission back above it: the same, mirrored
    throughput *= weight;
    specular = delta;
    last_pdf = pdf;
    if (through) ++rays.w;
    else ++rays.z;
    ro = through ? v.below : v.above, rd = dir, tmin = 0.0, tmax = kInf;
    // Russian roulette (pbrt-v4's): below 1, go on with that probability.
    float keep = max(throughput.x, max(throughput.y, throughput.z));
    if (depth >= kRouletteDepth && keep < 1.0) {
      if (!(u_lobe.y < keep)) break;
      throughput *= 1.0 / keep;
    }
  }
  return radiance;
}

// One pass: sample band.sample_index of pixel (i, j), placed by the
// pixel's sampler (path_pixel_sum: sample 0 at the centre), added to the
// colour the passes before left; the last pass leaves the mean. A trace
// that goes on from an earlier one's mean (band.first_sample > 0, live's
// refinement) draws the samples after that one's.
void path_main() {
  int i = int(gl_GlobalInvocationID.x), j = band.row0 + int(gl_GlobalInvocationID.y);
  if (i >= F.size.x || int(gl_GlobalInvocationID.y) >= band.rows) return;
  log_pixel = ivec2(i, j);
  int spp = F.mode.w, k = band.sample_index;
  bool aovs_now = k == 0 && F.counts.y != 0;
  uint seed = hr_pixel_seed(uint(F.tile.x + i), uint(F.tile.y + j), floatBitsToUint(F.env_turn.z));
  HrSampler rng = hr_sampler(seed, uint(k));
  vec2 uv = hr_pixel_position(rng, hr_pixel_shift(seed));
  EyeRay e = eye_ray(i, j, uv);
  uvec4 rays = uvec4(0u);
  vec3 c;
  bool first_hit = false;
  if (e.traced) {
    ++rays.x;
    c = path_radiance(i, j, e, rng, aovs_now, rays, first_hit);
  } else {
    if (e.empty_aimed) ++rays.x;
    c = path_escape(e.d);
  }
  if (aovs_now && !first_hit) write_miss_aovs(i, j);
  // The sum so far: none before sample 0; the mean of first_sample
  // samples a trace before scaled back to their sum at its first pass.
  float before = k == 0 ? 0.0 : k == band.first_sample ? float(k) : 1.0;
  float last = k == spp - 1 ? 1.0 / float(spp) : 1.0;
  if (kPanel && F.panel_kind.x == 3) {  // one channel of the pixel (display_renderer.cpp, pack_subpixels)
    int q = i % 3, ch = F.panel_kind.y != 0 ? q : 2 - q;
    uint at = out_pixel(i / 3, j) * 3u + uint(ch);
    colour_sum[at] = ((before == 0.0 ? 0.0 : colour_sum[at] * before) + c[ch]) * last;
  } else {
    uint at = out_pixel(i, j) * 3u;
    for (uint ch = 0u; ch < 3u; ++ch) colour_sum[at + ch] = ((before == 0.0 ? 0.0 : colour_sum[at + ch] * before) + c[ch]) * last;
  }
  add_counts(rays);
}
