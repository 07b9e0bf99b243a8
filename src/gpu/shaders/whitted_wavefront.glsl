// holoray/gpu: Whitted's integrator as a wavefront (issue 71), on the path
// integrator's stages and queues (wavefront.glsl): the extend, shadow and
// sizing kernels and the finish are the same; its start is its own, and its
// shade runs Whitted's shading, whitted_hit, the megakernel's own.
//
// A pixel's ray tree is walked depth first, as whitted_sample walks it:
// one ray of the tree a pixel at each step (band.depth counts steps, not
// depths), the rays still to trace on the pixel's own stack in device
// memory (wave_stack, the deepest entry last). At a step the shade stage
// adds the terms of the step before's unblocked shadow rays, shades its
// ray's hit (or adds the background where it met nothing), pushes what
// the hit sends on, and takes the top of the stack as the pixel's next
// ray, queued for the next step's extend. So a pixel's colour takes the
// megakernel's sums in the megakernel's order, and the lanes of the
// traversals fetch rays from every pixel still at work: none waits on a
// deeper tree. A step's rays are at most one a pixel, so the steps a band
// takes are the largest tree's rays: max_depth where no hit sends two
// rays on (a mirror and a refraction), else 2^max_depth - 1 at most
// (gpu/wavefront.cpp: whitted_steps).
//
// The pixel's state is a GpuWavePath: o_tmin and dir_tmax its next ray
// (what the extend stage reads), radiance_pdf its colour and (w, int
// bits) its stack's height, throughput_depth the ray's weight and depth,
// shadow_flags its shadow terms' weight (1: they carry the ray's own) and
// (w) its flags (2: the eye ray met something) and its shadow rays in
// flight << 8, rng.w the eye ray's optical offset and line_sign
// the eye ray's line and depth sign (its AOVs): what wave_finish, the path
// integrator's, reads to end the sample.

// The pixel being shaded (its place in the band) and the shadow rays its
// hit has written so far (whitted_wave_shadow, from shade_lights).
uint whitted_place = 0u;
int whitted_made = 0;

// A stack entry's place: its pixel's stack holds HR_WAVE_STACK_RAYS.
uint whitted_stack_at(uint p, int k) { return 3u * (p * uint(HR_WAVE_STACK_RAYS(F.counts.z)) + uint(k)); }

void whitted_wave_shadow(vec3 from, vec4 ray_to, vec3 term) {
  uint at = whitted_place * uint(wave_shadows_a_vertex()) + uint(whitted_made++);
  wave_shadows[at].origin_tmax = vec4(from, ray_to.w);
  wave_shadows[at].dir = vec4(ray_to.xyz, 0.0);
  wave_shadows[at].term = vec4(term, 0.0);
}

// Pixel p's next ray `r` written for the extend stage (a secondary ray:
// from 0, unbounded).
void whitted_next_ray(uint p, Pending r) {
  wave_paths[p].o_tmin = vec4(r.o, 0.0);
  wave_paths[p].dir_tmax = vec4(r.d, kInf);
  wave_paths[p].throughput_depth = vec4(r.weight, intBitsToFloat(r.depth));
}

// Stage start: pixel (i, j)'s eye ray for sample band.sample_index, as
// whitted_sample draws it; a ray that meets the scene's box queued for the
// first step, any other's colour the background.
void whitted_wave_start() {
  int i, j;
  uint p;
  bool queued = false;
  if (wave_band_pixel(i, j, p)) {
    vec2 uv = sample_offset(F.tile.x + i, F.tile.y + j, band.sample_index);
    EyeRay e = eye_ray(i, j, uv);
    queued = e.traced;
    uint eye_rays = (e.empty_aimed ? 1u : 0u) + (e.traced ? 1u : 0u);
    wave_paths[p].o_tmin = vec4(e.o, e.tmin);
    wave_paths[p].dir_tmax = vec4(e.d, e.tmax);
    wave_paths[p].radiance_pdf = vec4(e.traced ? vec3(0.0) : F.background.xyz, intBitsToFloat(0));
    wave_paths[p].throughput_depth = vec4(vec3(1.0), intBitsToFloat(1));
    wave_paths[p].shadow_flags = vec4(vec3(1.0), uintBitsToFloat(0u));  // shadow terms taken whole (wave_finish)
    wave_paths[p].rng.w = floatBitsToUint(e.optic0);
    wave_paths[p].line_sign = vec4(e.line_dir, e.t_sign);
    add_counts(uvec4(eye_rays, 0u, 0u, 0u));
  }
  uint at = wave_append(wave_path_head(1), queued ? 1u : 0u);
  if (queued) wave_queue[wave_queue_base(1) + at] = p;
}

// Stage shade (step band.depth): a pixel's ray of this step, its shadow
// terms of the step before added, then its hit shaded by whitted_hit (the
// background where it met nothing); the pixel's next ray, the last ray its
// hit pushed or else the top of its stack, queued for the next step.
void whitted_wave_shade() {
  uint p;
  bool queued = wave_to_shade(p), more = false;
  whitted_made = 0;
  if (queued) {
    GpuWavePath g = wave_paths[p];
    uint flags = floatBitsToUint(g.shadow_flags.w);
    vec3 c = g.radiance_pdf.xyz + wave_shadow_light(p, int(flags >> 8), vec3(1.0));  // shade_lights' sum
    int stacked = floatBitsToInt(g.radiance_pdf.w);
    bool first_hit = (flags & 2u) != 0u;
    Pending r = Pending(g.o_tmin.xyz, g.dir_tmax.xyz, g.throughput_depth.xyz, floatBitsToInt(g.throughput_depth.w));
    ivec2 pixel = wave_pixel(p);
    log_pixel = pixel;
    uvec4 rays = uvec4(0u);
    uint last_run = 0x0fffffffu;
    whitted_place = p, ray_sp = 0;
    Hit h;
    if (!wave_hit(p, h)) {
      c += r.weight * F.background.xyz;
    } else {
      float optic = h.t + (r.depth == 1 ? uintBitsToFloat(g.rng.w) : 0.0);
      whitted_hit(r, h, optic, pixel.x, pixel.y, band.sample_index == 0, g.line_sign, F.clip.z, F.mode.w, F.counts.z,
                  F.counts.y, first_hit, rays, last_run, c);
    }
    // Depth first: the hit's last ray pushed is traced next, its others go
    // on the pixel's stack, above the rays already there.
    if (ray_sp > 0) {
      for (int k = 0; k + 1 < ray_sp; ++k) {
        uint at = whitted_stack_at(p, stacked++);
        wave_stack[at] = vec4(ray_stack[k].o, intBitsToFloat(ray_stack[k].depth));
        wave_stack[at + 1u] = vec4(ray_stack[k].d, 0.0);
        wave_stack[at + 2u] = vec4(ray_stack[k].weight, 0.0);
      }
      whitted_next_ray(p, ray_stack[ray_sp - 1]);
      more = true;
    } else if (stacked > 0) {
      uint at = whitted_stack_at(p, --stacked);
      vec4 o_depth = wave_stack[at];
      whitted_next_ray(p, Pending(o_depth.xyz, wave_stack[at + 1u].xyz, wave_stack[at + 2u].xyz, floatBitsToInt(o_depth.w)));
      more = true;
    }
    wave_paths[p].radiance_pdf = vec4(c, intBitsToFloat(stacked));
    wave_paths[p].shadow_flags.w = uintBitsToFloat((first_hit ? 2u : 0u) | uint(whitted_made) << 8);
    add_counts(rays);
  }
  wave_shaded(queued, p, uint(whitted_made), more);
}
