#include "render/shading.hpp"

#include <algorithm>
#include <cmath>

#include "render/shading_models.hpp"

namespace holoray {

namespace shading {

[[gnu::noinline]] double light_falloff(const PointLight& light, const Vec3& to_light, double dist) {
  if (light.kind == LightKind::directional) return 1;
  double a = 1;
  if (light.kc != 1 || light.kl != 0 || light.kq != 0) a = 1 / (light.kc + (light.kl + light.kq * dist) * dist);
  if (light.range > 0) {
    const double x2 = (dist / light.range) * (dist / light.range);
    const double w = std::clamp(1 - x2 * x2, 0.0, 1.0);
    a *= w * w;
  }
  if (light.kind == LightKind::spot) {
    const double cos_a = -dot(light.direction, to_light);
    if (light.smooth_cone) {
      const double cos_outer = light.cos_fall_end;
      const double t = std::clamp((cos_a - cos_outer) / std::fmax(1e-3, light.cos_fall_start - cos_outer), 0.0, 1.0);
      a *= t * t;
    } else {
      const double angle = std::acos(std::clamp(cos_a, -1.0, 1.0));
      if (angle > light.fall_end) a = 0;
      else if (angle > light.fall_start) a *= 1 - (angle - light.fall_start) / (light.fall_end - light.fall_start);
    }
  }
  return a;
}


}  // namespace shading

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
