// holoray/api (internal): what a World holds once built, for the Renderers
// that take it and the front ends inside the library (live/).
#pragma once

#include <memory>

#include "holoray/world.hpp"
#include "render/emitters.hpp"
#include "render/environment.hpp"
#include "render/render_context.hpp"
#include "api/gpu_executor.hpp"
#include "api/internal.hpp"

namespace holoray::api {

struct WorldState {
  std::shared_ptr<const SceneData> scene;  // with the headlight a scene made in code without lights gets
  std::unique_ptr<RenderScene> render_scene;
  // The files' settings with the light options: depth, integrator,
  // environment, emitters. A renderer copies them and adds its own
  // (footprint, shadow cache).
  RenderSettings settings;
  std::unique_ptr<EnvironmentMap> environment;  // the path integrator's (settings.environment)
  std::unique_ptr<EmissiveTriangles> emitters;  // the path integrator's (settings.emitters)
  // The light options it was built with (RenderOptions' fields).
  Integrator integrator = Integrator::whitted;
  Environment environment_options;
  bool blender_principled = false;
  int max_depth = 0;
  double build_seconds = 0;
  // The GPU path's layouts of the scene, made by the first GPU renderer
  // (of each hierarchy width) and kept for the next.
  std::unique_ptr<GpuLayouts> gpu_layouts = std::make_unique<GpuLayouts>();
};

namespace detail {

/// The state behind a World (internal).
struct WorldAccess {
  static const std::shared_ptr<const WorldState>& state(const World& world) { return world.state_; }
};

}  // namespace detail

}  // namespace holoray::api
