// holoray/live: api::run_live, the window's loop. The scene is built once
// (the Renderer's checks and RenderScene, laid out once on the device);
// each change of view places the camera again from the moved viewpoint,
// exactly as `holoray render` places it, traces it into the device's
// buffers and shows it through the Presenter, all on one device. Nothing
// renders while nothing changes.
#include <fmt/format.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <numbers>

#include "api/renderer_state.hpp"
#include "gpu/gpu_scene.hpp"
#include "gpu/presenter.hpp"
#include "holoray/live.hpp"
#include "image/image_io.hpp"
#include "live/event_script.hpp"
#include "live/shown_codes.hpp"
#include "live/view_controls.hpp"
#include "live/window_module.hpp"

namespace holoray::api {

namespace {

using live::InputEvent;
using live::LiveView;
using Clock = std::chrono::steady_clock;

constexpr const char* kShown[] = {"colour", "albedo", "depth", "normal", "object id"};

// What the window shows and how; changed by the keys.
struct Showing {
  int what = gpu::PackParams::colour;
  bool subaperture = false;
};

// The lines the user reads: the options' printer, else nothing.
struct Printer {
  const LiveOptions& o;
  void operator()(const std::string& line) const {
    if (o.print) o.print(line);
  }
};

// The first name `stem-NNNN.ext` in the working folder not yet taken.
std::string next_free(const std::string& ext) {
  for (int n = 1;; ++n) {
    std::string name = fmt::format("holoray-live-{:04}.{}", n, ext);
    if (!std::filesystem::exists(name)) return name;
  }
}

class Session {
 public:
  Session(const Scene& scene, const Camera& camera, const RenderOptions& options, const LiveOptions& live)
      : live_(live), print_{live} {
    const DeviceChoice device = parse_device(options.device);
    if (!device.gpu) throw std::invalid_argument("`device`: holoray live renders on the GPU path: gpu or gpu:N");
    if (std::holds_alternative<Quilt>(camera))
      throw std::invalid_argument("`Quilt`: a quilt is not shown live; show a Looking Glass's own panel image (`LookingGlass`)");
    if (const auto* a = std::get_if<LensArray>(&camera); a && a->placement)
      throw std::invalid_argument("`placement`: live moves the array with the viewpoint; place it by the viewpoint (and `focus_distance`)");
    if (const auto* d = std::get_if<Display>(&camera); d && d->placement)
      throw std::invalid_argument("`placement`: live moves the panel with the viewpoint; place it by the viewpoint (and `focus_distance`)");
    if (live.exit_after < 0) throw std::invalid_argument(fmt::format("exit after: expected 0 or more frames, got {}", live.exit_after));
    if (!live.screenshot.empty() && !is_supported_output(live.screenshot))
      throw std::invalid_argument(fmt::format("screenshot: expected a .png or .exr file, got '{}'", live.screenshot));
    if (!std::getenv("DISPLAY") && !std::getenv("WAYLAND_DISPLAY"))
      throw std::runtime_error("holoray live needs a display, and neither DISPLAY nor WAYLAND_DISPLAY is set: "
                               "run it on a desktop, or under xvfb-run");
    if (!live.events.empty()) script_ = live::read_event_script(live.events);
    if (!live.record.empty()) std::filesystem::create_directories(live.record);
    // The Renderer checks everything `render` checks and builds the scene
    // once; its own executor stays the CPU's (never used): the GPU path is
    // made below, on the window's instance.
    RenderOptions built = options;
    built.device = "cpu";
    built.aovs = {};
    renderer_ = std::make_unique<Renderer>(scene, camera, built);
    state_ = &detail::RendererAccess::state(*renderer_);
    options_ = options;
    encoding_ = live.encoding ? (*live.encoding == Encoding::srgb ? holoray::Encoding::srgb : holoray::Encoding::linear)
                              : holoray::default_encoding(scene.source());
    thresholds_ = live::code_thresholds(encoding_);
    const FrameCamera& placed = state_->camera();
    camera_.emplace(placed);
    panel_ = placed.get<PanelView>() || placed.get<LookingGlassCamera>();
    if (const auto* desc = state_->choice.get<FrameCameraDesc::Integral>()) lens_fov_ = desc->array.fov_lens_deg;
    start_.viewpoint = *state_->scene->desc.viewpoint;
    if (!state_->choice.get<FrameCameraDesc::Pinhole>()) start_.focus_distance = state_->choice.focus_distance;
    view_ = start_;

    live::WindowRequest request;
    request.width = placed.width(), request.height = placed.height();
    request.title = "holoray live";
    request.monitor = live.monitor;
    request.fullscreen = live.fullscreen.value_or(panel_);
    window_ = live::open_window(request);
    try {
      gpu_ = std::make_unique<gpu::GpuRenderer>(device.index, window_->instance_extensions());
      gpu_->load(gpu::lay_out(*state_->render_scene), gpu::GpuRenderer::frame_bytes(placed.width(), placed.height(), !panel_));
      presenter_ = std::make_unique<gpu::Presenter>(*gpu_, [&](void* instance) { return window_->create_surface(instance); },
                                                    thresholds_);
    } catch (const gpu::GpuError& e) {
      throw std::runtime_error(e.what());
    }
  }

  LiveResult run() {
    LiveResult result;
    bool dirty = true;  // the first frame
    size_t next = 0;    // the script's next event
    Clock::time_point first;
    while (!window_->closed()) {
      if (live_.stop && live_.stop()) break;
      // A scripted run (--events, --exit-after) renders frame after frame.
      const bool replaying = next < script_.size() || live_.exit_after > 0;
      // Idle: wait for input (at most half a second, to ask `stop` again).
      std::vector<InputEvent> input = window_->events(!dirty && !replaying);
      while (next < script_.size() && script_[next].frame <= frames_) input.push_back(script_[next++].event);
      for (const InputEvent& e : input) dirty |= apply(e);
      if (quit_) break;
      if (!dirty && !replaying) continue;
      if (!show()) continue;  // minimised
      if (frames_ == 0) first = Clock::now();
      ++frames_;
      result.seconds = std::chrono::duration<double>(Clock::now() - first).count();
      dirty = false;
      if (!live_.record.empty()) write_shown(fmt::format("{}/frame_{:06}.png", live_.record, frames_ - 1), false);
      if (live_.exit_after && frames_ >= live_.exit_after) break;
    }
    if (!live_.screenshot.empty() && frames_ > 0) write_shown(live_.screenshot, true);
    result.frames = frames_;
    result.view = live::describe(view_);
    return result;
  }

 private:
  // One input event; whether the view or what is shown changed.
  bool apply(const InputEvent& e) {
    const auto [w, h] = window_->framebuffer_size();
    switch (e.kind) {
      case InputEvent::Kind::orbit: live::orbit(view_, e.dx, e.dy, w, h); return true;
      case InputEvent::Kind::pan: live::pan(view_, e.dx, e.dy, h); return true;
      case InputEvent::Kind::wheel: live::dolly(view_, e.dy); return true;
      case InputEvent::Kind::key: break;
    }
    const std::string& k = e.key;
    if (k == "Escape" || k == "Q") quit_ = true;
    else if (k == "Up" || k == "Down") {
      if (state_->choice.get<FrameCameraDesc::Pinhole>()) return said("a pinhole view has no array plane to move");
      live::move_plane(view_, k == "Up" ? 1 : -1);
      return true;
    } else if (k == "Left" || k == "Right") {
      if (!state_->choice.get<FrameCameraDesc::Integral>())
        return said("the lens field of view is a lens array's (a display's lenses are its file's)");
      live::widen_lenses(view_, k == "Right" ? 1 : -1, placed_lens_fov());
      return true;
    } else if (k == "A") {
      if (panel_) return said("a panel image is colour only");
      showing_.what = (showing_.what + 1) % 5;
      print_(fmt::format("showing    {}", kShown[showing_.what]));
      return true;
    } else if (k == "V") {
      const holoray::LensArray* a = camera_->lens_array();
      if (!a || a->desc().grid == holoray::Grid::hex) return said("sub-aperture views are shown for square and lenticular lens arrays");
      showing_.subaperture = !showing_.subaperture;
      print_(fmt::format("showing    {}", showing_.subaperture ? "the centre sub-aperture view" : "the EIA"));
      return true;
    } else if (k == "S" || k == "shift+S") {
      if (frames_ > 0) {
        const std::string name = next_free(k == "S" ? "png" : "exr");
        write_shown(name, true);
      }
    } else if (k == "Home") {
      view_ = start_;
      return true;
    } else if (k == "Space") {
      return said("no shot to play (a shot plays from `holoray animate`; live shows one scene)");
    }
    return false;
  }

  bool said(const std::string& why) {
    print_(fmt::format("live       {}", why));
    return false;
  }

  double placed_lens_fov() const {
    const holoray::LensArray* a = camera_->lens_array();
    return a ? a->lens_fov_deg() : lens_fov_.value_or(kDefaultLensFovDeg);
  }

  // The camera placed from the view, as `render` places it from a file's viewpoint.
  FrameCamera place() const {
    FrameCameraDesc choice = state_->choice;
    if (!choice.get<FrameCameraDesc::Pinhole>()) choice.focus_distance = view_.focus_distance;
    if (auto* i = std::get_if<FrameCameraDesc::Integral>(&choice.kind); i && view_.lens_fov_deg) {
      i->array.fov_lens_deg = view_.lens_fov_deg;
      i->array.gap.reset();
    }
    const std::string& source = state_->scene->desc.source;
    return make_frame_camera(choice, view_.viewpoint, source.empty() ? "the scene" : source);
  }

  // Traces the view and shows it; false when the window had no room.
  bool show() {
    const auto t0 = Clock::now();
    camera_.emplace(place());
    RenderSettings settings = state_->settings;
    if (const auto angle = camera_->pixel_angle()) settings.footprint = {0, *angle};
    const RenderContext context(*state_->render_scene, settings);
    const bool aovs = showing_.what != gpu::PackParams::colour;
    const AovSet wanted{aovs, aovs, aovs, aovs};
    const int W = camera_->width(), H = camera_->height();
    gpu::PackParams pack;
    pack.what = showing_.what;
    pack.shown = {W, H};
    pack.depth_scale = float(live::focus(view_));
    const holoray::LensArray* array = camera_->lens_array();
    if (showing_.subaperture && array) {
      const LensArrayDesc& d = array->desc();
      const int P = d.pixels_per_lens;
      const bool lenticular = d.grid == holoray::Grid::lenticular;
      pack.shown = {array->lens_count_x(), lenticular ? H : array->lens_count_y()};
      pack.first = {P / 2, lenticular ? 0 : P / 2};
      pack.step = {P, lenticular ? 1 : P};
    }
    gpu::GpuFrameStats stats;
    try {
      gpu_->trace(gpu::camera_frames(context, *camera_, wanted, options_.spp, 0, H), W, H, stats);
      if (!presenter_->show(pack, window_->framebuffer_size())) return false;
    } catch (const gpu::GpuError& e) {
      throw std::runtime_error(e.what());
    }
    shown_ = pack;
    const double seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    const uint64_t rays = stats.eye_rays + stats.shadow_rays + stats.reflected_rays + stats.refracted_rays;
    window_->set_title(fmt::format("holoray live: {:.1f} ms a frame, {:.1f} Mrays/s on {}{}", seconds * 1e3,
                                   stats.trace_seconds > 0 ? rays / stats.trace_seconds / 1e6 : 0.0, gpu_->describe(),
                                   showing_.what ? fmt::format(", {}", kShown[showing_.what]) : ""));
    return true;
  }

  // The frame shown: .png its pixels as shown, .exr its rendered colour.
  void write_shown(const std::string& path, bool say) {
    if (lower_extension(path) == ".exr") {
      const int W = camera_->width(), H = camera_->height();
      FrameBuffers fb = allocate_frame(W, H, {});
      gpu::GpuFrameStats stats;
      // The colour of the last frame traced (an AOV shown traced it too).
      try {
        gpu_->readback({}, fb, stats);
      } catch (const gpu::GpuError& e) {
        throw std::runtime_error(e.what());
      }
      write_image(path, fb.colour, holoray::Encoding::linear);
    } else {
      const std::vector<uint8_t> rgb = presenter_->shown_rgb();
      write_image(path, live::image_of_codes(rgb, shown_.shown[0], shown_.shown[1], thresholds_), encoding_);
    }
    if (say) print_(fmt::format("wrote      {}", path));
  }

  const LiveOptions& live_;
  Printer print_;
  RenderOptions options_;
  std::unique_ptr<Renderer> renderer_;
  RendererState* state_ = nullptr;
  holoray::Encoding encoding_ = holoray::Encoding::linear;
  gpu::CodeThresholds thresholds_{};
  bool panel_ = false;
  std::optional<double> lens_fov_;
  LiveView start_, view_;
  std::vector<live::ScriptedEvent> script_;
  std::unique_ptr<live::Window> window_;
  std::unique_ptr<gpu::GpuRenderer> gpu_;
  std::unique_ptr<gpu::Presenter> presenter_;
  std::optional<FrameCamera> camera_;  // as last placed
  gpu::PackParams shown_;
  Showing showing_;
  int frames_ = 0;
  bool quit_ = false;
};

}  // namespace

LiveResult run_live(const Scene& scene, const Camera& camera, const RenderOptions& options, const LiveOptions& live) {
  Session session(scene, camera, options, live);
  return session.run();
}

}  // namespace holoray::api
