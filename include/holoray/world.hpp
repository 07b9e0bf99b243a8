// holoray public API: a scene built once, rendered by many cameras.
//
//   World world(scene, options);             // read, lit and built once
//   Renderer left(world, camera_a, options);  // each camera placed on it
//   Renderer right(world, camera_b, options);
#pragma once

#include <memory>
#include <string>

#include "holoray/export.hpp"
#include "holoray/render.hpp"
#include "holoray/scene.hpp"

namespace holoray::api {

struct WorldState;  // internal
namespace detail {
struct WorldAccess;  // internal
}

/// A scene built for rendering (after OSPRay's World): its geometry built,
/// and its light resolved by the light options of a RenderOptions
/// (`integrator`, `environment`, `blender_principled`, `max_depth`: the
/// environment image read and importance-sampled, the emissive triangles
/// gathered; a scene made in code without lights gets a headlight at its
/// viewpoint). Built once, it is rendered by any number of Renderers with
/// any cameras, on either device, one after another or at once; each keeps
/// it alive. Copies share the one build. The CPU path builds its hierarchy
/// (Embree's) for the first CPU renderer, once for all of them; a GPU
/// renderer lays the scene out on its device and never needs it. Throws
/// std::invalid_argument naming the option for a bad light option,
/// SceneError for an environment image it cannot read.
class HOLORAY_API World {
 public:
  explicit World(const Scene& scene, const RenderOptions& light = {});
  ~World();
  World(const World&);
  World& operator=(const World&);

  /// The scene's file (Scene::source), empty for a scene built in code.
  const std::string& source() const;
  /// Zero-area polygons the build left out.
  size_t skipped_polygons() const;
  /// Seconds the build took (the scene's arrays, the light's tables).
  double build_seconds() const;

 private:
  friend struct detail::WorldAccess;
  std::shared_ptr<const WorldState> state_;
};

}  // namespace holoray::api
