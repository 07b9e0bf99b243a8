// holoray/gpu: one invocation per EIA pixel of one band of rows. The
// pixel's line from the lens array's parameters (camera-model.md, as
// camera/lens_array.cpp), its primary ray clipped to the scene's box
// (render/renderer.cpp, primary_over), a 4-wide BVH traversal of our own,
// and NFF's Whitted shading (nff-notes §4, §10; render/models/nff_model.hpp)
// with shadows, mirror and refracted rays to the frame's depth, walked
// depth first on a short stack (no recursion in GLSL). Float throughout.
// One ray tree per invocation: Mesa's lavapipe cuts a shader's loops after
// 65535 iterations in all (gpu-notes.md), so nothing loops over pixels.
#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_ballot : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_KHR_shader_subgroup_basic : require
#include "layout.h"
// What both devices compute, one text (src/shading/): Whitted's falloff and
// glTF terms here; the path integrator's sampling in path.glsl.
#include "shading/lights.h"
#include "shading/gltf_whitted.h"
#include "camera/pixel_lines.h"

// Workgroup size: 32x2 by default (on an H200, 1.12x the frames of 8x8 on
// balls_s4 and gears_s4), a specialization constant so that it can be tuned
// per device without another SPIR-V (gpu_renderer.cpp). No subgroup size is
// assumed (NVIDIA 32, lavapipe 8).
layout(local_size_x = 32, local_size_y = 2) in;
layout(local_size_x_id = 0, local_size_y_id = 1) in;
// Whether a shadow ray visits a node's children nearest first: any hit
// ends it, and not sorting measured 12 % faster per frame (balls_s4 and
// gears_s4 at 3840x2160 on an H200).
layout(constant_id = 2) const bool kSortShadowChildren = false;
// A pipeline of its own for the panels (display files, Looking Glass native
// images), whose samples are subpixels: their camera code is left out of
// the kernel the other cameras run, which keeps its registers.
layout(constant_id = 3) const bool kPanel = false;
// What the scene holds, likewise one pipeline each (made when a scene with
// it is loaded): Tachyon's shading, glTF's, a mesh's image textures, alpha
// masks. A scene without them runs a kernel without their code, so NFF's
// scenes keep the kernel measured before these were added.
layout(constant_id = 4) const bool kTachyon = false;
layout(constant_id = 5) const bool kGltf = false;
layout(constant_id = 6) const bool kMeshTextures = false;
layout(constant_id = 7) const bool kAlphaMasks = false;
// Count BVH nodes visited and primitives tested (GpuRenderer::count_work):
// the two counters, live across every traversal, took 24 registers a
// thread (96 against 72) and 1.07x the frame's time on an H100.
layout(constant_id = 8) const bool kCountWork = false;
// Log every traversal (HOLORAY_GPU_RAY_LOG, gpu_renderer.cpp): its
// invocation's pixel, the ray's kind and depth, and the nodes and
// primitives it visited, for bench/ray_schedule_model.py to model how
// other schedules would fill a subgroup's lanes. Set with kCountWork.
layout(constant_id = 9) const bool kRayLog = false;
// The shadow queue: the pixel kernel (kShadowQueue) queues the shadow rays
// of NFF's, Blinn-Phong's and glTF's shading instead of tracing them, and
// a pass of its own (kShadowPass, shadow_pass) traces the queue with lanes
// that each take the queue's next ray when their own is done (after Aila
// and Laine 2009), and a resolve adds each unblocked ray's term to its
// pixel. Shadow rays end at their first blocker, anywhere along their
// walk, so lanes in step ray by ray wait on their subgroup's longest. For
// measuring (HOLORAY_GPU_SHADOW_QUEUE): 1.25x on balls_s4, 0.53x on
// tree_s11 on an H200 (design/gpu.md, "The shadow queue").
layout(constant_id = 10) const bool kShadowQueue = false;
// kShadowPass: 0 the pixel kernel, 1 the shadow pass, 2 the resolve that
// adds each pixel's unblocked terms to its colour, in the order queued, so
// that a frame's colours are the same from run to run.
layout(constant_id = 11) const int kShadowPass = 0;
// 8-wide nodes (HR_FEATURE_WIDE_BVH, HOLORAY_GPU_BVH_WIDTH=8, for
// measuring): each two GpuNode records, children 0 to 3 then 4 to 7; 1.3
// to 1.5x fewer nodes a ray on the SPD scenes, 1.3 to 1.55x the boxes
// tested (design/gpu.md, "8-wide nodes").
layout(constant_id = 12) const bool kWideBvh = false;
// The path integrator (HR_FEATURE_PATH, path.glsl): one sample of each
// pixel a pass, added to what the passes before wrote. The modules that
// shade (the megakernel, the shade stage) are built once per integrator
// (HR_INTEGRATOR_PATH or _WHITTED, CMakeLists.txt), so that the other's code
// is gone before the driver reads the module: lavapipe's compile time grows
// with the module (a shade pipeline of both took 3.8 s, design/gpu.md).
#if defined(HR_INTEGRATOR_PATH)
const bool kPath = true;
#elif defined(HR_INTEGRATOR_WHITTED)
const bool kPath = false;
#else
layout(constant_id = 13) const bool kPath = false;
#endif
// The path integrator as a wavefront (HOLORAY_GPU_WAVEFRONT, wavefront.glsl):
// HR_WAVE_* the stage this pipeline runs, HR_WAVE_OFF the megakernel.
layout(constant_id = 14) const int kWaveStage = HR_WAVE_OFF;
// The most rays a lane of the wavefront's traversals takes from its queue
// (the host's choice by device; HOLORAY_GPU_RAYS_PER_LANE for measuring):
// 1, one ray an invocation in queue order, as a plain wavefront; more,
// lanes that finish fetch again (Aila and Laine 2009).
layout(constant_id = 15) const int kRaysPerLane = HR_SHADOW_RAYS_PER_LANE;
const int kNodeRecords = kWideBvh ? 2 : 1;
const int kNodeWidth = kWideBvh ? 8 : 4;

// One frame's constants per camera dispatched: a quilt's views are several.
layout(std430, binding = 0) readonly buffer FrameBlock { GpuFrame frames[]; };
#define F frames[band.frame]
layout(std430, binding = 1) readonly buffer NodeBlock { GpuNode nodes[]; };
layout(std430, binding = 2) readonly buffer RefBlock { uint refs[]; };
layout(std430, binding = 3) readonly buffer TriBlock { GpuTriangle tris[]; };
layout(std430, binding = 4) readonly buffer PatchBlock { GpuPatch patches[]; };
layout(std430, binding = 5) readonly buffer SphereBlock { GpuSphere spheres[]; };
layout(std430, binding = 6) readonly buffer ConeBlock { GpuCone cones[]; };
layout(std430, binding = 7) readonly buffer ObjectBlock { uint object_material[]; };
layout(std430, binding = 8) readonly buffer MaterialBlock { GpuMaterial materials[]; };
layout(std430, binding = 9) readonly buffer LightBlock { GpuLight lights[]; };
// Colour (3 floats a pixel) and the AOVs (albedo 3, depth 1, normal 3, id 1),
// for the whole image; each dispatch writes its band's rows.
layout(std430, binding = 10) writeonly buffer ColourBlock { float colour_out[]; };
// The same colours, read and added to by the shadow queue's resolve alone
// (so that the pixel kernel keeps its write-only colour buffer).
layout(std430, binding = 10) buffer ColourSumBlock { float colour_sum[]; };
layout(std430, binding = 11) writeonly buffer AovBlock { float aov_out[]; };
// Statistics, summed with one atomic per subgroup: nodes visited,
// primitives tested, then rays by kind: eye, shadow, reflected, refracted.
// Counters: HR_COUNT_SLOTS pairs per band (32 bits each: a band is short enough).
layout(std430, binding = 12) buffer CountBlock { uvec4 band_counts[]; };
layout(std430, binding = 13) readonly buffer TextureBlock { GpuTexture textures[]; };
layout(std430, binding = 14) readonly buffer LevelBlock { GpuLevel levels[]; };
layout(std430, binding = 15) readonly buffer TexelBlock { uint texels[]; };
layout(std430, binding = 16) readonly buffer ColourPatchBlock { GpuPatch vertex_colours[]; };
layout(std430, binding = 17) readonly buffer UvBlock { GpuUv uvs[]; };
// The ray log (kRayLog): records taken, then as many records as it holds (frame
// pixel i, j; kind: depth | 0x80 for a shadow ray, | frame << 8; nodes |
// primitives << 16); records past its capacity are counted, not kept.
layout(std430, binding = 18) buffer RayLogBlock { uvec4 ray_log_head; uvec4 ray_log[]; };
// The shadow queue (kShadowQueue): x of the head the rays queued (those
// past its capacity were traced where they were made), y the rays the
// shadow pass has fetched, z its capacity (written by the host: an H200's
// length() of a runtime array past 2^31 bytes came out short). A pixel's
// queued rays lie in runs, one for each light chunk of a hit, linked from
// its last (`shadow_last`, by colour buffer pixel, ~0 for none) back
// through the link in each run's first term (`shadow_terms`).
layout(std430, binding = 19) buffer ShadowQueueBlock { uvec4 shadow_head; GpuShadowRay shadow_queue[]; };
layout(std430, binding = 20) buffer ShadowLastBlock { uint shadow_last[]; };
layout(std430, binding = 21) buffer ShadowTermBlock { vec4 shadow_terms[]; };
// The path integrator's wavefront (kWaveStage, wavefront.glsl), for one band
// of at most band.capacity paths (p: a pixel's place in its band): each
// path's state; its ray's nearest hit (two records: t, the primitive, u, v;
// the geometric normal); the queues' heads (x the entries queued, y those
// fetched: a queue of the paths that go on to each vertex, then one of the
// shadow rays made at each) and the path queues, two of band.capacity
// entries taken in turn; each path's shadow rays (at p * the most a vertex
// makes, in the order made) and the queue of those made at a vertex.
layout(std430, binding = 25) buffer WavePathBlock { GpuWavePath wave_paths[]; };
layout(std430, binding = 26) buffer WaveHitBlock { vec4 wave_hits[]; };
// wave_args: the workgroups of the extend, shade and shadow dispatches
// (x, y, 1: VkDispatchIndirectCommand) of the vertex at hand, from its
// queues' counts (HR_WAVE_ARGS).
layout(std430, binding = 27) buffer WaveQueueBlock { uvec4 wave_heads[HR_WAVE_HEADS]; uvec4 wave_args[3]; uint wave_queue[]; };
layout(std430, binding = 28) buffer WaveShadowBlock { GpuWaveShadow wave_shadows[]; };
layout(std430, binding = 29) buffer WaveShadowQueueBlock { uint wave_shadow_queue[]; };
// Whitted's wavefront: each pixel's rays still to trace (whitted_wavefront.glsl).
layout(std430, binding = 30) buffer WaveStackBlock { vec4 wave_stack[]; };

// `sample_index`: the path integrator's pass (kPath); `first_sample`: its
// first this trace (> 0: the colours hold the mean of that many already).
// The wavefront's stages also take the vertex they work on (`depth`) and
// the paths a band holds at most (`capacity`).
layout(push_constant) uniform Band {
  int row0;
  int rows;
  int index;
  int frame;
  int sample_index;
  int first_sample;
  int depth;
  int capacity;
} band;

const float kInf = 1.0 / 0.0;

struct Hit {
  float t;
  uint ref;  // HR_PRIM_* << HR_PRIM_SHIFT | index
  float u, v;
  vec3 ng;   // geometric normal (outward or winding; not yet unit for triangles)
};

uint visited = 0u, tested = 0u;
// Node steps a lane of a fetching traversal took, busy or not (their
// subgroup's loop's turns: kCountWork): lanes' use is `visited` over them.
uint lane_steps = 0u;
// What the ray log says of the ray traced now (kRayLog).
ivec2 log_pixel = ivec2(0);
uint log_kind = 0u;

// ---- primitives (accel/shapes.cpp's tests, in float) ----

// ---- a mesh's image textures (render/textures.cpp, MipMap::sample_uv;
// render/hit_surface.cpp, texel_at) ----

// Texel index i of an axis of n under a wrap mode (glTF 2.0 §5.26).
int wrap_index(int i, int n, int mode) {
  if (i >= 0 && i < n) return i;
  if (mode == HR_WRAP_CLAMP) return clamp(i, 0, n - 1);
  if (mode == HR_WRAP_MIRROR) {
    int m = i - 2 * n * int(floor(float(i) / float(2 * n)));
    return m < n ? m : 2 * n - 1 - m;
  }
  return i - n * int(floor(float(i) / float(n)));
}

// u or v kept near the unit square (the period under repeat and mirror is 2).
float fold(float x, int mode) { return mode == HR_WRAP_CLAMP ? clamp(x, -1.0, 2.0) : x - 2.0 * floor(x / 2.0); }

float srgb_decode(float c) { return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4); }

// Texel (x, y) of a level, wrapped: RGB decoded (sRGB or code / 255), alpha.
vec4 uv_texel(ivec4 L, int x, int y, ivec4 wrap_filter, bool srgb) {
  uint t = texels[L.w + wrap_index(y, L.y, wrap_filter.y) * L.x + wrap_index(x, L.x, wrap_filter.x)];
  vec4 c = vec4(float(t & 0xffu), float((t >> 8) & 0xffu), float((t >> 16) & 0xffu), float(t >> 24)) / 255.0;
  if (srgb) c.rgb = vec3(srgb_decode(c.r), srgb_decode(c.g), srgb_decode(c.b));
  return c;
}

// One level at folded (u, v): bilinear between texel centres, or the nearest texel.
vec4 uv_level(ivec4 L, float u, float v, ivec4 wrap_filter, bool srgb, bool nearest) {
  float x = u * float(L.x), y = v * float(L.y);
  if (nearest) return uv_texel(L, int(floor(x)), int(floor(y)), wrap_filter, srgb);
  int x0 = int(floor(x - 0.5)), y0 = int(floor(y - 0.5));
  float fx = x - 0.5 - floor(x - 0.5), fy = y - 0.5 - floor(y - 0.5);
  return mix(mix(uv_texel(L, x0, y0, wrap_filter, srgb), uv_texel(L, x0 + 1, y0, wrap_filter, srgb), fx),
             mix(uv_texel(L, x0, y0 + 1, wrap_filter, srgb), uv_texel(L, x0 + 1, y0 + 1, wrap_filter, srgb), fx), fy);
}

// The image at (u, v), linear between the two levels around `level` (0 the finest).
vec4 sample_uv(GpuTexture t, float u, float v, float level, bool srgb, bool nearest) {
  if (isnan(u) || isinf(u) || isnan(v) || isinf(v)) return vec4(0.0);
  u = fold(u, t.wrap_filter.x), v = fold(v, t.wrap_filter.y);
  int first = t.kind_level_count.y;
  float top = float(t.kind_level_count.z - 1);
  float lv = isnan(level) || isinf(level) ? 0.0 : clamp(level, 0.0, top);
  if (lv <= 0.0) return uv_level(levels[first].size_offset, u, v, t.wrap_filter, srgb, nearest);
  int l0 = int(floor(lv));
  float f = lv - float(l0);
  vec4 a = uv_level(levels[first + l0].size_offset, u, v, t.wrap_filter, srgb, false);
  if (float(l0) >= top || f == 0.0) return a;
  return mix(a, uv_level(levels[first + l0 + 1].size_offset, u, v, t.wrap_filter, srgb, false), f);
}

// Texture k's (u, v) at barycentrics (bu, bv) of triangle coordinates `uv`
// (texture_uv: interpolated, then the texture transform).
vec2 texture_uv(GpuTexture t, GpuUv uv, float bu, float bv) {
  float w0 = 1.0 - bu - bv;
  float iu = uv.uv01.x * w0 + uv.uv01.z * bu + uv.uv2_scale.x * bv;
  float iv = uv.uv01.y * w0 + uv.uv01.w * bu + uv.uv2_scale.y * bv;
  return vec2(t.uv_m0.x * iu + t.uv_m0.y * iv + t.uv_m0.z, t.uv_m0.w * iu + t.uv_m1.x * iv + t.uv_m1.y);
}

// Texture k at a triangle's hit seen `width` wide (world units): its texel,
// RGB linear; false when k is no image or the triangle has no coordinates.
bool texel_at(int k, int uv_at, float bu, float bv, float width, out vec4 texel) {
  texel = vec4(1.0);
  if (k < 0 || uv_at < 0) return false;
  GpuTexture t = textures[k];
  if (t.kind_level_count.x != HR_TEX_UV_IMAGE || t.kind_level_count.y < 0) return false;
  GpuUv uv = uvs[uv_at];
  vec2 tuv = texture_uv(t, uv, bu, bv);
  // The footprint in level-0 texels: world width x texture units per world
  // unit x the transform's scale x texels per unit.
  float texels_across = width * uv.uv2_scale.z * t.uv_m1.z * sqrt(float(t.alpha_size.y) * float(t.alpha_size.z));
  float level = texels_across > 1.0 ? log2(texels_across) : 0.0;
  texel = sample_uv(t, tuv.x, tuv.y, level, t.wrap_filter.w != 0, t.wrap_filter.z != 0);
  return true;
}

// Whether an alpha-masked material cuts triangle k away at (bu, bv)
// (RenderScene::AlphaCutout: MTL's map_d, else the colour texture's alpha,
// read at level 0, times the material's alpha, against its cutoff).
bool cut_away(GpuTriangle tri, float bu, float bv) {
  GpuMaterial m = materials[object_material[floatBitsToInt(tri.ng.w)]];
  if (m.maps2.z == 0) return false;
  float alpha = m.alpha.x;
  int k = m.maps2.y >= 0 ? m.maps2.y : m.maps.x, uv_at = floatBitsToInt(tri.v0.w);
  if (k >= 0 && uv_at >= 0 && textures[k].kind_level_count.x == HR_TEX_UV_IMAGE && textures[k].kind_level_count.y >= 0) {
    GpuTexture t = textures[k];
    vec2 tuv = texture_uv(t, uvs[uv_at], bu, bv);
    alpha *= m.maps2.y < 0 || t.alpha_size.x != 0 ? sample_uv(t, tuv.x, tuv.y, 0.0, false, false).a
                                                  : sample_uv(t, tuv.x, tuv.y, 0.0, false, t.wrap_filter.z != 0).r;
  }
  return alpha < m.alpha.y;
}

// A ray as the watertight triangle test takes it (Woop, Benthin and Wald
// 2013, "Watertight Ray/Triangle Intersection", JCGT 2(1)): its axes
// permuted so that its largest direction component is z (k), and the shear
// that turns it into +z (s), once per ray. The permutation is cyclic: the
// paper's swap of x and y for a negative z, which keeps the winding, would
// only negate all three edge functions, and the test is blind to their
// common sign.
struct ShearedRay {
  ivec3 k;
  vec3 s;
};

ShearedRay sheared(vec3 d) {
  vec3 a = abs(d);
  int kz = a.x > a.y ? (a.x > a.z ? 0 : 2) : (a.y > a.z ? 1 : 2);
  int kx = kz == 2 ? 0 : kz + 1, ky = kx == 2 ? 0 : kx + 1;
  ShearedRay r;
  r.k = ivec3(kx, ky, kz);
  r.s = vec3(d[kx] / d[kz], d[ky] / d[kz], 1.0 / d[kz]);
  return r;
}

// Where the ray (origin o, sheared r) meets triangle k, in (tmin, h.t).
// Each vertex is moved to the ray's frame by the same float operations
// whichever triangle holds it, and the edge functions are `precise` (no
// fused multiply-add): two triangles sharing an edge compute it as exact
// negatives, so a ray on the edge meets one of them or both, never neither.
// The vertices' coordinates are read from the buffer by the ray's axis
// indices, each its own load: on an H100 1.20x faster (teapot_s6) than
// picking them out of the loaded vectors, whose dynamic indexing became
// selects (bench/gpu_results.md).
bool hit_triangle(uint k, vec3 o, ShearedRay r, float tmin, inout Hit h) {
  vec3 op = vec3(o[r.k.x], o[r.k.y], o[r.k.z]);
  float az = tris[k].v0[r.k.z] - op.z, bz = tris[k].v1[r.k.z] - op.z, cz = tris[k].v2[r.k.z] - op.z;
  precise float ax = (tris[k].v0[r.k.x] - op.x) - r.s.x * az, ay = (tris[k].v0[r.k.y] - op.y) - r.s.y * az;
  precise float bx = (tris[k].v1[r.k.x] - op.x) - r.s.x * bz, by = (tris[k].v1[r.k.y] - op.y) - r.s.y * bz;
  precise float cx = (tris[k].v2[r.k.x] - op.x) - r.s.x * cz, cy = (tris[k].v2[r.k.y] - op.y) - r.s.y * cz;
  precise float e0 = cx * by - cy * bx, e1 = ax * cy - ay * cx, e2 = bx * ay - by * ax;
  if ((e0 < 0.0 || e1 < 0.0 || e2 < 0.0) && (e0 > 0.0 || e1 > 0.0 || e2 > 0.0)) return false;
  float det = e0 + e1 + e2;
  if (det == 0.0) return false;
  float inv = 1.0 / det;
  float t = (e0 * (r.s.z * az) + e1 * (r.s.z * bz) + e2 * (r.s.z * cz)) * inv;
  if (!(t > tmin && t < h.t)) return false;
  float u = e1 * inv, v = e2 * inv;  // vertex 1's and vertex 2's weights
  if (kAlphaMasks && cut_away(tris[k], u, v)) return false;
  h.t = t, h.u = u, h.v = v, h.ng = tris[k].ng.xyz;
  h.ref = (HR_PRIM_TRIANGLE << HR_PRIM_SHIFT) | k;
  return true;
}

bool hit_sphere(uint k, vec3 o, vec3 d, float tmin, bool shadow, inout Hit h) {
  vec4 cr = spheres[k].centre_radius;
  if (shadow && spheres[k].info.y == 0) return false;  // a light's sphere casts no shadow
  float r = abs(cr.w);
  vec3 oc = o - cr.xyz;
  float tc = -dot(oc, d);  // d is unit
  vec3 q = oc + d * tc;
  float h2 = r * r - dot(q, q);
  if (h2 < 0.0) return false;
  float hh = sqrt(h2);
  for (int n = 0; n < 2; ++n) {
    float root = n == 0 ? tc - hh : tc + hh;
    if (!(root > tmin && root < h.t)) continue;
    vec3 nn = (oc + d * root) / r;
    if (cr.w < 0.0 && dot(nn, d) <= 0.0) continue;  // inside only
    h.t = root, h.u = 0.0, h.v = 0.0, h.ng = nn;
    h.ref = (HR_PRIM_SPHERE << HR_PRIM_SHIFT) | k;
    return true;
  }
  return false;
}

bool hit_cone(uint k, vec3 o, vec3 d, float tmin, inout Hit h) {
  GpuCone c = cones[k];
  vec3 a = c.axis_len.xyz;
  float len = c.axis_len.w, kk = c.k_sign.x, rb = c.base_rb.w;
  // Solved from the point of the ray nearest the base, not from its origin:
  // in float, |wp|^2 - r0^2 from an origin far from a thin cone loses the
  // radius to cancellation (tree_s11's twigs: 30 dB against the CPU's doubles).
  float shift = dot(c.base_rb.xyz - o, d);  // d is unit
  vec3 w = o + d * shift - c.base_rb.xyz;
  float hw = dot(w, a), hd = dot(d, a);
  vec3 wp = w - a * hw, dp = d - a * hd;
  float r0 = rb + kk * hw;
  float qa = dot(dp, dp) - kk * kk * hd * hd;
  float qb = dot(wp, dp) - kk * hd * r0;
  float qc = dot(wp, wp) - r0 * r0;
  float t0, t1;
  if (qa == 0.0) {
    if (qb == 0.0) return false;
    t0 = t1 = -qc / (2.0 * qb);
  } else {
    float disc = qb * qb - qa * qc;
    if (disc < 0.0) return false;
    float q = -(qb + (qb >= 0.0 ? sqrt(disc) : -sqrt(disc)));
    if (q == 0.0) {
      t0 = t1 = 0.0;
    } else {
      t0 = q / qa;
      t1 = qc / q;
      if (t0 > t1) { float x = t0; t0 = t1; t1 = x; }
    }
  }
  for (int n = 0; n < 2; ++n) {
    float local = n == 0 ? t0 : t1, root = local + shift;
    if (!(root > tmin && root < h.t)) continue;
    float hh = hw + local * hd;
    if (hh < 0.0 || hh > len) continue;
    if (rb + kk * hh < 0.0) continue;  // the mirrored nappe
    vec3 nn = normalize(normalize(wp + dp * local) - a * kk);
    if (c.k_sign.y < 0.0 && dot(nn, d) <= 0.0) continue;  // inside only
    h.t = root, h.u = 0.0, h.v = 0.0, h.ng = nn;
    h.ref = (HR_PRIM_CONE << HR_PRIM_SHIFT) | k;
    return true;
  }
  return false;
}

bool hit_ref(uint ref, vec3 o, vec3 d, ShearedRay r, float tmin, bool shadow, inout Hit h) {
  if (kCountWork) ++tested;
  uint kind = ref >> HR_PRIM_SHIFT, k = ref & ((1u << HR_PRIM_SHIFT) - 1u);
  if (kind == HR_PRIM_TRIANGLE) return hit_triangle(k, o, r, tmin, h);
  if (kind == HR_PRIM_SPHERE) return hit_sphere(k, o, d, tmin, shadow, h);
  return hit_cone(k, o, d, tmin, h);
}

// ---- traversal: nearest hit in (tmin, tmax), or any hit for shadows ----

// 1 / d with each zero component taken as +-1e-30: an exact 0 gives an
// infinity, and a slab whose plane holds the origin then gives 0 * inf =
// NaN, which min() and max() may drop or keep (a ray straight down x = 0
// lost the boxes that end at x = 0).
vec3 safe_inverse(vec3 d) {
  vec3 tiny = vec3(1e-30);
  return 1.0 / mix(d, mix(-tiny, tiny, greaterThanEqual(d, vec3(0.0))), lessThan(abs(d), tiny));
}

// Where the ray (origin o, 1 / direction inv) enters and leaves each of
// node n's four child boxes, clipped to [tmin, tmax]: child c is met
// where t0[c] <= t1[c] (slabs, axis by axis). Each slab distance is three
// roundings from exact (1 / d, the subtraction, the product): the span is
// widened by twice their bound, so a ray that grazes a box's face or edge,
// as one through a triangle's vertex on it does, still enters the box
// (Ize 2013, "Robust BVH Ray Traversal", JCGT 2(2)).
const float kSlabGrowth = 2.0 * 3.0 * 5.9604645e-8 / (1.0 - 3.0 * 5.9604645e-8);
void child_spans(GpuNode n, vec3 o, vec3 inv, float tmin, float tmax, out vec4 t0, out vec4 t1) {
  vec4 ax = (n.lo_x - o.x) * inv.x, bx = (n.hi_x - o.x) * inv.x;
  vec4 ay = (n.lo_y - o.y) * inv.y, by = (n.hi_y - o.y) * inv.y;
  vec4 az = (n.lo_z - o.z) * inv.z, bz = (n.hi_z - o.z) * inv.z;
  vec4 near = max(max(min(ax, bx), min(ay, by)), min(az, bz));
  vec4 far = min(min(max(ax, bx), max(ay, by)), max(az, bz));
  t0 = max(near - abs(near) * kSlabGrowth, vec4(tmin));
  t1 = min(far + abs(far) * kSlabGrowth, vec4(tmax));
}

bool walk_bvh(vec3 o, vec3 d, float tmin, float tmax, bool any, out Hit h);
// Every ray's traversal, logged where the ray log is on.
bool trace_ray(vec3 o, vec3 d, float tmin, float tmax, bool any, out Hit h) {
  if (!kRayLog) return walk_bvh(o, d, tmin, tmax, any, h);
  uint nodes0 = visited, prims0 = tested;
  bool found = walk_bvh(o, d, tmin, tmax, any, h);
  uint at = atomicAdd(ray_log_head.x, 1u);
  if (at < uint(ray_log.length()))
    ray_log[at] = uvec4(uint(log_pixel.x), uint(log_pixel.y), log_kind | (any ? 0x80u : 0u) | (uint(band.frame) << 8),
                        min(visited - nodes0, 0xffffu) | (min(tested - prims0, 0xffffu) << 16));
  return found;
}
// One node record's children that the ray meets: leaves tested now,
// inner children put in order[] nearest last. A macro, not a loop over
// the records or a function: the 4-wide kernel then folds to the code it
// was before 8-wide nodes (a loop of one pass, and a function's arrays
// copied in and out, stayed in spirv-opt's output).
#define HR_MEET_CHILDREN(n, ON_ANY_HIT)                                                                   \
  {                                                                                                       \
    vec4 t0, t1;                                                                                          \
    child_spans(n, o, inv, tmin, h.t, t0, t1);                                                            \
    for (int c = 0; c < 4; ++c) {                                                                         \
      if (n.count[c] < 0 || !(t0[c] <= t1[c])) continue;                                                  \
      if (n.count[c] > 0) { /* a leaf: test it now */                                                     \
        for (int r = 0; r < n.count[c]; ++r)                                                              \
          if (hit_ref(refs[n.index[c] + r], o, d, sr, tmin, any, h)) {                                    \
            found = true;                                                                                 \
            if (any) ON_ANY_HIT;                                                                          \
          }                                                                                               \
        continue;                                                                                         \
      }                                                                                                   \
      int at = m++;                                                                                       \
      while ((kSortShadowChildren || !any) && at > 0 && near_t[at - 1] < t0[c]) { /* descending near t */ \
        near_t[at] = near_t[at - 1], order[at] = order[at - 1];                                           \
        --at;                                                                                             \
      }                                                                                                   \
      near_t[at] = t0[c], order[at] = n.index[c];                                                         \
    }                                                                                                     \
  }
// The ray's nearest hit in [tmin, tmax] (`any`: whether there is one).
bool walk_bvh(vec3 o, vec3 d, float tmin, float tmax, bool any, out Hit h) {
  h.t = tmax, h.ref = 0xffffffffu, h.u = 0.0, h.v = 0.0, h.ng = vec3(0.0);
  vec3 inv = safe_inverse(d);
  ShearedRay sr = sheared(d);
  // The node to visit next stays in a register: only the other children
  // met go through the stack (local memory).
  int stack[HR_STACK];
  int sp = 0, next = 0;
  bool found = false;
  while (next >= 0) {
    if (kCountWork) ++visited;
    // Children met, in order[] nearest last (visited next).
    int order[kNodeWidth];
    float near_t[kNodeWidth];
    int m = 0;
    GpuNode n = nodes[next * kNodeRecords];
    HR_MEET_CHILDREN(n, return true)
    if (kWideBvh) {
      n = nodes[next * kNodeRecords + 1];
      HR_MEET_CHILDREN(n, return true)
    }
    // The nearest child next, the others kept; none met: the last one kept.
    for (int c = 0; c + 1 < m && sp < HR_STACK; ++c) stack[sp++] = order[c];
    next = m > 0 ? order[m - 1] : sp > 0 ? stack[--sp] : -1;
  }
  return found;
}

// ---- the cameras: their lines are camera/pixel_lines.h, the CPU's text ----

// The frame's camera as the shared line functions take it (its constants
// are GpuFrame's lens_grid, panel_grid, pinhole and looking_glass).
HrFrame camera_frame() {
  HrFrame f;
  f.origin = F.origin.xyz, f.x = F.axis_x.xyz, f.y = F.axis_y.xyz, f.z = F.axis_z.xyz;
  return f;
}

// Subpixel c (s = c mod 3 of pixel i) of row j of a Looking Glass: its view
// value from the calibration's phase, then the sheared view of that
// continuous quilt index through the pixel (camera/pixel_lines.h). The
// phase is looking_glass_view()'s, as i A + j B + K_s with A and B split in
// two floats each and K_s taken mod 1 on the CPU (gpu_scene.cpp): the
// CPU's form in float would lose the view's fraction across a 2K panel.
void looking_glass_line(int c, int j, float u, float v, out vec3 origin, out vec3 dir) {
  int i = c / 3, s = c - 3 * i;
  HrLookingGlass g = F.looking_glass;
  int cell = hr_looking_glass_cell(F.cell_kind.x, F.cell_kind.y, g.centre.height, i, j);
  float a = fract(float(i) * F.panel.x) + float(i) * F.panel.y + fract(float(j) * F.panel.z) + float(j) * F.panel.w +
            F.cells[cell][s];
  float x = clamp(1.0 - fract(a), 0.00001, 0.999999);
  hr_looking_glass_line(g, camera_frame(), i, j, u, v, x, origin, dir);
}

// The pixel's line (world): origin at its lens centre, unit direction.
void pixel_line(int i, int j, float u, float v, out vec3 origin, out vec3 dir) {
  int grid = F.mode.y;
  if (kPanel && grid == HR_LOOKING_GLASS) {
    looking_glass_line(i, j, u, v, origin, dir);
    return;
  }
  if (grid == HR_PINHOLE) {
    hr_pinhole_line(F.pinhole, camera_frame(), i, j, u, v, origin, dir);
    return;
  }
  vec3 c, d;
  if (kPanel)
    hr_panel_line(F.panel_grid, i, j, u, v, c, d);
  else
    hr_lens_array_line(F.lens_grid, i, j, u, v, c, d);
  HrFrame f = camera_frame();
  origin = hr_to_world_point(f, c);
  dir = normalize(hr_to_world_dir(f, d));
}

// renderer.cpp's sample_offset: the pixel centre first, then a hashed
// rotation of the R2 sequence.
uint hash32(uint x) {
  x ^= x >> 16; x *= 0x7feb352du; x ^= x >> 15; x *= 0x846ca68bu; x ^= x >> 16;
  return x;
}
vec2 sample_offset(int i, int j, int k) {
  if (k == 0) return vec2(0.5);
  uint h = hash32(uint(i) * 73856093u ^ hash32(uint(j) * 19349663u));
  vec2 r = vec2(float(h & 0xffffu), float(h >> 16)) / 65536.0;
  return fract(r + float(k) * vec2(0.7548776662466927, 0.5698402909980532));
}

// A pixel sample's eye ray: the line at (u, v) in pixel (i, j) clipped to
// the scene's box (renderer.cpp, clip_primary and primary_over), or a
// pinhole view's to its clipping planes (view_renderer.cpp). `traced`:
// it meets the box; `empty_aimed`: a pinhole ray into an empty scene,
// which the CPU counts. t_sign: the line's parameter per unit of the ray's;
// optic0: how far the ray's origin lies behind where the CPU starts it (a
// Tachyon texture's MIP level and fog go by that distance).
struct EyeRay {
  vec3 o, d, line_dir;
  float tmin, tmax, t_sign, optic0;
  bool traced, empty_aimed, ortho;
};

EyeRay eye_ray(int i, int j, vec2 uv) {
  EyeRay e;
  vec3 lo, ld;
  pixel_line(i, j, uv.x, uv.y, lo, ld);
  e.line_dir = ld;
  // The line against the scene's box (renderer.cpp, clip_primary).
  vec3 inv = safe_inverse(ld);
  vec3 ta = (F.box_lo.xyz - lo) * inv, tb = (F.box_hi.xyz - lo) * inv;
  float t0 = max(max(min(ta.x, tb.x), min(ta.y, tb.y)), min(ta.z, tb.z));
  float t1 = min(min(max(ta.x, tb.x), max(ta.y, tb.y)), max(ta.z, tb.z));
  float margin = F.box_lo.w;
  e.ortho = F.mode.z == HR_ORTHOSCOPIC;
  bool pinhole = F.mode.y == HR_PINHOLE || (kPanel && F.mode.y == HR_LOOKING_GLASS);
  // A pinhole view's ray is not clipped to the box but to the view's
  // clipping planes, perpendicular to its axis (view_renderer.cpp): a ray at
  // cosine ca to the axis meets them at clip / ca.
  float ca = dot(ld, -F.axis_z.xyz);
  bool aimed = ca > 0.0 || (F.clip.x == 0.0 && isinf(F.clip.y));
  e.traced = pinhole ? F.box_hi.w == 0.0 && aimed : F.box_hi.w == 0.0 && t0 <= t1 && (e.ortho || t1 > 0.0);
  e.empty_aimed = pinhole && aimed && !e.traced;
  e.o = lo, e.d = ld, e.t_sign = 1.0, e.optic0 = 0.0, e.tmin = 0.0, e.tmax = kInf;
  if (e.ortho) {
    // The CPU starts it beyond the box and runs back along the line
    // (renderer.cpp, primary_over); here it starts on the lens plane and
    // runs back over negative distances, the same segment, so that float
    // keeps the distances that the depth AOV is (a box thousands of
    // units deep, as Room's, lost 1e-4 of them from the far start).
    float start = t1 + margin;
    e.d = -ld;
    e.t_sign = -1.0, e.optic0 = start, e.tmin = -start, e.tmax = -(t0 - margin);
  } else if (pinhole) {
    bool clipped = !(F.clip.x == 0.0 && isinf(F.clip.y));
    e.tmin = clipped ? F.clip.x / ca : 0.0, e.tmax = clipped ? F.clip.y / ca : kInf;
  } else {
    e.tmin = max(0.0, t0 - margin), e.tmax = t1 + margin;
  }
  return e;
}

// ---- shading (render/models/nff_model.hpp, blinn_phong_model.cpp) ----

struct Surface {
  vec3 p, ng, ns;  // position; unit normals, ng outward or winding, ns beside it
  int object;
  uint material;
};

Surface surface_of(vec3 o, vec3 d, Hit h) {
  Surface s;
  s.p = o + d * h.t;
  uint kind = h.ref >> HR_PRIM_SHIFT, k = h.ref & ((1u << HR_PRIM_SHIFT) - 1u);
  if (kind == HR_PRIM_TRIANGLE) {
    GpuTriangle tri = tris[k];
    s.ng = tri.ng.xyz;
    s.ns = s.ng;
    int patch_at = floatBitsToInt(tri.v1.w);
    if (patch_at >= 0) {
      GpuPatch pn = patches[patch_at];
      vec3 ns = pn.n0.xyz * (1.0 - h.u - h.v) + pn.n1.xyz * h.u + pn.n2.xyz * h.v;
      if (length(ns) > 0.0) s.ns = normalize(ns);
    }
    s.object = floatBitsToInt(tri.ng.w);
  } else if (kind == HR_PRIM_SPHERE) {
    s.ng = s.ns = normalize(h.ng);
    s.object = spheres[k].info.x;
  } else {
    s.ng = s.ns = normalize(h.ng);
    s.object = floatBitsToInt(cones[k].k_sign.z);
  }
  s.material = object_material[s.object];
  return s;
}

// A light's falloff parameters as the shared falloff takes them
// (shading/lights.h; render/light_falloff.hpp on the CPU).
HrLightFalloff falloff_params(GpuLight L) {
  HrLightFalloff f;
  f.kind = int(L.position_kind.w);
  f.direction = L.direction.xyz;
  f.kc = L.attenuation.x, f.kl = L.attenuation.y, f.kq = L.attenuation.z, f.range = L.attenuation.w;
  f.fall_start = L.cone.x, f.fall_end = L.cone.y, f.cos_fall_start = L.cone.z, f.cos_fall_end = L.cone.w;
  f.smooth_cone = L.flags.x != 0;
  f.unit = L.intensity_unit.w != 0.0;
  return f;
}

vec3 reflect_about(vec3 d, vec3 n) { return d - n * (2.0 * dot(d, n)); }

// ---- glTF 2.0's metallic-roughness BRDF: its terms are shading/gltf_whitted.h ----

const float kPi = 3.141592653589793;
const float kMirrorRoughness = 0.1;  // gltf_brdf.hpp: below it, one mirror ray

// ---- Tachyon's texfuncs and shading (render/textures.cpp,
// render/models/tachyon_model.cpp; docs/tachyon-notes.md §3) ----

// Tachyon ignores a term below half an 8-bit step (MINCONTRIB).
const float kMinContrib = 0.5 / 255.0;

// A level's texel, 0 to 255 per channel.
vec3 texel(ivec4 L, int x, int y, int z) {
  uint t = texels[L.w + (z * L.y + y) * L.x + x];
  return vec3(float(t & 0xffu), float((t >> 8) & 0xffu), float((t >> 16) & 0xffu));
}

// Tachyon's ImageMap and VolImageMapTrilinear (MipMap::trilinear).
vec3 trilinear(ivec4 L, float u, float v, float w) {
  float x = float(L.x - 1) * u, y = float(L.y - 1) * v, z = float(L.z - 1) * w;
  int ix = int(x), iy = int(y), iz = int(z);
  float px = x - float(ix), py = y - float(iy), pz = z - float(iz);
  int ix1 = min(ix + 1, L.x - 1), iy1 = min(iy + 1, L.y - 1), iz1 = min(iz + 1, L.z - 1);
  vec3 near_lo = mix(texel(L, ix, iy, iz), texel(L, ix1, iy, iz), px);
  vec3 near_hi = mix(texel(L, ix, iy1, iz), texel(L, ix1, iy1, iz), px);
  vec3 c = mix(near_lo, near_hi, py);
  if (L.z > 1) {
    vec3 far_lo = mix(texel(L, ix, iy, iz1), texel(L, ix1, iy, iz1), px);
    vec3 far_hi = mix(texel(L, ix, iy1, iz1), texel(L, ix1, iy1, iz1), px);
    c = mix(c, mix(far_lo, far_hi, py), pz);
  }
  return c / 255.0;
}

// Tachyon's MIPMap (MipMap::blend_levels): black outside the unit cube;
// past the second-coarsest level the coarsest, unblended.
vec3 mip_sample(GpuTexture t, float u, float v, float w, float d) {
  if (!(u >= 0.0 && u <= 1.0 && v >= 0.0 && v <= 1.0 && w >= 0.0 && w <= 1.0)) return vec3(0.0);
  int first = t.kind_level_count.y, n = t.kind_level_count.z;
  float level = clamp(d, 0.0, 1.0) * (float(n) - 0.9999);
  int i = int(level);
  if (i < n - 2)
    return mix(trilinear(levels[first + i].size_offset, u, v, w), trilinear(levels[first + i + 1].size_offset, u, v, w),
               level - float(i));
  return trilinear(levels[first + n - 1].size_offset, u, v, w);
}

// u - trunc(u), wrapped into [0, 1): Tachyon's repeat.
float tachyon_wrap(float u) {
  u -= trunc(u);
  return u < 0.0 ? u + 1.0 : u;
}

// The colour of texture k at p (world) seen at optic_dist along the ray
// (textures.cpp, texture_colour), for a material of colour `base`.
vec3 tachyon_texture(int k, vec3 base, vec3 p, float optic_dist) {
  GpuTexture t = textures[k];
  vec3 q = p - t.centre.xyz;
  int kind = t.kind_level_count.x;
  bool mapped = t.kind_level_count.y >= 0;
  if (kind == HR_TEX_CHECKER3D) {
    ivec3 cell = ivec3(abs(q) * 3.0 + 0.5) % 2;
    return (cell.x + cell.y + cell.z) % 2 == 1 ? vec3(1.0, 0.2, 0.0) : vec3(0.0, 0.2, 1.0);
  }
  if (kind == HR_TEX_WOOD) {
    vec3 x = q / t.scale.xyz;
    float radius = sqrt(x.x * x.x + x.z * x.z);
    float angle = x.z == 0.0 ? 3.1415926 / 2.0 : atan(x.x / x.z);
    radius += 3.0 * sin(20.0 * angle + x.y / 150.0);
    int g = int(radius + 0.5);  // truncated toward 0, as C++ does; a negative grain is light
    return g < 0 || g % 60 < 40 ? vec3(0.8, 1.0, 0.2) : vec3(0.0);
  }
  if (kind == HR_TEX_CYLINDER_CHECKER || kind == HR_TEX_CYLINDRICAL_IMAGE || kind == HR_TEX_SPHERICAL_IMAGE) {
    float u, v;
    // The angles of Tachyon's acos(x / r) taken as atan(|y|, x), the same
    // angle: float's acos loses it near 0 and pi, where a star map's single
    // texels are.
    if (kind == HR_TEX_SPHERICAL_IMAGE) {  // xyztospr: v from the -y pole, u about y in turns
      float around = sqrt(q.x * q.x + q.z * q.z);
      if (!(length(q) > 0.0)) {
        u = 0.0, v = 0.0;
      } else {
        v = atan(around, -q.y) / 3.1415926;  // Tachyon's own truncated pi
        float theta = around > 0.0 ? atan(abs(q.z), q.x) / 6.283185307179586 : 0.0;
        u = q.z > 0.0 ? theta : 1.0 - theta;
      }
    } else {  // xyztocyl about z (the image's cylinder: the texture's y, so y and z swapped first)
      vec3 c = kind == HR_TEX_CYLINDER_CHECKER ? q : q.xzy;
      v = c.z;
      float a = c.x != 0.0 || c.y != 0.0 ? atan(abs(c.y), c.x) / 6.283185307179586 : 0.0;
      u = c.y < 0.0 ? 1.0 - a : a;
    }
    if (kind == HR_TEX_CYLINDER_CHECKER) {
      int x = int(abs(u) * 18.0) % 2, y = int(abs(v) * 10.0) % 2;
      return (x + y) % 2 == 1 ? vec3(1.0, 0.2, 0.0) : vec3(0.0, 0.2, 1.0);
    }
    if (!mapped) return base;
    u = tachyon_wrap(u * t.scale.x + t.rotate.x);
    v = tachyon_wrap(v * t.scale.y + t.rotate.y);
    float max_scale = max(abs(t.scale.x), abs(t.scale.y));
    return mip_sample(t, u, v, 0.0, 0.05 * optic_dist * max_scale / (1e-8 + 8.0 * length(q)));  // per 8 radii
  }
  if ((kind == HR_TEX_PLANAR_IMAGE || kind == HR_TEX_VOLUME_IMAGE) && mapped) {
    float u = tachyon_wrap(dot(t.uaxis.xyz, q) * t.scale.x + t.rotate.x);
    float v = tachyon_wrap(dot(t.vaxis.xyz, q) * t.scale.y + t.rotate.y);
    float max_scale = max(abs(t.scale.x), abs(t.scale.y));
    float w = 0.0;
    if (kind == HR_TEX_VOLUME_IMAGE) {
      w = tachyon_wrap(dot(t.waxis.xyz, q) * t.scale.z + t.rotate.z);
      max_scale = max(max_scale, abs(t.scale.z));
    }
    return mip_sample(t, u, v, w, 0.05 * optic_dist * max_scale);
  }
  return base;
}

// Tachyon's light toward a point: N.L over the attenuation, the spot's
// linear falloff in the angle (tachyon_light); xyz the direction, w the
// intensity, and the distance in `dist`.
vec4 tachyon_light(GpuLight L, vec3 p, vec3 n, out float dist) {
  int kind = int(L.position_kind.w);
  if (kind == HR_LIGHT_DIRECTIONAL) {
    dist = kInf;
    return vec4(-L.direction.xyz, dot(n, -L.direction.xyz));
  }
  vec3 d = L.position_kind.xyz - p;
  dist = length(d);
  if (!(dist > 0.0)) return vec4(0.0);
  vec3 to_light = d / dist;
  vec4 at = L.attenuation;
  float intensity = dot(n, to_light) / (at.x + (at.y + at.z * dist) * dist);
  if (kind == HR_LIGHT_SPOT) {
    float angle = acos(clamp(-dot(L.direction.xyz, to_light), -1.0, 1.0));
    if (angle > L.cone.y) intensity = 0.0;
    else if (angle > L.cone.x) intensity *= 1.0 - (angle - L.cone.x) / (L.cone.y - L.cone.x);
  }
  return vec4(to_light, intensity);
}

// The fog's share of a hit at r along its ray (tachyon_finish): the hit's
// colour is k of itself and 1 - k of the fog's.
float fog_keep(float r) {
  int mode = int(F.fog.w);
  if (mode == 0) return 1.0;
  float k = mode == HR_FOG_LINEAR ? (F.fog_range.y - r) / (F.fog_range.y - F.fog_range.x)
          : mode == HR_FOG_EXP    ? exp(-F.fog_range.z * (r - F.fog_range.x))
                                  : exp(-(F.fog_range.z * (r - F.fog_range.x)) * (F.fog_range.z * (r - F.fog_range.x)));
  return clamp(k, 0.0, 1.0);
}

// How much of a light a Tachyon shadow ray from o toward d lets through
// (tachyon_shadow): 0 when an opaque surface blocks it, else the product of
// the transparent surfaces' transmittance, walked hit by hit where the
// scene has any; lights' own spheres pass.
float tachyon_shadow(vec3 o, vec3 d, float tmax, inout uint shadow_rays) {
  ++shadow_rays;
  log_kind |= 0x80u;  // its walks through transparent surfaces look for the nearest hit, yet are this shadow ray's
  Hit h;
  if (F.flags.x == 0) return trace_ray(o, d, 0.0, tmax, true, h) ? 0.0 : 1.0;
  float filter_ = 1.0, tnear = 0.0;
  for (int step = 0; step < 64; ++step) {  // the CPU's cap: a ray grazing a stack of coincident surfaces
    if (!trace_ray(o, d, tnear, tmax, false, h)) return filter_;
    GpuMaterial m = materials[surface_of(o, d, h).material];
    if (m.tachyon.w == 0.0) {
      if (int(m.emission_model.w) != HR_MODEL_TACHYON || !(m.ks_shine_t_ior.z > 0.0)) return 0.0;
      filter_ *= m.ks_shine_t_ior.z;
      if (filter_ < kMinContrib) return 0.0;
    }
    tnear = max(h.t, tnear) + F.clip.z;
    if (!(tnear < tmax)) return filter_;
    ++shadow_rays;
  }
  return 0.0;
}

// Where the camera's pixel (i, j) goes in the output: its tile of the image
// (a quilt's view) and the rows this render holds.
uint out_pixel(int i, int j) { return uint(F.tile.y + j - F.rows.x) * uint(F.tile.z) + uint(F.tile.x + i); }

// A tangent-space normal map's texel turned into the shading normal at a
// triangle whose texture coordinates are `uv` (RenderScene::apply_normal_map:
// the tangent along increasing u, the bitangent along increasing v, both
// made orthonormal to the interpolated normal n; x and y times `scale`).
vec3 normal_mapped(GpuTriangle tri, GpuUv uv, vec3 n, vec3 texel, float scale) {
  vec3 e1 = tri.v1.xyz - tri.v0.xyz, e2 = tri.v2.xyz - tri.v0.xyz;
  float du1 = uv.uv01.z - uv.uv01.x, dv1 = uv.uv01.w - uv.uv01.y;
  float du2 = uv.uv2_scale.x - uv.uv01.x, dv2 = uv.uv2_scale.y - uv.uv01.y;
  float det = du1 * dv2 - du2 * dv1;
  if (!(abs(det) > 0.0)) return n;  // the texture is not spread over the triangle: no frame
  vec3 dpdu = (e1 * dv2 - e2 * dv1) / det, dpdv = (e2 * du1 - e1 * du2) / det;
  vec3 along = dpdu - n * dot(n, dpdu);
  if (!(length(along) > 0.0)) return n;
  vec3 tangent = normalize(along), bitangent = cross(n, tangent);
  if (dot(bitangent, dpdv) < 0.0) bitangent = -bitangent;
  vec3 mapped = tangent * ((2.0 * texel.x - 1.0) * scale) + bitangent * ((2.0 * texel.y - 1.0) * scale) + n * (2.0 * texel.z - 1.0);
  return length(mapped) > 0.0 ? normalize(mapped) : n;
}

// A hit's material with a mesh's maps applied at a triangle with texture
// coordinates (RenderScene::surface), read at the MIP level of the
// pixel's footprint `optic` away along the eye's path: colour, emission,
// metallic and roughness (pbr's x and y), Blinn-Phong's specular map; a
// normal map turns `s`'s shading normal.
struct MappedMaterial {
  vec3 colour, emission;
  vec4 pbr;
  float highlight;
};

MappedMaterial mapped_material(GpuMaterial m, Hit h, float optic, inout Surface s) {
  MappedMaterial mm;
  mm.colour = m.colour_kd.xyz, mm.emission = m.emission_model.xyz, mm.pbr = m.pbr, mm.highlight = 1.0;
  if (kMeshTextures && (h.ref >> HR_PRIM_SHIFT) == HR_PRIM_TRIANGLE && int(m.emission_model.w) != HR_MODEL_TACHYON) {
    GpuTriangle tri = tris[h.ref & ((1u << HR_PRIM_SHIFT) - 1u)];
    int uv_at = floatBitsToInt(tri.v0.w);
    if (uv_at >= 0) {
      float width = F.footprint.x + F.footprint.y * optic;
      vec4 texel;
      if (texel_at(m.maps.x, uv_at, h.u, h.v, width, texel)) mm.colour *= texel.rgb;
      if (int(m.emission_model.w) == HR_MODEL_BLINN_PHONG) {
        if (texel_at(m.maps2.x, uv_at, h.u, h.v, width, texel)) mm.highlight = texel.r;
      } else if (texel_at(m.maps.y, uv_at, h.u, h.v, width, texel)) {  // blue metallic, green roughness
        mm.pbr.x = clamp(m.pbr.x * texel.b, 0.0, 1.0), mm.pbr.y = clamp(m.pbr.y * texel.g, 0.0, 1.0);
      }
      if (texel_at(m.maps.z, uv_at, h.u, h.v, width, texel)) s.ns = normal_mapped(tri, uvs[uv_at], s.ns, texel.rgb, m.alpha.z);
      if (texel_at(m.maps.w, uv_at, h.u, h.v, width, texel)) mm.emission *= texel.rgb;
    }
  }
  return mm;
}

// A Tachyon surface's colour: its triangle's vertex colours interpolated,
// else its texfunc's seen `optic` away, else `colour`
// (RenderScene::surface_colour).
vec3 tachyon_colour(GpuMaterial m, Hit h, vec3 p, vec3 colour, float optic) {
  int coloured = (h.ref >> HR_PRIM_SHIFT) == HR_PRIM_TRIANGLE ? floatBitsToInt(tris[h.ref & ((1u << HR_PRIM_SHIFT) - 1u)].v2.w) : -1;
  if (coloured >= 0)
    return vertex_colours[coloured].n0.xyz * (1.0 - h.u - h.v) + vertex_colours[coloured].n1.xyz * h.u +
           vertex_colours[coloured].n2.xyz * h.v;
  return m.maps.x >= 0 ? tachyon_texture(m.maps.x, colour, p, optic) : colour;
}

// The AOVs of pixel (i, j) from its first sample's first hit, met by the
// line along `ld` at signed depth `depth` (render/renderer.cpp, store_pixel).
void write_hit_aovs(int i, int j, vec3 ld, Surface s, GpuMaterial m, MappedMaterial mm, float depth) {
  uint a = out_pixel(i, j) * 8u;
  vec3 toward = F.mode.z == HR_ORTHOSCOPIC ? ld : -ld;
  vec3 n = dot(s.ns, toward) >= 0.0 ? s.ns : -s.ns;
  // glTF's albedo: the diffuse share (render_scene.hpp, albedo_of).
  vec3 albedo = kGltf && int(m.emission_model.w) == HR_MODEL_GLTF ? mm.colour * ((1.0 - mm.pbr.x) * (1.0 - mm.pbr.z)) : mm.colour;
  aov_out[a + 0u] = albedo.x, aov_out[a + 1u] = albedo.y, aov_out[a + 2u] = albedo.z;
  aov_out[a + 3u] = depth;
  aov_out[a + 4u] = n.x, aov_out[a + 5u] = n.y, aov_out[a + 6u] = n.z;
  aov_out[a + 7u] = float(s.object);
}

// The AOVs of a pixel whose first sample met nothing: zero, depth NaN, id -1.
void write_miss_aovs(int i, int j) {
  uint a = out_pixel(i, j) * 8u;
  for (uint q = 0u; q < 8u; ++q) aov_out[a + q] = 0.0;
  aov_out[a + 3u] = uintBitsToFloat(0x7fc00000u);
  aov_out[a + 7u] = -1.0;
}

// Shadow rays prepared at once (their terms in a small array), then traced.
const int kLightChunk = 8;

struct Pending {
  vec3 o, d, weight;
  int depth;
};

// The shadow queue traced (kShadowPass 1): each lane walks one ray a node
// a step, and lanes whose ray is done take the queue's next together (one
// atomic a subgroup), so no lane waits on another's longer walk (after
// Aila and Laine 2009). A ray that reaches its light is marked so
// (dir_lit.w = 1). A subgroup takes at most HR_SHADOW_RAYS_PER_LANE rays
// a lane, and the dispatch holds enough invocations for the queue's
// capacity; those that find it drained leave at once. The loop's one exit
// is in its condition (design/gpu.md: lavapipe and loops).
void add_fetch_work();
// The wavefront's shadow queue of the vertex at band.depth (wavefront.glsl).
uint wave_shadow_head() { return uint(HR_WAVE_VERTICES + band.depth % HR_WAVE_VERTICES); }
void shadow_pass() {
  bool wave = kWaveStage == HR_WAVE_SHADOW;  // the wavefront's shadow rays, else the shadow queue's
  uint queued = wave ? wave_heads[wave_shadow_head()].x : min(shadow_head.x, shadow_head.z);
  uint budget = uint(wave ? kRaysPerLane : HR_SHADOW_RAYS_PER_LANE) * gl_SubgroupSize, taken = 0u;
  bool live = false, drained = false;
  vec3 o = vec3(0.0), d = vec3(0.0), inv = vec3(0.0);
  ShearedRay sr = sheared(vec3(0.0, 0.0, 1.0));
  float tmax = 0.0;
  uint at = 0u;
  int stack[HR_STACK];
  int sp = 0, next = -1;
  bool more = true;
  while (more) {
    uvec4 want = subgroupBallot(!live);
    uint k = min(subgroupBallotBitCount(want), budget - taken);
    if (k > 0u && !drained) {
      uint base = 0u;
      if (subgroupElect()) base = wave ? atomicAdd(wave_heads[wave_shadow_head()].y, k) : atomicAdd(shadow_head.y, k);
      base = subgroupBroadcastFirst(base);
      taken += k;
      drained = base + k >= queued;
      uint rank = subgroupBallotExclusiveBitCount(want);
      if (!live && rank < k && base + rank < queued) {
        at = base + rank;
        vec4 origin_tmax, dir;
        if (wave) {
          at = wave_shadow_queue[at];
          origin_tmax = wave_shadows[at].origin_tmax, dir = wave_shadows[at].dir;
        } else {
          origin_tmax = shadow_queue[at].origin_tmax, dir = shadow_queue[at].dir_lit;
        }
        o = origin_tmax.xyz, tmax = origin_tmax.w, d = dir.xyz, inv = safe_inverse(d), sr = sheared(d);
        live = true, sp = 0, next = 0;
      }
    }
    if (live) {
      if (kCountWork) ++visited;
      bool blocked = false;
      int first = -1;
      for (int rec = 0; rec < kNodeRecords && !blocked; ++rec) {
        GpuNode n = nodes[next * kNodeRecords + rec];
        vec4 t0, t1;
        child_spans(n, o, inv, 0.0, tmax, t0, t1);
        for (int c = 0; c < 4 && !blocked; ++c) {
          if (n.count[c] < 0 || !(t0[c] <= t1[c])) continue;
          if (n.count[c] > 0) {
            for (int q = 0; q < n.count[c] && !blocked; ++q) {
              Hit h;
              h.t = tmax, h.ref = 0xffffffffu, h.u = 0.0, h.v = 0.0, h.ng = vec3(0.0);
              blocked = hit_ref(refs[n.index[c] + q], o, d, sr, 0.0, true, h);
            }
          } else if (first < 0) {
            first = n.index[c];
          } else if (sp < HR_STACK) {
            stack[sp++] = n.index[c];
          }
        }
      }
      next = first >= 0 ? first : sp > 0 ? stack[--sp] : -1;
      if (blocked || next < 0) {
        if (wave && blocked) wave_shadows[at].term = vec4(0.0);
        if (!wave && !blocked) shadow_queue[at].dir_lit.w = 1.0;
        live = false;
      }
    }
    if (kCountWork) ++lane_steps;
    more = subgroupAny(live) || (!drained && taken < budget);
  }
  add_fetch_work();
}

// A fetching traversal's work added to the counters of band.index (the
// shadow queue's: band 0): nodes, primitives and its lanes' steps (z).
void add_fetch_work() {
  if (!kCountWork) return;
  uvec3 work = subgroupAdd(uvec3(visited, tested, lane_steps));
  if (subgroupElect()) {
    int slot = 2 * (band.index * HR_COUNT_SLOTS + int(gl_WorkGroupID.x % uint(HR_COUNT_SLOTS)));
    atomicAdd(band_counts[slot].x, work.x);
    atomicAdd(band_counts[slot].y, work.y);
    atomicAdd(band_counts[slot].z, work.z);
  }
}

// Each pixel's unblocked shadow terms added to its colour (kShadowPass 2),
// from its last queued ray back; invocations by colour buffer pixel, the
// image's count in the push constants' row0, the band's first pixel in rows.
void shadow_resolve() {
  uint p = uint(band.rows) + (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * (gl_WorkGroupSize.x * gl_WorkGroupSize.y) +
           gl_LocalInvocationIndex;
  if (p >= uint(band.row0)) return;
  uint capacity = shadow_head.z, run = shadow_last[p];
  vec3 sum = vec3(0.0);
  while (run < capacity) {
    uint packed = floatBitsToUint(shadow_terms[run].w);  // the run before << 4 | the run's length
    uint n = min(packed & 15u, capacity - run);
    for (uint q = 0u; q < n; ++q)
      if (shadow_queue[run + q].dir_lit.w != 0.0) sum += shadow_terms[run + q].xyz;
    uint before = packed >> 4;
    run = before < run ? before : capacity;  // linked back to earlier runs only
  }
  if (sum != vec3(0.0)) colour_sum[p * 3u + 0u] += sum.x, colour_sum[p * 3u + 1u] += sum.y, colour_sum[p * 3u + 2u] += sum.z;
}

void add_counts(uvec4 rays);
#include "path.glsl"

// The rays of a pixel's ray tree still to trace, depth first (no recursion
// in GLSL): an invocation's own, shared by the functions that push them.
Pending ray_stack[HR_MAX_DEPTH + 2];
int ray_sp = 0;

// What one Whitted hit shows: its surface turned to the side the ray came
// from (nff-notes §10.2), its material with the mesh's maps applied.
struct Shaded {
  Surface s;
  GpuMaterial m;
  vec3 colour, emission, view, ng, ns, above;
  vec4 pbr;
  float highlight, eps;  // eps: the scene's offset for secondary rays
  bool front;
};

// A Tachyon surface hit by `r` (tachyon_model.cpp, TachyonModel::shade):
// its light seen through fog, its mirror and straight-through rays pushed
// (past the depth limit they see the background), and each light's term
// behind Tachyon's filtered shadow. Returns what it adds to the sample.
vec3 shade_tachyon(Pending r, Hit h, Shaded a, float optic, int max_depth, inout uint shadow_rays, inout uint reflected_rays,
                   inout uint refracted_rays) {
  GpuMaterial m = a.m;
  float kd = m.colour_kd.w, ks = m.ks_shine_t_ior.x, shine = m.ks_shine_t_ior.y;
  vec3 tex = tachyon_colour(m, h, a.s.p, a.colour, optic);
  vec3 c = vec3(0.0);
  if (m.tachyon.w != 0.0) {  // a light's sphere: its colour, unshaded
    c = r.weight * tex;
  } else {
    // Fog takes its share of everything this hit shows, secondary rays included.
    float keep = fog_keep(optic);
    c = r.weight * ((1.0 - keep) * F.fog.xyz);
    vec3 w = r.weight * keep;
    float T = m.ks_shine_t_ior.z;
    if (ks > kMinContrib) {  // past the depth limit a secondary ray sees the background
      ++reflected_rays;
      if (r.depth < max_depth) ray_stack[ray_sp++] = Pending(a.above, normalize(reflect_about(r.d, a.ns)), w * ks, r.depth + 1);
      else c += w * ks * F.background.xyz;
    }
    if (T > kMinContrib) {  // straight through
      ++refracted_rays;
      if (r.depth < max_depth) ray_stack[ray_sp++] = Pending(a.s.p - a.ng * a.eps, r.d, w * T, r.depth + 1);
      else c += w * T * F.background.xyz;
    }
    c += w * tex * m.tachyon.x;
    if (kd > kMinContrib || m.tachyon.y > kMinContrib) {
      for (int l = 0; l < F.counts.x; ++l) {
        GpuLight L = lights[l];
        float dist;
        vec4 to_light = tachyon_light(L, a.s.p, a.ns, dist);
        if (!(to_light.w > kMinContrib)) continue;
        float seen = tachyon_shadow(a.above, to_light.xyz, dist - a.eps, shadow_rays);
        if (seen == 0.0) continue;
        vec3 term = tex * (kd * to_light.w * seen) * L.intensity_unit.xyz;
        if (m.tachyon.y > kMinContrib) {  // Blinn's half vector, unnormalised until the dot
          vec3 hv = to_light.xyz - r.d;
          float spec = dot(a.ns, hv);
          if (spec > kMinContrib)
            term += (m.tachyon.z != 0.0 ? tex : L.intensity_unit.xyz) * (pow(spec / length(hv), shine) * m.tachyon.y);
        }
        c += w * term;
      }
    }
  }
  return c;
}

// The mirror and transmitted rays of a hit of `r` pushed, for glTF's model
// (GltfModel::secondary_rays) or NFF's and Blinn-Phong's (shading.cpp,
// add_secondary), before the shadow rays so that what they need is not kept
// across them.
void push_secondary_rays(Pending r, Shaded a, bool gltf, inout uint reflected_rays, inout uint refracted_rays) {
  GpuMaterial m = a.m;
  float eps = a.eps;
  if (gltf) {
    float T = m.ks_shine_t_ior.z, n_dot_v = dot(a.ns, a.view);
    if (a.pbr.y < kMirrorRoughness) {  // the Fresnel mix at N.V
      vec3 rd = reflect_about(r.d, a.ns);
      if (dot(rd, a.ng) <= 0.0) rd = reflect_about(r.d, a.ng);
      vec3 mirror = hr_gltf_mirror_weight(a.colour, a.pbr.x, a.pbr.w, n_dot_v);
      ray_stack[ray_sp++] = Pending(a.above, normalize(rd), r.weight * mirror * (1.0 - T), r.depth + 1);
      ++reflected_rays;
    }
    // BLEND's uncovered share and the transmission's share of the covered
    // part both go straight through (thin-walled): one ray.
    if (T > 0.0 || a.pbr.z > 0.0) {
      vec3 through = hr_gltf_transmit_weight(a.colour, a.pbr.x, a.pbr.w, a.pbr.z, n_dot_v);
      ray_stack[ray_sp++] = Pending(a.s.p - a.ng * eps, r.d, r.weight * (vec3(T) + through * (1.0 - T)), r.depth + 1);
      ++refracted_rays;
    }
  } else {
    float ks = m.ks_shine_t_ior.x, T = m.ks_shine_t_ior.z, ior = m.ks_shine_t_ior.w;
    if (ks > 0.0) {  // the true normal where the shading one sends it in
      vec3 rd = reflect_about(r.d, a.ns);
      if (dot(rd, a.ng) <= 0.0) rd = reflect_about(r.d, a.ng);
      ray_stack[ray_sp++] = Pending(a.above, normalize(rd), r.weight * ks, r.depth + 1);
      ++reflected_rays;
    }
    if (T > 0.0) {
      float eta = a.front ? 1.0 / ior : ior;
      float cos_i = dot(a.view, a.ns);
      float kk = 1.0 - eta * eta * (1.0 - cos_i * cos_i);
      vec3 o2, d2;
      if (kk < 0.0) {  // total internal reflection
        vec3 rd = reflect_about(r.d, a.ns);
        if (dot(rd, a.ng) <= 0.0) rd = reflect_about(r.d, a.ng);
        o2 = a.above, d2 = normalize(rd);
        ++reflected_rays;
      } else {
        d2 = normalize(r.d * eta + a.ns * (eta * cos_i - sqrt(kk)));
        if (dot(d2, a.ng) >= 0.0) d2 = r.d;
        o2 = a.s.p - a.ng * eps;
        ++refracted_rays;
      }
      ray_stack[ray_sp++] = Pending(o2, d2, r.weight * T, r.depth + 1);
    }
  }
}

// The BRDF's term (glTF's, times the part of the surface that is there) or
// NFF's and Blinn-Phong's, toward a light along `to_light`.
vec3 surface_term(Shaded a, bool gltf, vec3 to_light) {
  GpuMaterial m = a.m;
  float kd = m.colour_kd.w, ks = m.ks_shine_t_ior.x, shine = m.ks_shine_t_ior.y;
  vec3 term;
  if (gltf) {
    term = (1.0 - m.ks_shine_t_ior.z) * hr_gltf_direct(a.colour, a.pbr.x, a.pbr.y, a.pbr.w, a.pbr.z, a.ns, a.view, to_light);
  } else {
    term = a.colour * (kd * dot(a.ns, to_light));
    if (ks > 0.0) {
      float r_dot_v = dot(reflect_about(-to_light, a.ns), a.view);
      if (r_dot_v > 0.0) term += vec3(ks * pow(r_dot_v, shine));
    }
    if (int(m.emission_model.w) == HR_MODEL_BLINN_PHONG) {
      float n_dot_h = dot(a.ns, normalize(to_light + a.view));
      if (n_dot_h > 0.0) term += m.specular.xyz * (a.highlight * pow(n_dot_h, shine));
    }
  }
  return term;
}

void whitted_wave_shadow(vec3 from, vec4 ray_to, vec3 term);  // whitted_wavefront.glsl

// The lights seen from a hit of `r`, kLightChunk at a time: each light's
// weighted term computed before its shadow ray, so that only the ray and
// the term cross the traversal. With the shadow queue the rays are queued
// (one atomic for the lanes here together, each lane's rays a run of their
// own, linked to the pixel's run before; a run past the queue's capacity is
// traced here; in Whitted's wavefront every ray is written for its shadow
// stage). Returns the unblocked terms traced here.
vec3 shade_lights(Pending r, Shaded a, bool gltf, int spp, inout uint shadow_rays, inout uint last_run) {
  vec3 c = vec3(0.0);
  for (int l0 = 0; l0 < F.counts.x; l0 += kLightChunk) {
    vec3 contrib[kLightChunk];
    vec4 ray_to[kLightChunk];  // direction, and how far
    int n = 0;
    for (int l = l0; l < min(l0 + kLightChunk, F.counts.x); ++l) {  // shading.cpp, shadow_ray and the models' terms
      GpuLight L = lights[l];
      int kind = int(L.position_kind.w);
      vec3 to_light;
      float dist = kInf, falloff = 1.0;
      bool casts;
      if (kind == HR_LIGHT_DIRECTIONAL) {
        to_light = -L.direction.xyz;
        casts = dot(a.ns, to_light) > 0.0;
      } else {
        to_light = L.position_kind.xyz - a.s.p;
        dist = length(to_light);
        to_light /= dist;
        casts = dist > a.eps && dot(a.ns, to_light) > 0.0;
        if (casts && L.intensity_unit.w == 0.0) {
          falloff = hr_light_falloff(falloff_params(L), to_light, dist);
          casts = falloff > 0.0;
        }
        dist -= a.eps;
      }
      if (casts) {
        contrib[n] = r.weight * (L.intensity_unit.xyz * falloff * surface_term(a, gltf, to_light));
        ray_to[n] = vec4(to_light, dist);
        ++n;
      }
    }
    uint first = 0u;
    bool queued = false;
    if (kShadowQueue) {
      uint total = subgroupAdd(uint(n)), before = subgroupExclusiveAdd(uint(n)), base = 0u;
      if (subgroupElect() && total > 0u) base = atomicAdd(shadow_head.x, total);
      first = subgroupBroadcastFirst(base) + before;
      queued = n > 0 && first + uint(n) <= shadow_head.z;
    }
    for (int q = 0; q < n; ++q) {
      ++shadow_rays;
      if (kWaveStage != HR_WAVE_OFF) {  // traced by the wavefront's shadow stage, its term added after
        whitted_wave_shadow(a.above, ray_to[q], contrib[q]);
        continue;
      }
      if (queued) {
        uint at = first + uint(q);
        shadow_queue[at] = GpuShadowRay(vec4(a.above, ray_to[q].w), vec4(ray_to[q].xyz, 0.0));
        shadow_terms[at] = vec4(contrib[q] / float(spp), uintBitsToFloat(q == 0 ? last_run << 4 | uint(n) : 0u));
        continue;
      }
      Hit sh;
      if (!trace_ray(a.above, ray_to[q].xyz, 0.0, ray_to[q].w, true, sh)) c += contrib[q];
    }
    if (queued) last_run = first;
  }
  return c;
}

// The hit `h` of `r` resolved: its surface, material and maps (read at the
// footprint `optic` away), normals turned toward the ray.
Shaded shaded_hit(Pending r, Hit h, float optic, float eps) {
  Shaded a;
  a.eps = eps;
  a.s = surface_of(r.o, r.d, h);
  a.m = materials[a.s.material];
  MappedMaterial mm = mapped_material(a.m, h, optic, a.s);
  a.colour = mm.colour, a.emission = mm.emission, a.pbr = mm.pbr, a.highlight = mm.highlight;
  a.view = -r.d;
  a.front = dot(a.s.ng, a.view) >= 0.0;
  a.ng = a.front ? a.s.ng : -a.s.ng, a.ns = a.front ? a.s.ns : -a.s.ns;
  a.above = a.s.p + a.ng * eps;
  return a;
}

// What a hit `h` of `r` shows with Whitted's light added to `c` (the
// caller adds the background where `r` meets nothing): its surface shaded, its
// secondary rays pushed on ray_stack, its shadow rays traced (in the
// wavefront, written for the shadow stage: their terms added later). An
// eye ray's hit in the first sample writes the pixel's AOVs and sets
// `first_hit`.
void whitted_hit(Pending r, Hit h, float optic, int i, int j, bool first_sample, vec4 line_sign, float eps, int spp,
                 int max_depth, int aovs, inout bool first_hit, inout uvec4 rays, inout uint last_run, inout vec3 c) {
  uint shadow_rays = rays.y, reflected_rays = rays.z, refracted_rays = rays.w;
  Shaded a = shaded_hit(r, h, optic, eps);
  if (r.depth == 1 && first_sample) {
    first_hit = true;
    if (aovs != 0) write_hit_aovs(i, j, line_sign.xyz, a.s, a.m, MappedMaterial(a.colour, a.emission, a.pbr, a.highlight), line_sign.w * h.t);
  }
  if (kTachyon && int(a.m.emission_model.w) == HR_MODEL_TACHYON) {
    c += shade_tachyon(r, h, a, optic, max_depth, shadow_rays, reflected_rays, refracted_rays);
  } else {
    bool gltf = kGltf && int(a.m.emission_model.w) == HR_MODEL_GLTF;
    if (r.depth < max_depth) push_secondary_rays(r, a, gltf, reflected_rays, refracted_rays);
    c += r.weight * ((gltf ? vec3(0.0) : F.ambient.xyz * a.colour * a.m.colour_kd.w) + a.emission);  // glTF: no ambient
    c += shade_lights(r, a, gltf, spp, shadow_rays, last_run);
  }
  rays.yzw = uvec3(shadow_rays, reflected_rays, refracted_rays);
}

// Sample k of pixel (i, j) with Whitted's light: its ray tree walked depth
// first. Sets `first_hit` where the first sample's eye ray met something
// (whose AOVs it writes there, so that none stays live across the
// traversals after).
vec3 whitted_sample(int i, int j, int k, float eps, int spp, int max_depth, int aovs, inout bool first_hit, inout uvec4 rays,
                    inout uint last_run) {
  vec2 uv = sample_offset(F.tile.x + i, F.tile.y + j, k);  // the image's pixel: a quilt's, not its view's
  EyeRay e = eye_ray(i, j, uv);
  vec3 c = F.background.xyz;
  if (e.empty_aimed) ++rays.x;  // an empty scene: the CPU counts the ray it traces through nothing
  if (e.traced) {
    ray_sp = 0;
    ray_stack[ray_sp++] = Pending(e.o, e.d, vec3(1.0), 1);
    c = vec3(0.0);
    ++rays.x;
    while (ray_sp > 0) {
      Pending r = ray_stack[--ray_sp];
      log_kind = uint(r.depth);
      bool primary = r.depth == 1;
      Hit h;
      if (!trace_ray(r.o, r.d, primary ? e.tmin : 0.0, primary ? e.tmax : kInf, false, h)) {
        c += r.weight * F.background.xyz;
        continue;
      }
      whitted_hit(r, h, h.t + (primary ? e.optic0 : 0.0), i, j, k == 0, vec4(e.line_dir, e.t_sign), eps, spp, max_depth, aovs,
                  first_hit, rays, last_run, c);
    }
  }
  return c;
}

#include "whitted_wavefront.glsl"

// A pixel's colour written: one channel of a panel's packed pixel
// (display_renderer.cpp, pack_subpixels), else its three.
void write_colour(int i, int j, vec3 colour) {
  if (kPanel && F.panel_kind.x == 3) {
    int k = i % 3, ch = F.panel_kind.y != 0 ? k : 2 - k;
    colour_out[out_pixel(i / 3, j) * 3u + uint(ch)] = colour[ch];
  } else {
    uint pixel = out_pixel(i, j);
    colour_out[pixel * 3u + 0u] = colour.x;
    colour_out[pixel * 3u + 1u] = colour.y;
    colour_out[pixel * 3u + 2u] = colour.z;
  }
}

void main() {
#if defined(HR_SHADE_KERNEL)
  wave_main();  // the wavefront's shade stage alone, a SPIR-V of its own (as below)
#elif defined(HR_TRAVERSAL_KERNELS)
  // The wavefront's small kernels alone (its traversals, the dispatches'
  // sizes, its start and finish), a SPIR-V of their own (CMakeLists.txt):
  // lavapipe inlines a module's whole call graph before it folds the
  // stage's branches away, about 8 s a pipeline whatever the stage, and a
  // kernel of the whole module costs more to run (a band's start and finish
  // took 0.33 s of a 0.57 s frame there, design/gpu.md).
  wave_small_kernel();
#else
  if (kPath) {
    path_main();
  } else if (kShadowPass == 1) {
    shadow_pass();
  } else if (kShadowPass == 2) {
    shadow_resolve();
  } else {
    int i = int(gl_GlobalInvocationID.x), j = band.row0 + int(gl_GlobalInvocationID.y);
    if (i < F.size.x && int(gl_GlobalInvocationID.y) < band.rows) {
      log_pixel = ivec2(i, j);
      uvec4 rays = uvec4(0u);  // eye, shadow, reflected, refracted
      uint last_run = 0x0fffffffu;  // the pixel's last run of queued shadow rays (none: past any capacity)
      float eps = F.clip.z;
      int spp = F.mode.w, max_depth = F.counts.z, aovs = F.counts.y;
      vec3 sum = vec3(0.0);
      bool first_hit = false;
      for (int k = 0; k < spp; ++k) sum += whitted_sample(i, j, k, eps, spp, max_depth, aovs, first_hit, rays, last_run);
      write_colour(i, j, sum / float(spp));
      if (kShadowQueue) shadow_last[out_pixel(i, j)] = last_run;
      if (aovs != 0 && !first_hit) write_miss_aovs(i, j);  // background (a hit's were written where it was met)
      add_counts(rays);
    }
  }
#endif
}

// This invocation's work added to its band's counters: nodes visited and
// primitives tested, and `rays` by kind (eye, shadow, reflected,
// refracted). One atomic per subgroup, whatever its size (NVIDIA 32,
// lavapipe 8).
void add_counts(uvec4 rays) {
  uvec2 work = subgroupAdd(uvec2(visited, tested));
  uvec4 kinds = subgroupAdd(rays);
  if (subgroupElect()) {
    // Spread over HR_COUNT_SLOTS pairs per band, so that the subgroups of
    // a row do not all wait on one address.
    int at = 2 * (band.index * HR_COUNT_SLOTS + int(gl_WorkGroupID.x % uint(HR_COUNT_SLOTS)));
    atomicAdd(band_counts[at].x, work.x);
    atomicAdd(band_counts[at].y, work.y);
    atomicAdd(band_counts[at + 1].x, kinds.x);
    atomicAdd(band_counts[at + 1].y, kinds.y);
    atomicAdd(band_counts[at + 1].z, kinds.z);
    atomicAdd(band_counts[at + 1].w, kinds.w);
  }
}
