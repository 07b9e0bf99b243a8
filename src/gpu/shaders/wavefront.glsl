// holoray/gpu: the path integrator as a wavefront (issue 71; Laine, Karras
// and Aila 2013, "Megakernels considered harmful"; pbrt-v4's GPU
// integrator). The same shared integrator as path_main
// (render/path_integrator.h), cut at its traversals into stages, each a
// dispatch over queues in device memory (kWaveStage: the two traversals a
// pipeline each, the three others one between them, layout.h), recorded by
// gpu/wavefront.cpp for one band of rows and one sample:
//
//   start                 each pixel's eye ray; a path that meets the
//                         scene's box is queued for its first vertex
//   for each vertex:
//     extend              the queued paths' rays to their nearest hits,
//                         lanes fetching the queue's next ray as theirs
//                         ends (Aila and Laine 2009), so that none waits
//                         on a longer walk
//     shade               each hit through hr_path_step: what the path
//                         met added, its shadow rays written (not traced),
//                         the next ray drawn and the path queued for the
//                         next vertex
//     shadow              the shadow rays, any hit, lanes fetching; a
//                         blocked ray's term zeroed
//   finish                each path's last shadow terms added, the sample
//                         written as path_main writes it
//
// A path's shadow terms are added where the next shading (or the finish)
// begins, in the order they were made, times the throughput they were made
// with: the sums the megakernel makes, in its order, so the image is the
// same run to run and the same as the megakernel's to float rounding. Only
// the paths move through the queues; a path's state stays at its place in
// the band (GpuWavePath). Included by path.glsl. Whitted's integrator runs
// on the same traversals and queues (whitted_wavefront.glsl).

// The paths queued for vertex `depth` (its head), and where that queue's
// entries lie: the queues of consecutive vertices take turns. Whitted's
// steps outnumber the heads where its trees branch: a head serves every
// HR_WAVE_VERTICES-th step, zeroed two steps before its turn
// (wave_dispatch_sizes).
uint wave_path_head(int depth) { return uint(depth % HR_WAVE_VERTICES); }
uint wave_queue_base(int depth) { return uint(depth & 1) * uint(band.capacity); }

// The most shadow rays a vertex makes (hr_path_direct_light: one a light,
// one an area light, one for the environment, one for the emitters;
// Whitted's: one a light).
int wave_shadows_a_vertex() {
  if (!kPath) return F.counts.x;
  return F.counts.x + F.path_counts.x + (F.path_flags.w != 0 ? 1 : 0) + (F.path_counts.y > 0 ? 1 : 0);
}

// The path at place p of this band: its pixel.
ivec2 wave_pixel(uint p) { return ivec2(int(p % uint(F.size.x)), band.row0 + int(p / uint(F.size.x))); }

// This invocation's place in a stage over the band's paths (or a queue's
// entries): rows of the band's width, as the pixel passes are dispatched.
uint wave_invocation() { return gl_GlobalInvocationID.y * uint(F.size.x) + gl_GlobalInvocationID.x; }

// This invocation's pixel (i, j) in a stage over the band (start,
// finish) and its place p; false past the band's pixels.
bool wave_band_pixel(out int i, out int j, out uint p) {
  i = int(gl_GlobalInvocationID.x), j = band.row0 + int(gl_GlobalInvocationID.y);
  p = wave_invocation();
  return i < F.size.x && int(gl_GlobalInvocationID.y) < band.rows;
}

// The hit that the extend stage found for path p (wavefront.glsl's
// hr_path_trace): false where its ray met nothing.
bool wave_hit(uint p, out Hit h) {
  vec4 a = wave_hits[2u * p], b = wave_hits[2u * p + 1u];
  h.t = a.x, h.ref = floatBitsToUint(a.y), h.u = a.z, h.v = a.w, h.ng = b.xyz;
  return h.ref != 0xffffffffu;
}

// A shadow ray of the vertex being shaded written to its path's own
// place (its terms are summed in this order), not traced: hr_path_unblocked
// in the shade stage. Its term is added later, if nothing blocks it.
vec3 wave_shadow(inout HrPathDevice d, vec3 from, vec3 dir, float tmax, vec3 term) {
  uint at = d.wave_path * uint(wave_shadows_a_vertex()) + uint(d.wave_shadows++);
  wave_shadows[at].origin_tmax = vec4(from, tmax);
  wave_shadows[at].dir = vec4(dir, 0.0);
  wave_shadows[at].term = vec4(term, 0.0);
  return vec3(0.0);
}

// Entries `count` each of this subgroup's lanes adds to queue `head` of
// `queue` (one atomic a subgroup): the first index of this lane's.
uint wave_append(uint head, uint count) {
  uint total = subgroupAdd(count), base = 0u;
  if (subgroupElect() && total > 0u) base = atomicAdd(wave_heads[head].x, total);
  return subgroupBroadcastFirst(base) + subgroupExclusiveAdd(count);
}

// A path as the shading stages hold it: the integrator's state, the
// device's part of it (its pixel, AOVs, ray counts), its sampler, and its
// shadow rays in flight with the throughput they were made with.
struct WavePath {
  HrPathState s;
  HrPathDevice d;
  HrSampler rng;
  vec3 shadow_throughput;
  int shadows;
};

// Path p as GpuWavePath keeps it.
WavePath wave_load(uint p) {
  GpuWavePath g = wave_paths[p];
  WavePath w;
  w.s.o = g.o_tmin.xyz, w.s.tmin = g.o_tmin.w, w.s.dir = g.dir_tmax.xyz, w.s.tmax = g.dir_tmax.w;
  w.s.radiance = g.radiance_pdf.xyz, w.s.last_pdf = g.radiance_pdf.w;
  w.s.throughput = g.throughput_depth.xyz, w.s.depth = floatBitsToInt(g.throughput_depth.w);
  uint flags = floatBitsToUint(g.shadow_flags.w);
  w.s.specular = (flags & 1u) != 0u;
  w.shadow_throughput = g.shadow_flags.xyz;
  w.shadows = int(flags >> 8);
  w.rng.seed = g.rng.x, w.rng.index = g.rng.y, w.rng.dimension = g.rng.z;
  w.d.pixel = wave_pixel(p);
  w.d.aovs_now = band.sample_index == 0 && F.counts.y != 0;
  w.d.optic0 = uintBitsToFloat(g.rng.w);
  w.d.line_dir = g.line_sign.xyz;
  w.d.t_sign = g.line_sign.w;
  w.d.first_hit = (flags & 2u) != 0u;
  w.d.rays = uvec4(0u);
  w.d.wave_path = p;
  w.d.wave_shadows = 0;
  return w;
}

void wave_store(uint p, WavePath w) {
  uint flags = (w.s.specular ? 1u : 0u) | (w.d.first_hit ? 2u : 0u) | (uint(w.shadows) << 8);
  wave_paths[p].o_tmin = vec4(w.s.o, w.s.tmin);
  wave_paths[p].dir_tmax = vec4(w.s.dir, w.s.tmax);
  wave_paths[p].radiance_pdf = vec4(w.s.radiance, w.s.last_pdf);
  wave_paths[p].throughput_depth = vec4(w.s.throughput, intBitsToFloat(w.s.depth));
  wave_paths[p].shadow_flags = vec4(w.shadow_throughput, uintBitsToFloat(flags));
  wave_paths[p].rng = uvec4(w.rng.seed, w.rng.index, w.rng.dimension, floatBitsToUint(w.d.optic0));
  wave_paths[p].line_sign = vec4(w.d.line_dir, w.d.t_sign);
}

// The terms of path p's `shadows` shadow rays in flight added to its light,
// each zeroed if blocked, summed in the order made and then weighted by the
// throughput they were made with (hr_path_step's sum, in its order).
vec3 wave_shadow_light(uint p, int shadows, vec3 shadow_throughput) {
  if (shadows == 0) return vec3(0.0);
  uint first = p * uint(wave_shadows_a_vertex());
  vec3 sum = vec3(0.0);
  for (int k = 0; k < shadows; ++k) sum += wave_shadows[first + uint(k)].term.xyz;
  return shadow_throughput * sum;
}

// Stage start: pixel (i, j)'s eye ray for sample band.sample_index, as
// path_main draws it; a ray through the scene's box queued for vertex 1,
// any other's sample its background.
void wave_start() {
  int i, j;
  uint p;
  bool queued = false;
  if (wave_band_pixel(i, j, p)) {
    WavePath w;
    uint seed = hr_pixel_seed(uint(F.tile.x + i), uint(F.tile.y + j), floatBitsToUint(F.env_turn.z));
    w.rng = hr_sampler(seed, uint(band.sample_index));
    vec2 uv = hr_pixel_position(w.rng, hr_pixel_shift(seed));
    EyeRay e = eye_ray(i, j, uv);
    w.d.optic0 = e.optic0, w.d.line_dir = e.line_dir, w.d.t_sign = e.t_sign, w.d.first_hit = false;
    w.s = hr_path_start(e.o, e.d, e.tmin, e.tmax);
    if (!e.traced) w.s.radiance = path_escape(e.d);
    w.shadow_throughput = vec3(0.0), w.shadows = 0;
    queued = e.traced;
    wave_store(p, w);
    add_counts(uvec4(e.traced || e.empty_aimed ? 1u : 0u, 0u, 0u, 0u));
  }
  uint at = wave_append(wave_path_head(1), queued ? 1u : 0u);
  if (queued) wave_queue[wave_queue_base(1) + at] = p;
}

// The workgroups a dispatch of `invocations` takes, as (x, y, 1) with x
// within Vulkan's guaranteed 65535.
uvec4 wave_groups(uint invocations) {
  uint groups = max(1u, (invocations + gl_WorkGroupSize.x * gl_WorkGroupSize.y - 1u) / (gl_WorkGroupSize.x * gl_WorkGroupSize.y));
  uint x = min(groups, 65535u);
  return uvec4(x, (groups + x - 1u) / x, 1u, 0u);
}

// The sizes of the vertex's dispatches (one invocation, HR_WAVE_ARGS): the
// extend and shade stages' from its paths queued, the shadow stage's from
// its shadow rays (0 before its shading: run again after it). A dispatch
// the size of its queue, not of the band: the deep vertices hold few paths.
void wave_dispatch_sizes() {
  if (gl_GlobalInvocationID.x != 0u || gl_GlobalInvocationID.y != 0u) return;
  // The heads the vertex after next fills, free since their last turn.
  wave_heads[wave_path_head(band.depth + 2)] = uvec4(0u);
  wave_heads[HR_WAVE_VERTICES + (band.depth + 1) % HR_WAVE_VERTICES] = uvec4(0u);
  uint paths = wave_heads[wave_path_head(band.depth)].x, shadows = wave_heads[wave_shadow_head()].x;
  uint per_lane = uint(kRaysPerLane);
  wave_args[0] = wave_groups((paths + per_lane - 1u) / per_lane);
  wave_args[1] = wave_groups(paths);
  wave_args[2] = wave_groups((shadows + per_lane - 1u) / per_lane);
}

// A dispatch's invocation, numbered across its workgroups (any grid).
uint wave_flat_invocation() {
  return (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * (gl_WorkGroupSize.x * gl_WorkGroupSize.y) + gl_LocalInvocationIndex;
}

// Stage extend: the paths queued for vertex band.depth each to its ray's
// nearest hit, written for the shade stage. Each lane walks one ray a node
// a step (walk_bvh's order, so the same hit), and lanes whose ray is done
// take the queue's next together (one atomic a subgroup), at most
// kRaysPerLane rays a lane (lavapipe's loop cap); the loop's one
// exit is in its condition (design/gpu.md: lavapipe and loops).
void wave_extend() {
  uint head = wave_path_head(band.depth), base_at = wave_queue_base(band.depth);
  uint queued = wave_heads[head].x;
  uint budget = uint(kRaysPerLane) * gl_SubgroupSize, taken = 0u;
  bool live = false, drained = false, found = false, any = false;
  vec3 o = vec3(0.0), d = vec3(0.0), inv = vec3(0.0);
  ShearedRay sr = sheared(vec3(0.0, 0.0, 1.0));
  float tmin = 0.0;
  Hit h;
  h.t = 0.0, h.ref = 0xffffffffu, h.u = 0.0, h.v = 0.0, h.ng = vec3(0.0);
  uint p = 0u;
  int stack[HR_STACK];
  int sp = 0, next = -1;
  bool more = true;
  while (more) {
    uvec4 want = subgroupBallot(!live);
    uint k = min(subgroupBallotBitCount(want), budget - taken);
    if (k > 0u && !drained) {
      uint base = 0u;
      if (subgroupElect()) base = atomicAdd(wave_heads[head].y, k);
      base = subgroupBroadcastFirst(base);
      taken += k;
      drained = base + k >= queued;
      uint rank = subgroupBallotExclusiveBitCount(want);
      if (!live && rank < k && base + rank < queued) {
        p = wave_queue[base_at + base + rank];
        vec4 o_tmin = wave_paths[p].o_tmin, dir_tmax = wave_paths[p].dir_tmax;
        o = o_tmin.xyz, tmin = o_tmin.w, d = dir_tmax.xyz, inv = safe_inverse(d), sr = sheared(d);
        h.t = dir_tmax.w, h.ref = 0xffffffffu, h.u = 0.0, h.v = 0.0, h.ng = vec3(0.0);
        live = true, found = false, sp = 0, next = 0;
      }
    }
    if (live) {
      if (kCountWork) ++visited;
      int order[kNodeWidth];
      float near_t[kNodeWidth];
      int m = 0;
      GpuNode n = nodes[next * kNodeRecords];
      HR_MEET_CHILDREN(n, {})
      if (kWideBvh) {
        n = nodes[next * kNodeRecords + 1];
        HR_MEET_CHILDREN(n, {})
      }
      for (int c = 0; c + 1 < m && sp < HR_STACK; ++c) stack[sp++] = order[c];
      next = m > 0 ? order[m - 1] : sp > 0 ? stack[--sp] : -1;
      if (next < 0) {
        wave_hits[2u * p] = vec4(h.t, uintBitsToFloat(found ? h.ref : 0xffffffffu), h.u, h.v);
        wave_hits[2u * p + 1u] = vec4(h.ng, 0.0);
        live = false;
      }
    }
    if (kCountWork) ++lane_steps;
    more = subgroupAny(live) || (!drained && taken < budget);
  }
  add_fetch_work();
}

// A shade stage's entry: the path (pixel) this invocation takes from the
// queue of vertex band.depth, if any is left for it.
bool wave_to_shade(out uint p) {
  uint q = wave_flat_invocation();
  p = 0u;
  if (q >= wave_heads[wave_path_head(band.depth)].x) return false;
  p = wave_queue[wave_queue_base(band.depth) + q];
  return true;
}

// A shade stage's exit: path p's `made` shadow rays (at its own places)
// queued for the shadow stage, and the path queued for the next vertex if
// it goes on (`more`). Every invocation of the dispatch calls it (the
// queues' subgroup operations); `queued` false: one that shaded nothing.
void wave_shaded(bool queued, uint p, uint made, bool more) {
  if (queued) {
    uint at = wave_append(wave_shadow_head(), made), first = p * uint(wave_shadows_a_vertex());
    for (uint k = 0u; k < made; ++k) wave_shadow_queue[at + k] = first + k;
  }
  uint at = wave_append(wave_path_head(band.depth + 1), more ? 1u : 0u);
  if (more) wave_queue[wave_queue_base(band.depth + 1) + at] = p;
}

// Stage shade: a path queued for vertex band.depth, its shadow rays of the
// vertex before added (their stage is done), then one step of the shared
// integrator at its hit; a path that goes on is queued for the next vertex.
void wave_shade() {
  uint p;
  bool queued = wave_to_shade(p), more = false;
  int made = 0;
  if (queued) {
    WavePath w = wave_load(p);
    log_pixel = w.d.pixel;
    w.s.radiance += wave_shadow_light(p, w.shadows, w.shadow_throughput);
    w.shadow_throughput = w.s.throughput;  // what this vertex's shadow terms take (hr_path_step changes it after)
    HrPathHit h;
    more = hr_path_step(w.d, w.s, h, w.rng);
    w.shadows = made = w.d.wave_shadows;
    wave_store(p, w);
    add_counts(w.d.rays);
  }
  wave_shaded(queued, p, uint(made), more);
}

// Stage finish: pixel (i, j)'s path (or Whitted's tree), ended, its last
// shadow terms added; its sample written as path_main writes it, and the
// miss AOVs where the eye ray met nothing.
void wave_finish() {
  int i, j;
  uint p;
  if (!wave_band_pixel(i, j, p)) return;
  WavePath w = wave_load(p);
  vec3 c = w.s.radiance + wave_shadow_light(p, w.shadows, w.shadow_throughput);
  if (w.d.aovs_now && !w.d.first_hit) write_miss_aovs(i, j);
  add_sample(i, j, c);
}

void whitted_wave_start();
void whitted_wave_shade();

// The kernels of the wavefront's small module (trace.comp's main under
// HR_TRAVERSAL_KERNELS): each its own pipeline.
void wave_small_kernel() {
  if (kWaveStage == HR_WAVE_EXTEND) wave_extend();
  else if (kWaveStage == HR_WAVE_ARGS) wave_dispatch_sizes();
  else if (kWaveStage == HR_WAVE_START && kPath) wave_start();
  else if (kWaveStage == HR_WAVE_START) whitted_wave_start();  // whitted_wavefront.glsl
  else if (kWaveStage == HR_WAVE_FINISH) wave_finish();
  else shadow_pass();
}

// The shade stage, the whole module's one wavefront kernel.
void wave_main() {
  if (kPath) wave_shade();
  else whitted_wave_shade();
}
