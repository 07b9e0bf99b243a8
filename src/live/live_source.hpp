// holoray/live: what `holoray live` shows, built once: a still scene (its
// World, with every check `render` makes) or an animated shot (by
// ShotFrames), the camera, and the viewpoint at each of its frames.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "holoray/camera.hpp"
#include "holoray/render.hpp"
#include "holoray/scene.hpp"
#include "holoray/world.hpp"
#include "render/frame_camera.hpp"
#include "render/render_context.hpp"
#include "shot/shot_frames.hpp"

namespace holoray::api {

/// What live shows: a scene built once, the camera, and where the viewpoint
/// stands at each of its frames (a still has one). World frame, scene units.
struct LiveSource {
  const RenderScene* scene = nullptr;
  RenderSettings settings;
  FrameCameraDesc choice;
  std::string name;  // the scene or shot file, for messages
  std::string encoding_path;  // the file the auto encoding follows
  int frames = 1;
  double fps = 24;
  std::function<Viewpoint(int frame)> viewpoint;
  std::function<void(int frame)> seek;  // a shot: the scene moved to the frame
  std::unique_ptr<World> world;         // a still's, which built it
  std::unique_ptr<ShotFrames> shot;
};

/// A still. Throws as Renderer's constructor, and std::invalid_argument
/// naming the option for what live does not show (a quilt, an explicit
/// placement).
LiveSource still_source(const Scene& scene, const Camera& camera, const RenderOptions& options);
/// A shot (shot-format.md); `camera`: a pinhole, display or Looking Glass
/// instead of its [array]. Throws SceneError for a malformed shot or scene
/// file, std::invalid_argument naming the option.
LiveSource shot_source(const std::string& path, const std::optional<Camera>& camera, const RenderOptions& options);

}  // namespace holoray::api
