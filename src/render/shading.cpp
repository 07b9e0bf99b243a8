#include "render/shading.hpp"

#include <algorithm>
#include <cmath>

#include "render/shading_models.hpp"

namespace holoray {

using namespace shading;

Vec3 trace(const RenderContext& scene, const Ray& ray, int depth, RayCounts& counts) {
  Hit hit;
  if (!scene.accel().intersect(ray, hit)) return scene.background();
  return shade(scene, ray, scene.surface(ray, hit), depth, counts);
}

namespace {

// Adds mirror and transmitted light to `colour`, traced one ray at a time (incoherent).
void add_secondary(const RenderContext& scene, const Ray& ray, const SurfacePoint& sp, const HitFrame& f, int depth,
                   RayCounts& counts, Vec3& colour) {
  if (depth >= scene.max_depth()) return;
  const SecondaryRays s = secondary_rays(scene, ray, sp, f);
  if (s.mirror) {
    ++counts.reflected;
    colour += mul(trace(scene, s.mirror_ray, depth + 1, counts), s.mirror_weight);
  }
  if (s.transmit) {
    ++(s.transmit_reflects ? counts.reflected : counts.refracted);
    colour += mul(trace(scene, s.transmit_ray, depth + 1, counts), s.transmit_weight);
  }
}


}  // namespace

Vec3 shade(const RenderContext& scene, const Ray& ray, const SurfacePoint& sp, int depth, RayCounts& counts) {
  if (sp.material->model == ShadingModel::tachyon) return TachyonModel::shade(scene, ray, sp, depth, counts);
  const HitFrame f = frame_of(scene, ray, sp);
  Vec3 colour = ambient_term(scene, f);
  add_emission(scene, ray, sp, colour);
  const bool cached = scene.shadow_cache() != nullptr;
  const CellRef cell = cached ? cell_of(scene, sp) : CellRef::none();
  const auto& lights = scene.lights();
  for (size_t l = 0; l < lights.size(); ++l) {
    Ray shadow;
    double falloff;
    if (!shadow_ray(scene, f, sp, lights[l], shadow, falloff)) continue;
    int seen = cached ? cached_visibility(scene, f, sp, cell, static_cast<int>(l), shadow, counts) : -1;
    if (seen < 0) {
      ++counts.shadow;
      seen = !scene.accel().occluded(shadow);
    }
    if (seen) colour += light_contribution(f, sp, lights[l], shadow.dir, falloff);
  }
  add_secondary(scene, ray, sp, f, depth, counts, colour);
  return colour;
}

Vec3 shade_local(const RenderContext& scene, const Ray& ray, const SurfacePoint& sp, uint32_t lit, uint32_t trace,
                 RayCounts& counts) {
  const HitFrame f = frame_of(scene, ray, sp);
  Vec3 colour = ambient_term(scene, f);
  add_emission(scene, ray, sp, colour);
  const auto& lights = scene.lights();
  for (size_t l = 0; l < lights.size() && l < kMaxPartLights; ++l) {
    const bool traced = trace >> l & 1u;
    if (!traced && !(lit >> l & 1u)) continue;
    Ray shadow;
    double falloff;
    if (!shadow_ray(scene, f, sp, lights[l], shadow, falloff)) continue;
    if (traced) {
      ++counts.shadow;
      if (scene.accel().occluded(shadow)) continue;
    }
    colour += light_contribution(f, sp, lights[l], shadow.dir, falloff);
  }
  return colour;
}

Vec3 shade_secondary(const RenderContext& scene, const Ray& ray, const SurfacePoint& sp, int depth, RayCounts& counts) {
  Vec3 colour;
  add_secondary(scene, ray, sp, frame_of(scene, ray, sp), depth, counts, colour);
  return colour;
}

}  // namespace holoray
