// holoray/render: the path integrator (RenderSettings::integrator = path):
// unidirectional path tracing with next-event estimation and multiple
// importance sampling (Veach 1997, ch. 9; pbrt-v4's PathIntegrator), Russian
// roulette after the third bounce, on the CPU over Embree. The integrator
// itself is render/path_integrator.h, the text the GPU kernel compiles too
// (gpu/shaders/path.glsl); path_tracer.cpp gives it the CPU's scene through
// its hooks. What it computes per vertex (the BSDF, its sampling, the
// lights' falloff, the environment's mapping, the sampler) is shading/.
//
// Light it sees: the scene's point, spot and directional lights (delta
// lights, sampled every vertex), the environment (RenderSettings::
// environment, importance-sampled and MIS-weighted against the BSDF; the
// scene's background colour when none is given), and emissive surfaces
// (glTF emission, Tachyon's light spheres), reached by the BSDF's rays.
#pragma once

#include <cstdint>

#include "render/ray_counts.hpp"
#include "render/render_context.hpp"
#include "render/renderer.hpp"
#include "shading/sampler.h"

namespace holoray {

/// Radiance (linear RGB) arriving along `ray` (world; the eye ray of a
/// pixel sample), its random numbers from `sampler` (its first pair is the
/// caller's: the pixel position). `first` (optional) gets the first hit's
/// surface and `first_t` its distance along the ray; `hit_found` says
/// whether there was one. Counts its rays into `counts`.
Vec3 path_radiance(const RenderContext& scene, const Ray& ray, shading::HrSampler& sampler, RayCounts& counts,
                   SurfacePoint* first = nullptr, Hit* first_hit = nullptr, bool* hit_found = nullptr);

/// What a ray that left the scene sees under the path integrator: the
/// environment along `dir` (world, unit), else the background colour.
Vec3 path_escape(const RenderContext& scene, const Vec3& dir);

/// Sample 0's first hit in a pixel, for its AOVs (`found` false: none).
struct PathFirstHit {
  bool found = false;
  PrimaryRay primary;  ///< the ray that met it
  Hit hit;
  SurfacePoint surface;
};

/// The sum of the `spp` samples of pixel (i, j) under the path integrator,
/// placed in it by the pixel's sampler (shading/sampler.h: sample 0 at the
/// centre). `primary(u, v, pr, escape)` gives the pixel's primary ray at
/// (u, v) in the pixel, or false with `escape` the direction (world, unit)
/// its light would arrive along when its line misses the scene: every
/// camera's renderer says only that. `first` gets sample 0's hit.
template <class Primary>
Vec3 path_pixel_sum(const RenderContext& scene, int i, int j, int spp, RayCounts& counts, Primary&& primary,
                    PathFirstHit& first) {
  Vec3 sum;
  first = PathFirstHit{};
  const uint32_t seed = shading::hr_pixel_seed(static_cast<uint32_t>(i), static_cast<uint32_t>(j), scene.settings().sample_salt);
  const shading::vec2 shift = shading::hr_pixel_shift(seed);
  for (int k = 0; k < spp; ++k) {
    shading::HrSampler sampler = shading::hr_sampler(seed, static_cast<uint32_t>(k));
    const shading::vec2 u = shading::hr_pixel_position(sampler, shift);
    PrimaryRay pr;
    Vec3 escape;
    if (!primary(u.x, u.y, pr, escape)) {
      sum += path_escape(scene, escape);
      continue;
    }
    ++counts.eye;
    SurfacePoint sp;
    Hit hit;
    bool found = false;
    sum += path_radiance(scene, pr.ray, sampler, counts, &sp, &hit, &found);
    if (k == 0 && found) first = PathFirstHit{true, pr, hit, sp};
  }
  return sum;
}

}  // namespace holoray
