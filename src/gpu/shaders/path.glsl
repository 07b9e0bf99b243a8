// holoray/gpu: the path integrator on the device (trace.comp's kPath): the
// shared integrator (render/path_integrator.h, the text the CPU compiles)
// over the GPU path's scene arrays, through the hooks below. One sample of each
// pixel a pass (band.sample_index), added to the passes before: an
// invocation's loops stay inside lavapipe's 65535 iterations whatever the
// samples per pixel (shared/docs/gpu-notes.md). Included by trace.comp,
// whose traversal, camera lines and surfaces it calls.
#include "shading/sampler.h"
#include "shading/bsdf.h"
#include "shading/lights.h"
#include "shading/environment.h"
#include "render/path_records.h"

layout(std430, binding = 22) readonly buffer AreaLightBlock { GpuAreaLight area_lights[]; };
layout(std430, binding = 23) readonly buffer EnvironmentBlock { GpuEnvTexel env_texels[]; };
layout(std430, binding = 24) readonly buffer EmitterBlock { GpuEmitter emitters[]; };

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

// ---- the device's hooks of the shared integrator (render/path_integrator.h) ----

// What the integrator carries for the device: the pixel, whether its AOVs
// are written now (sample 0), the eye ray's optical offset, its line and
// depth sign (for the AOVs), whether the eye ray met anything, and the ray
// counts (eye, shadow, reflected, refracted).
struct HrPathDevice {
  ivec2 pixel;
  bool aovs_now;
  float optic0;
  vec3 line_dir;
  float t_sign;
  bool first_hit;
  uvec4 rays;
  // The wavefront's (wavefront.glsl): the path's place in its band, its
  // shadow rays written at this vertex.
  uint wave_path;
  int wave_shadows;
};

// What a ray met: the hit, its surface after normal mapping, the
// material's maps, the colour Tachyon's texture gives, a Tachyon light's
// sphere.
struct HrPathHit {
  Hit hit;
  Surface s;
  MappedMaterial mm;
  vec3 colour;
  uint material;
  bool sphere;
};

bool wave_hit(uint p, out Hit h);
// The wavefront's shade stage (wavefront.glsl), where a hook does not trace.
bool wave_shading() { return kWaveStage == HR_WAVE_SHADING; }
bool hr_path_trace(inout HrPathDevice d, vec3 o, vec3 dir, float tmin, float tmax, int depth, out HrPathHit h) {
  log_kind = uint(depth);
  // The wavefront's shading stage reads what its traversal stage found.
  bool found = wave_shading() ? wave_hit(d.wave_path, h.hit) : trace_ray(o, dir, tmin, tmax, false, h.hit);
  if (!found) return false;
  bool primary = depth == 1;
  float optic = h.hit.t + (primary ? d.optic0 : 0.0);  // along the eye's way, as the CPU measures it
  h.s = surface_of(o, dir, h.hit);
  h.material = h.s.material;
  GpuMaterial m = materials[h.material];
  h.mm = mapped_material(m, h.hit, optic, h.s);
  if (primary) {
    d.first_hit = true;
    if (d.aovs_now) write_hit_aovs(d.pixel.x, d.pixel.y, d.line_dir, h.s, m, h.mm, d.t_sign * h.hit.t);
  }
  h.colour = h.mm.colour;
  h.sphere = false;
  if (kTachyon && int(m.emission_model.w) == HR_MODEL_TACHYON) {
    h.colour = tachyon_colour(m, h.hit, h.s.p, h.colour, optic);
    h.sphere = m.tachyon.w != 0.0;
  }
  return true;
}

float hr_path_hit_t(HrPathHit h) { return h.hit.t; }
vec3 hr_path_hit_p(HrPathHit h) { return h.s.p; }
vec3 hr_path_hit_ng(HrPathHit h) { return h.s.ng; }
vec3 hr_path_hit_ns(HrPathHit h) { return h.s.ns; }

vec3 wave_shadow(inout HrPathDevice d, vec3 from, vec3 dir, float tmax, vec3 term);
vec3 hr_path_unblocked(inout HrPathDevice d, vec3 from, vec3 dir, float tmax, vec3 term) {
  if (wave_shading()) return wave_shadow(d, from, dir, tmax, term);  // traced by the next stage
  log_kind = 0x80u;
  Hit blocker;
  return trace_ray(from, dir, 0.0, tmax, true, blocker) ? vec3(0.0) : term;
}

void hr_path_count(inout HrPathDevice d, int kind) {
  if (kind == HR_PATH_RAY_SHADOW) ++d.rays.y;
  else if (kind == HR_PATH_RAY_REFRACTED) ++d.rays.w;
  else ++d.rays.z;
}

float hr_path_epsilon(inout HrPathDevice d) { return F.clip.z; }
int hr_path_max_depth(inout HrPathDevice d) { return F.counts.z; }

bool hr_path_light_sphere(inout HrPathDevice d, HrPathHit h, out vec3 colour) {
  colour = h.colour;
  return h.sphere;
}

vec3 hr_path_emission(inout HrPathDevice d, HrPathHit h, vec3 dir, bool specular, float last_pdf) {
  GpuMaterial m = materials[h.material];
  if (!hr_path_positive(m.emission_model.xyz)) return vec3(0.0);
  float w = 1.0;
  if (!specular && F.path_counts.y > 0 && (h.hit.ref >> HR_PRIM_SHIFT) == HR_PRIM_TRIANGLE) {
    // The emitters draw a point with area density luminance / their power.
    float pdf_area = hr_luminance(m.emission_model.xyz) * F.env_constant.w;
    w = hr_power_heuristic(last_pdf, hr_area_to_solid_angle(pdf_area, h.hit.t * h.hit.t, abs(dot(h.s.ng, dir))));
  }
  return h.mm.emission * w;
}

// The BSDF from the material, its colour and its glTF parameters (metallic,
// roughness, transmission, F0), maps applied: render/path_tracer.cpp's.
HrBsdf hr_path_bsdf(inout HrPathDevice d, HrPathHit h, float cos_o, bool entering) {
  GpuMaterial m = materials[h.material];
  vec4 pbr = h.mm.pbr;
  int model = int(m.emission_model.w);
  vec3 diffuse = h.colour * m.colour_kd.w, mirror = vec3(m.ks_shine_t_ior.x), transmit = vec3(m.ks_shine_t_ior.z);
  if (model == HR_MODEL_GLTF)
    return F.path_flags.y != 0 ? hr_principled_bsdf(h.colour, pbr.x, pbr.y, pbr.w, pbr.z, cos_o)
                               : hr_gltf_bsdf(h.colour, pbr.x, pbr.y, pbr.w, pbr.z, cos_o);
  if (model == HR_MODEL_TACHYON) return hr_plain_bsdf(diffuse, mirror, transmit, 1.0);  // its transparency goes straight on
  float ior = m.ks_shine_t_ior.w > 0.0 ? m.ks_shine_t_ior.w : 1.0;
  return hr_plain_bsdf(diffuse, mirror, transmit, entering ? 1.0 / ior : ior);
}

int hr_path_light_count(inout HrPathDevice d) { return F.counts.x; }

HrPathLight hr_path_light(inout HrPathDevice d, int l) {
  GpuLight L = lights[l];
  HrPathLight r;
  r.kind = int(L.position_kind.w);
  r.position = L.position_kind.xyz;
  r.direction = L.direction.xyz;
  r.intensity = L.intensity_unit.xyz;
  bool directional = r.kind == HR_LIGHT_KIND_DIRECTIONAL;
  r.cos_half_angle = directional ? L.direction.w : 1.0;
  r.radius = directional ? 0.0 : L.direction.w;
  r.falloff = falloff_params(L);
  r.skip = L.flags.y != 0 && F.path_flags.z != 0;
  return r;
}

int hr_path_area_light_count(inout HrPathDevice d) { return F.path_counts.x; }

HrPathAreaLight hr_path_area_light(inout HrPathDevice d, int a) {
  GpuAreaLight A = area_lights[a];
  HrPathAreaLight r;
  r.centre = A.centre_ellipse.xyz;
  r.axis_u = A.axis_u_area.xyz;
  r.axis_v = A.axis_v.xyz;
  r.normal = A.normal.xyz;
  r.radiance = A.radiance.xyz;
  r.area = A.axis_u_area.w;
  r.ellipse = A.centre_ellipse.w != 0.0;
  return r;
}

vec3 hr_path_escape(inout HrPathDevice d, vec3 dir) { return path_escape(dir); }
bool hr_path_env_lights(inout HrPathDevice d) { return F.path_flags.w != 0; }
float hr_path_env_pdf(inout HrPathDevice d, vec3 dir) { return env_pdf(dir); }

vec3 hr_path_env_sample(inout HrPathDevice d, float u_cell, vec2 u, out vec3 dir, out float pdf) {
  return env_sample(u_cell, u, dir, pdf);
}

bool hr_path_has_emitters(inout HrPathDevice d) { return F.path_counts.y > 0; }

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

// An emitter by its power (the first whose running sum passes u_pick:
// upper_bound), a point uniform on it.
bool hr_path_emitter_sample(inout HrPathDevice d, vec2 u_pick, vec2 u_emit, vec3 p, out vec3 dir, out float dist,
                            out vec3 le, out float pdf) {
  int n = F.path_counts.y;
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
  dir = tri.v0.xyz + e1 * b.x + e2 * b.y - p;
  float dist2 = dot(dir, dir);
  dist = sqrt(dist2);
  dir /= dist;
  float cos_l = abs(dot(normalize(cross(e1, e2)), dir));  // emission is two-sided
  if (!(dist > 2.0 * F.clip.z && cos_l > 0.0)) return false;
  pdf = e.z / e.w * dist2 / cos_l;
  GpuMaterial m = materials[object_material[floatBitsToInt(tri.ng.w)]];
  le = emission_at(k, m, b, dist) * (1.0 / pdf);
  return true;
}

#include "render/path_integrator.h"

// Sample band.sample_index of pixel (i, j), `c`, added to the colour the
// passes before left; the last pass leaves the mean.
void add_sample(int i, int j, vec3 c) {
  int spp = F.mode.w, k = band.sample_index;
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
  HrPathDevice d;
  d.pixel = ivec2(i, j);
  d.aovs_now = aovs_now;
  d.optic0 = e.optic0;
  d.line_dir = e.line_dir;
  d.t_sign = e.t_sign;
  d.first_hit = false;
  d.rays = uvec4(0u);
  d.wave_path = 0u;
  d.wave_shadows = 0;
  vec3 c;
  if (e.traced) {
    ++d.rays.x;
    c = hr_path_radiance(d, e.o, e.d, e.tmin, e.tmax, rng);
  } else {
    if (e.empty_aimed) ++d.rays.x;
    c = path_escape(e.d);
  }
  if (aovs_now && !d.first_hit) write_miss_aovs(i, j);
  add_sample(i, j, c);
  add_counts(d.rays);
}

#include "wavefront.glsl"
