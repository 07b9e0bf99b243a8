#include "live/live_source.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "api/renderer_state.hpp"
#include "shot/shot_reader.hpp"

namespace holoray::api {


// A still: its World, built once, after the checks a Renderer on it makes
// (check_camera); the GPU path is made on the window's instance.
LiveSource still_source(const Scene& scene, const Camera& camera, const RenderOptions& options) {
  if (std::holds_alternative<Quilt>(camera))
    throw std::invalid_argument("`Quilt`: a quilt is not shown live; show a Looking Glass's own panel image (`LookingGlass`)");
  if (const auto* a = std::get_if<LensArray>(&camera); a && a->placement)
    throw std::invalid_argument("`placement`: live moves the array with the viewpoint; place it by the viewpoint (and `focus_distance`)");
  if (const auto* d = std::get_if<Display>(&camera); d && d->placement)
    throw std::invalid_argument("`placement`: live moves the panel with the viewpoint; place it by the viewpoint (and `focus_distance`)");
  LiveSource s;
  RenderOptions built = options;
  built.device = "cpu";
  built.aovs = {};
  s.world = std::make_unique<World>(scene, built);
  check_camera(*s.world, camera, built);  // as a Renderer on it checks it
  const WorldState& w = *detail::WorldAccess::state(*s.world);
  s.scene = w.render_scene.get();
  s.settings = w.settings;
  s.choice = frame_camera_desc(camera);
  s.name = s.encoding_path = scene.source();
  const Viewpoint vp = *w.scene->desc.viewpoint;
  s.viewpoint = [vp](int) { return vp; };
  return s;
}

// A shot (shot-format.md): its scene files built into one scene, its
// objects and viewpoint at each frame; its [array] the camera unless a
// pinhole, display or Looking Glass camera is given (as `holoray animate`).
LiveSource shot_source(const std::string& path, const std::optional<Camera>& camera, const RenderOptions& options) {
  if (camera && std::holds_alternative<Quilt>(*camera))
    throw std::invalid_argument("`Quilt`: a quilt is not shown live; show a Looking Glass's own panel image (`LookingGlass`)");
  if (camera && std::holds_alternative<LensArray>(*camera))
    throw std::invalid_argument("camera: the shot's [array] places the lens array; pass a pinhole, display or Looking Glass camera");
  if (options.integrator == Integrator::path)
    throw std::invalid_argument("`integrator` path: live path traces a still scene; a shot path traces with "
                                "`holoray animate --integrator path`");
  if (options.max_depth < 0 || options.max_depth > kMaxDepth)
    throw std::invalid_argument(fmt::format("max_depth: expected 1 to {} (0: the scene's), got {}", kMaxDepth, options.max_depth));
  LiveSource s;
  s.shot = std::make_unique<ShotFrames>(read_shot_file(path));
  ShotFrames& shot = *s.shot;
  s.scene = &shot.scene();
  s.settings = shot.settings();
  if (options.max_depth != 0) s.settings.max_depth = options.max_depth;
  s.choice = camera ? frame_camera_desc(*camera) : FrameCameraDesc{FrameCameraDesc::Integral{shot.shot().array}, std::nullopt};
  s.name = path;
  s.encoding_path = shot.shot().objects.empty() ? path : shot.shot().objects.front().scene;
  s.frames = shot.frame_count();
  s.fps = shot.shot().fps;
  s.viewpoint = [&shot](int frame) { return shot.viewpoint(frame); };
  s.seek = [&shot](int frame) { shot.seek(frame); };
  shot.seek(0);
  return s;
}

}  // namespace holoray::api
