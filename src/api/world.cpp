// A scene built once (holoray/world.hpp): lit as a render asks, its
// geometry built; every Renderer that takes it shares the build.
#include "holoray/world.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "api/light_options.hpp"
#include "api/world_state.hpp"
#include "holoray/stopwatch.hpp"

namespace holoray::api {

World::World(const Scene& scene, const RenderOptions& light) {
  const auto t_build = Clock::now();
  static_assert(kMaxDepth == kDepthCap, "the API's depth limit is the renderer's");
  if (light.max_depth < 0 || light.max_depth > kDepthCap)
    throw std::invalid_argument(fmt::format("max_depth: expected 1 to {} (0: the scene's), got {}", kDepthCap, light.max_depth));
  check_light(light.integrator, light.environment, light.cache.enabled);
  auto s = std::make_shared<WorldState>();
  s->scene = scene.data();
  const SceneDesc& desc = s->scene->desc;
  // A scene built in code without lights is lit as a mesh file is: by a
  // headlight at its viewpoint.
  if (desc.lights.empty() && desc.viewpoint && desc.source.empty()) {
    auto lit = std::make_shared<SceneData>(*s->scene);
    Light headlight;
    headlight.position = desc.viewpoint->from;
    headlight.headlight = true;
    lit->desc.lights.push_back(headlight);
    s->scene = std::move(lit);
  }
  s->render_scene = std::make_unique<RenderScene>(s->scene->desc);
  s->settings = file_settings(*s->render_scene);
  if (light.max_depth != 0) s->settings.max_depth = light.max_depth;
  if (light.integrator == Integrator::path) {
    s->environment = environment_of(light.environment, s->scene->desc);
    s->settings.integrator = holoray::Integrator::path;
    s->settings.environment = s->environment.get();
    s->settings.principled = light.blender_principled;
    s->emitters = std::make_unique<EmissiveTriangles>(*s->render_scene);
    if (!s->emitters->empty()) s->settings.emitters = s->emitters.get();
    // The readers' stand-in headlight lights a scene without light; an
    // environment of the render's own, or emissive surfaces, are light.
    s->settings.skip_headlights = light.environment.given() || !s->emitters->empty();
  }
  s->integrator = light.integrator;
  s->environment_options = light.environment;
  s->blender_principled = light.blender_principled;
  s->max_depth = light.max_depth;
  s->build_seconds = seconds_since(t_build);
  state_ = std::move(s);
}

World::~World() = default;
World::World(const World&) = default;
World& World::operator=(const World&) = default;

const std::string& World::source() const { return state_->scene->desc.source; }
size_t World::skipped_polygons() const { return state_->render_scene->skipped_polygons(); }
double World::build_seconds() const { return state_->build_seconds; }

}  // namespace holoray::api
