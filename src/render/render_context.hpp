// holoray/render: a built scene as one render traces it (OSPRay's World and
// Renderer): the scene, shared and unchanged by the render, and what the
// render adds: the ray-tree depth, the shadow cache, the pixel footprint and
// the background. Two renders of one scene, through two cameras or with and
// without the cache (a shot's reference frames), are two contexts on it.
#pragma once

#include "render/render_scene.hpp"

namespace holoray {

class ShadowCache;     // render/shadow_cache.hpp
class EnvironmentMap;  // render/environment.hpp
class EmissiveTriangles;  // render/emitters.hpp

/// How light is computed: Whitted's recursive ray tracing (the paper's:
/// point lights, hard shadows, mirror and refraction rays) or path tracing
/// (render/path_tracer.hpp).
enum class Integrator { whitted, path };

/// What one render asks of a built scene.
struct RenderSettings {
  /// Ray-tree depth limit, eye ray = 1, from 1 to kDepthCap (16: past that a
  /// hall of mirrors costs 2^depth rays per pixel).
  int max_depth = kMaxRayDepth;
  /// Shadow visibility reuse (render/shadow_cache.hpp) built on this scene
  /// and synced to its motion, or null: every shadow ray traced. Not owned.
  const ShadowCache* shadow_cache = nullptr;
  PixelFootprint footprint;  ///< the MIP levels of mesh textures
  Vec3 background;           ///< what a ray that hits nothing sees (linear RGB)
  Integrator integrator = Integrator::whitted;
  /// The path integrator's environment, or null: the background colour,
  /// constant, lights the scene. Not owned.
  const EnvironmentMap* environment = nullptr;
  /// The path integrator's emissive surfaces, sampled as lights; null: they
  /// light the scene only where its rays meet them. Not owned.
  const EmissiveTriangles* emitters = nullptr;
  /// The path integrator leaves out the readers' stand-in headlight (the
  /// render has an environment of its own).
  bool skip_headlights = false;
  /// The path integrator shades glTF materials as Blender 3.x's Principled
  /// BSDF layers them (shading/bsdf.h, HrBsdf::principled), not as glTF's
  /// Appendix B: for scenes exported from Blender, compared with Cycles.
  bool principled = false;
  /// Mixed into every pixel's sampler seed: two renders with different
  /// salts draw unrelated samples (api::RenderOptions::seed; a shot's
  /// frames take AnimateOptions::seed, plus the frame's number where the seed
  /// is animated, as Cycles').
  uint32_t sample_salt = 0;
};

/// The settings a scene's files ask for: their depth limit and background,
/// no cache, the finest texture level.
inline RenderSettings file_settings(const RenderScene& scene) {
  RenderSettings s;
  s.max_depth = scene.file_max_depth();
  s.background = scene.background();
  return s;
}

/// The scene and one render's settings: what the tracing and shading read.
/// Cheap to copy; the scene must outlive it.
class RenderContext {
 public:
  RenderContext(const RenderScene& scene, const RenderSettings& settings) : scene_(&scene), settings_(settings) {}
  /// The scene rendered as its files ask (file_settings): a still without
  /// options, as the tests and benchmarks render one.
  RenderContext(const RenderScene& scene) : RenderContext(scene, file_settings(scene)) {}  // NOLINT: implicit on purpose

  const RenderScene& scene() const { return *scene_; }
  const RenderSettings& settings() const { return settings_; }

  // The render's.
  int max_depth() const { return settings_.max_depth; }
  const ShadowCache* shadow_cache() const { return settings_.shadow_cache; }
  const Vec3& background() const { return settings_.background; }
  SurfacePoint surface(const Ray& ray, const Hit& hit) const { return scene_->surface(ray, hit, settings_.footprint); }
  Vec3 emission(const SurfacePoint& sp, double distance) const { return scene_->emission(sp, distance, settings_.footprint); }

  // The scene's (RenderScene).
  const AccelScene& accel() const { return scene_->accel(); }
  const std::vector<PointLight>& lights() const { return scene_->lights(); }
  Vec3 surface_colour(const SurfacePoint& sp, double optic_dist) const { return scene_->surface_colour(sp, optic_dist); }
  bool has_tachyon_materials() const { return scene_->has_tachyon_materials(); }
  bool has_tachyon_transparency() const { return scene_->has_tachyon_transparency(); }
  bool only_plain_nff() const { return scene_->only_plain_nff(); }
  const Vec3& ambient() const { return scene_->ambient(); }
  const std::optional<FogDesc>& fog() const { return scene_->fog(); }
  const Bounds3& bounds() const { return scene_->bounds(); }
  double epsilon() const { return scene_->epsilon(); }
  size_t object_count() const { return scene_->object_count(); }
  int object_of(uint32_t group, PrimKind kind, uint32_t prim) const { return scene_->object_of(group, kind, prim); }

 private:
  const RenderScene* scene_;
  RenderSettings settings_;
};

}  // namespace holoray
