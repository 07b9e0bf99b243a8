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
#include "render/path_records.h"
#include "shading/sampler.h"

namespace holoray {

/// One path sample's first vertex x and the light it gathered there, kept
/// so that another eye that sees x can take the same sample
/// (render/view_sharing.hpp). The sample's radiance toward its own eye is
/// emission + sum_k f(wo, dir[k]) incoming[k] (f the BSDF at x times
/// |cos|, shading/bsdf.h): next-event estimation's terms, each already
/// MIS-weighted and unblocked, and the bounce's, whose incoming light is
/// the rest of the path over the BSDF's density. Evaluated with another
/// eye's wo, the same sum estimates x's radiance toward that eye without
/// bias: the weights and densities do not depend on wo (Veach 1997, 9.2).
struct FirstVertexRecord {
  static constexpr int kMaxTerms = 16;
  /// False: nothing to share (no surface met, a light's sphere, a delta
  /// lobe at x, whose light goes one way only, or more than kMaxTerms terms).
  bool shareable = false;
  /// The BSDF at x is Lambert's alone: its radiance is `radiance` toward any eye.
  bool lambert = false;
  /// x's shading normal faces the eye (else the geometric one stood in:
  /// hr_path_vertex), which another eye must share for `vertex`'s frame.
  bool shading_normal = false;
  Vec3 radiance;
  Hit hit;
  SurfacePoint surface;
  shading::HrPathVertex vertex;  ///< x as the integrator saw it: its frame and BSDF (wo: this eye's)
  Vec3 eye_dir;   ///< the sample's eye ray direction (world, unit)
  Vec3 emission;  ///< what x emits toward the eye (the same toward any)
  int terms = 0;
  shading::vec3 dir_local[kMaxTerms];  ///< toward the light, in `vertex`'s frame
  Vec3 incoming[kMaxTerms];            ///< its light over f (linear RGB)
  // While the path is traced: the next-event terms (f times the light,
  // their directions in the world), the bounce's direction, and whether
  // the terms overflowed.
  Vec3 dir[kMaxTerms];
  Vec3 bounce_dir;
  bool bounced = false, overflow = false, sphere = false;

  /// Ready for the next path: what the last one left is forgotten.
  void clear(const Vec3& eye) {
    shareable = lambert = bounced = overflow = sphere = false;
    terms = 0;
    emission = {};
    eye_dir = eye;
  }
};

/// Radiance (linear RGB) arriving along `ray` (world; the eye ray of a
/// pixel sample), its random numbers from `sampler` (its first pair is the
/// caller's: the pixel position). `first` (optional) gets the first hit's
/// surface and `first_t` its distance along the ray; `hit_found` says
/// whether there was one. Counts its rays into `counts`. `record`
/// (optional) gets the first vertex's light (FirstVertexRecord).
Vec3 path_radiance(const RenderContext& scene, const Ray& ray, shading::HrSampler& sampler, RayCounts& counts,
                   SurfacePoint* first = nullptr, Hit* first_hit = nullptr, bool* hit_found = nullptr,
                   FirstVertexRecord* record = nullptr);

/// The radiance a shareable `record`'s sample sends from its x along
/// `dir` (world, unit: from another eye toward x): its terms with the BSDF
/// evaluated for that eye. False where that eye sees x's other side (the
/// terms were gathered on the record's side).
bool path_radiance_toward(const RenderContext& scene, const FirstVertexRecord& record, const Vec3& dir, Vec3& out);

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

/// Each of the `spp` samples of pixel (i, j) under the path integrator,
/// placed in it by the pixel's sampler (shading/sampler.h: sample 0 at the
/// centre), given to `sample(c)` as its radiance c (linear RGB) in sample
/// order. `primary(u, v, pr, escape)` gives the pixel's primary ray at
/// (u, v) in the pixel, or false with `escape` the direction (world, unit)
/// its light would arrive along when its line misses the scene: every
/// camera's renderer says only that. `first` gets sample 0's hit.
/// `record` (optional) holds, while `sample` runs, that sample's first
/// vertex (FirstVertexRecord; not shareable for a line that missed).
template <class Primary, class Sample>
void path_pixel_samples(const RenderContext& scene, int i, int j, int spp, RayCounts& counts, Primary&& primary,
                        PathFirstHit& first, FirstVertexRecord* record, Sample&& sample) {
  first = PathFirstHit{};
  const uint32_t seed = shading::hr_pixel_seed(static_cast<uint32_t>(i), static_cast<uint32_t>(j), scene.settings().sample_salt);
  const shading::vec2 shift = shading::hr_pixel_shift(seed);
  for (int k = 0; k < spp; ++k) {
    shading::HrSampler sampler = shading::hr_sampler(seed, static_cast<uint32_t>(k));
    const shading::vec2 u = shading::hr_pixel_position(sampler, shift);
    PrimaryRay pr;
    Vec3 escape;
    if (!primary(u.x, u.y, pr, escape)) {
      if (record) record->clear(escape);
      sample(path_escape(scene, escape));
      continue;
    }
    ++counts.eye;
    SurfacePoint sp;
    Hit hit;
    bool found = false;
    sample(path_radiance(scene, pr.ray, sampler, counts, &sp, &hit, &found, record));
    if (k == 0 && found) first = PathFirstHit{true, pr, hit, sp};
  }
}

/// The sum of path_pixel_samples' samples.
template <class Primary>
Vec3 path_pixel_sum(const RenderContext& scene, int i, int j, int spp, RayCounts& counts, Primary&& primary,
                    PathFirstHit& first) {
  Vec3 sum;
  path_pixel_samples(scene, i, j, spp, counts, primary, first, nullptr, [&](const Vec3& c) { sum += c; });
  return sum;
}

}  // namespace holoray
