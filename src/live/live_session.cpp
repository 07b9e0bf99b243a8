// holoray/live: api::run_live and run_live_shot, the window's loop. The
// scene is built once (a still's by the Renderer, with every check `render`
// makes; a shot's by ShotFrames) and laid out once on the device (again
// only when a shot's objects move); each change of view places the camera
// again from the moved viewpoint, exactly as `holoray render` places it,
// traces it into the device's buffers and shows it through the Presenter,
// all on one device. Nothing renders while nothing changes, but a
// path-traced view, which takes more samples while it stands still.
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <numbers>

#include "api/gpu_executor.hpp"
#include "gpu/gpu_scene.hpp"
#include "gpu/presenter.hpp"
#include "holoray/live.hpp"
#include "image/image_io.hpp"
#include "live/event_script.hpp"
#include "live/live_source.hpp"
#include "live/offscreen_window.hpp"
#include "live/shown_codes.hpp"
#include "live/view_controls.hpp"
#include "live/window_module.hpp"
#include "preview/simulate.hpp"

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
  Session(LiveSource source, const RenderOptions& options, const LiveOptions& live)
      : live_(live), print_{live}, source_(std::move(source)), options_(options) {
    const DeviceChoice device = parse_device(options.device);
    if (!device.gpu) throw std::invalid_argument("`device`: holoray live renders on the GPU path: gpu or gpu:N");
    if (options.spp < 1) throw std::invalid_argument(fmt::format("spp: expected at least 1 sample per pixel, got {}", options.spp));
    if (live.exit_after < 0) throw std::invalid_argument(fmt::format("exit after: expected 0 or more frames, got {}", live.exit_after));
    if (live.max_spp < 0) throw std::invalid_argument(fmt::format("max spp: expected 0 or more samples per pixel, got {}", live.max_spp));
    path_ = source_.settings.integrator == holoray::Integrator::path;
    if (!live.screenshot.empty() && !is_supported_output(live.screenshot))
      throw std::invalid_argument(fmt::format("screenshot: expected a .png or .exr file, got '{}'", live.screenshot));
    if (!live.events.empty()) script_ = live::read_event_script(live.events);
    if (live.offscreen && live.exit_after < 1)
      throw std::invalid_argument("`offscreen`: goes with exit after N frames (there is no window to close)");
    if (!live.offscreen && !std::getenv("DISPLAY") && !std::getenv("WAYLAND_DISPLAY"))
      throw std::runtime_error("holoray live needs a display, and neither DISPLAY nor WAYLAND_DISPLAY is set: "
                               "run it on a desktop, under xvfb-run, or offscreen (--offscreen)");
    if (!live.record.empty()) std::filesystem::create_directories(live.record);
    encoding_ = live.encoding ? (*live.encoding == Encoding::srgb ? holoray::Encoding::srgb : holoray::Encoding::linear)
                              : holoray::default_encoding(source_.encoding_path);
    thresholds_ = live::code_thresholds(encoding_);
    playing_ = live.play && source_.frames > 1;
    if (live.simulate) {
      const auto* d = source_.choice.get<FrameCameraDesc::Display>();
      if (!d) throw std::invalid_argument("`simulate`: goes with a display file (`Display`): what an eye sees through its lens sheet");
      display_ = d->display;
    }
    const FrameCamera placed = place();
    camera_.emplace(placed);
    panel_ = gpu::renders_panel(placed);

    live::WindowRequest request;
    request.width = placed.width(), request.height = placed.height();
    request.title = "holoray live";
    request.monitor = live.monitor;
    request.fullscreen = live.fullscreen.value_or(panel_ && !live.simulate);
    window_ = live.offscreen ? live::offscreen_window(request) : live::open_window(request);
    try {
      gpu_ = std::make_unique<gpu::GpuRenderer>(device.index, window_->instance_extensions());
      image_bytes_ = gpu::GpuRenderer::frame_bytes(placed.width(), placed.height(), !panel_);
      follow();
      using MakeSurface = std::function<uint64_t(void*)>;
      presenter_ = std::make_unique<gpu::Presenter>(
          *gpu_, live.offscreen ? MakeSurface{} : MakeSurface{[&](void* instance) { return window_->create_surface(instance); }},
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
      // A scripted run (--events, --exit-after) renders frame after frame,
      // and so does a playing shot, and a path-traced view still refining.
      const bool busy = next < script_.size() || live_.exit_after > 0 || playing_ || refining();
      // Idle: wait for input (at most half a second, to ask `stop` again).
      std::vector<InputEvent> input = window_->events(!dirty && !busy);
      while (next < script_.size() && script_[next].frame <= frames_) input.push_back(script_[next++].event);
      for (const InputEvent& e : input) dirty |= apply(e);
      if (quit_) break;
      if (playing_) dirty |= advance();
      if (!dirty && !busy) continue;
      if (!show(dirty, result)) continue;  // minimised
      if (frames_ == 0) first = Clock::now();
      ++frames_;
      result.seconds = std::chrono::duration<double>(Clock::now() - first).count();
      dirty = false;
      if (!live_.record.empty()) write_shown(fmt::format("{}/frame_{:04}.png", live_.record, frames_ - 1), false);
      if (live_.exit_after && frames_ >= live_.exit_after) break;
    }
    if (!live_.screenshot.empty() && frames_ > 0) write_shown(live_.screenshot, true);
    result.frames = frames_;
    result.view = live::describe(view());
    result.shot_frame = shot_frame_;
    if (display_) result.eye_mm = fmt::format("{:.17g},{:.17g},{:.17g}", eye_mm_.x, eye_mm_.y, eye_mm_.z);
    result.simulated_width = simulated_.width;
    return result;
  }

 private:
  // The view shown: the one the controls moved, else the source's at the shot's frame.
  LiveView view() const {
    if (moved_) return *moved_;
    LiveView v;
    v.viewpoint = source_.viewpoint(shot_frame_);
    if (!source_.choice.get<FrameCameraDesc::Pinhole>()) v.focus_distance = source_.choice.focus_distance;
    return v;
  }
  // The view the controls move, taken from the one shown on first use.
  LiveView& moved() {
    if (!moved_) moved_ = view();
    return *moved_;
  }

  // A playing shot's frame from the clock (real time, looping); whether it changed.
  bool advance() {
    const double elapsed = std::chrono::duration<double>(Clock::now() - play_start_).count();
    const int frame = (play_from_ + int(std::floor(elapsed * source_.fps))) % source_.frames;
    if (frame == shot_frame_) return false;
    shot_frame_ = frame;
    return true;
  }

  void play(bool on) {
    playing_ = on;
    play_start_ = Clock::now();
    play_from_ = shot_frame_;
  }

  // One input event; whether the view or what is shown changed.
  bool apply(const InputEvent& e) {
    const auto [w, h] = window_->framebuffer_size();
    // --simulate: the pointer is the eye's place over the panel, the wheel
    // its distance; the panel image stays as traced.
    if (display_ && (e.kind == InputEvent::Kind::pointer || e.kind == InputEvent::Kind::wheel)) {
      if (e.kind == InputEvent::Kind::pointer) {
        eye_mm_.x = (e.dx / std::max(1, w) - 0.5) * display_->width * display_->pixel_pitch_mm;
        eye_mm_.y = (0.5 - e.dy / std::max(1, h)) * display_->height * display_->pixel_pitch_mm;
      } else {
        eye_mm_.z = std::max(1.0, eye_mm_.z * std::pow(0.9, e.dy));
      }
      return true;
    }
    if (e.kind == InputEvent::Kind::pointer) return false;
    retrace_ = true;
    switch (e.kind) {
      case InputEvent::Kind::pointer: return false;
      case InputEvent::Kind::orbit: live::orbit(moved(), e.dx, e.dy, w, h); return true;
      case InputEvent::Kind::pan: live::pan(moved(), e.dx, e.dy, h); return true;
      case InputEvent::Kind::wheel: live::dolly(moved(), e.dy); return true;
      case InputEvent::Kind::key: break;
    }
    const std::string& k = e.key;
    const FrameCameraDesc& choice = source_.choice;
    if (k == "Escape" || k == "Q") quit_ = true;
    else if (k == "Up" || k == "Down") {
      if (choice.get<FrameCameraDesc::Pinhole>()) return said("a pinhole view has no array plane to move");
      live::move_plane(moved(), k == "Up" ? 1 : -1);
      return true;
    } else if (k == "Left" || k == "Right") {
      if (!choice.get<FrameCameraDesc::Integral>())
        return said("the lens field of view is a lens array's (a display's lenses are its file's)");
      const holoray::LensArray* a = camera_->lens_array();
      live::widen_lenses(moved(), k == "Right" ? 1 : -1, a ? a->lens_fov_deg() : kDefaultLensFovDeg);
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
      if (frames_ > 0) write_shown(next_free(k == "S" ? "png" : "exr"), true);
    } else if (k == "Home") {
      moved_.reset();
      return true;
    } else if (k == "Space") {
      if (source_.frames < 2) return said("no shot to play: give one with --shot");
      play(!playing_);
      return true;
    } else if (k == "PageDown" || k == "PageUp") {
      if (source_.frames < 2) return said("no shot to step through: give one with --shot");
      play(false);
      shot_frame_ = (shot_frame_ + (k == "PageDown" ? 1 : source_.frames - 1)) % source_.frames;
      return true;
    }
    return false;
  }

  bool said(const std::string& why) {
    print_(fmt::format("live       {}", why));
    return false;
  }

  // The camera placed from the view, as `render` places it from a file's viewpoint.
  FrameCamera place() const {
    const LiveView v = view();
    FrameCameraDesc choice = source_.choice;
    if (!choice.get<FrameCameraDesc::Pinhole>()) choice.focus_distance = v.focus_distance;
    if (auto* i = std::get_if<FrameCameraDesc::Integral>(&choice.kind); i && v.lens_fov_deg) {
      i->array.fov_lens_deg = v.lens_fov_deg;
      i->array.gap.reset();
    }
    return make_frame_camera(choice, v.viewpoint, source_.name.empty() ? "the scene" : source_.name);
  }

  // A shot's scene moved to the frame shown, laid out again on the device
  // where its objects moved: the fast build, then refitted frame by frame
  // (gpu_executor.cpp says why).
  void follow() {
    if (source_.seek && seeked_ != shot_frame_) source_.seek(shot_frame_), seeked_ = shot_frame_;
    gpu::ScenePose now(source_.scene->accel());
    if (uploaded_ && *uploaded_ == now) return;
    const RenderContext context(*source_.scene, source_.settings);
    gpu_->load(uploaded_ ? gpu::lay_out(context, BvhQuality::fast, gpu_->bvh_width(), &kept_)
                         : gpu::lay_out(context, BvhQuality::high, gpu_->bvh_width()),
               image_bytes_, panel_, uploaded_.has_value());
    uploaded_ = std::move(now);
  }

  // Whether the path integrator's view shown is still taking samples
  // (LiveOptions::max_spp): the panel's colours alone, not a simulated eye's view.
  bool refining() const { return path_ && !display_ && samples_ > 0 && samples_ < live_.max_spp; }

  // Traces the view and shows it, adding each part's time to `spent`;
  // false when the window had no room. A path-traced view that did not
  // `change` adds samples to the last.
  bool show(bool changed, LiveResult& spent) {
    const auto t0 = Clock::now();
    auto since = t0;
    auto lap = [&since](double& into) {
      const auto now = Clock::now();
      into += std::chrono::duration<double>(now - since).count();
      since = now;
    };
    holoray::RenderStats stats;
    try {
      follow();
      lap(spent.layout_seconds);
      camera_.emplace(place());
      RenderSettings settings = source_.settings;
      if (const auto angle = camera_->pixel_angle()) settings.footprint = {0, *angle};
      const RenderContext context(*source_.scene, settings);
      const bool aovs = showing_.what != gpu::PackParams::colour;
      const AovSet wanted{aovs, aovs, aovs, aovs};
      const int W = camera_->width(), H = camera_->height();
      gpu::PackParams pack;
      pack.what = showing_.what;
      pack.shown = {W, H};
      pack.depth_scale = float(live::focus(view()));
      const holoray::LensArray* array = camera_->lens_array();
      if (showing_.subaperture && array) {
        const LensArrayDesc& d = array->desc();
        const int P = d.pixels_per_lens;
        const bool lenticular = d.grid == holoray::Grid::lenticular;
        pack.shown = {array->lens_count_x(), lenticular ? H : array->lens_count_y()};
        pack.first = {P / 2, lenticular ? 0 : P / 2};
        pack.step = {P, lenticular ? 1 : P};
      }
      if (!display_) {
        // A path-traced view that did not change takes the samples after
        // the last trace's, until it has max_spp; then it is shown as it is.
        const bool still = path_ && !changed && samples_ > 0;
        if (!still || refining()) {
          const int first = still ? samples_ : 0;
          const int spp = still ? std::min(first + options_.spp, live_.max_spp) : options_.spp;
          gpu_->trace(gpu::camera_frames(context, *camera_, wanted, spp, 0, H), W, H, stats, first);
          samples_ = spp;
        }
        lap(spent.trace_seconds);
        if (!presenter_->show(pack, window_->framebuffer_size())) return false;
        lap(spent.show_seconds);
      } else {
        // What an eye sees through the display (preview/simulate.hpp), from
        // the panel image traced on the device and read back once per view.
        if (retrace_) {
          gpu_->trace(gpu::camera_frames(context, *camera_, {}, options_.spp, 0, H), W, H, stats);
          panel_image_ = allocate_frame(W, H, {});
          gpu_->readback({}, panel_image_, stats);
          retrace_ = false;
        }
        lap(spent.trace_seconds);
        SimulateOptions so;
        so.eye_mm = eye_mm_;
        so.width = std::max(1, window_->framebuffer_size()[0]);
        simulated_ = simulate_view(panel_image_.colour, *display_, so);
        if (!presenter_->show_image(simulated_.data.data(), simulated_.width, simulated_.height, window_->framebuffer_size()))
          return false;
        lap(spent.show_seconds);
        pack = {};
        pack.shown = {simulated_.width, simulated_.height};
      }
      shown_ = pack;
    } catch (const gpu::GpuError& e) {
      throw std::runtime_error(e.what());
    }
    const double seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    const uint64_t rays = stats.rays.total();
    window_->set_title(fmt::format("holoray live: {:.1f} ms a frame, {:.1f} Mrays/s on {}{}{}{}", seconds * 1e3,
                                   stats.trace_seconds > 0 ? rays / stats.trace_seconds / 1e6 : 0.0, gpu_->describe(),
                                   source_.frames > 1 ? fmt::format(", frame {} of {}{}", shot_frame_, source_.frames,
                                                                    playing_ ? "" : " (paused)")
                                                      : "",
                                   showing_.what ? fmt::format(", {}", kShown[showing_.what]) : "",
                                   display_ ? fmt::format(", eye {:.0f},{:.0f},{:.0f} mm", eye_mm_.x, eye_mm_.y, eye_mm_.z) : ""));
    return true;
  }

  // The frame shown: .png its pixels as shown, .exr its rendered colour.
  void write_shown(const std::string& path, bool say) {
    if (lower_extension(path) == ".exr" && display_) {
      write_image(path, simulated_, holoray::Encoding::linear);
    } else if (lower_extension(path) == ".exr") {
      FrameBuffers fb = allocate_frame(camera_->width(), camera_->height(), {});
      holoray::RenderStats stats;
      try {
        gpu_->readback({}, fb, stats);  // the colour of the last frame traced (an AOV shown traced it too)
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
  LiveSource source_;
  RenderOptions options_;
  holoray::Encoding encoding_ = holoray::Encoding::linear;
  gpu::CodeThresholds thresholds_{};
  bool panel_ = false;
  // --simulate: the display, the eye (display frame, mm), the panel image
  // traced for the view (again only when the view changed) and what the eye sees.
  std::optional<DisplayDesc> display_;
  Vec3 eye_mm_{0, 0, 600};
  bool retrace_ = true;
  bool path_ = false;         // the path integrator: a still view refines (refining())
  int samples_ = 0;           // per pixel in the view shown
  FrameBuffers panel_image_;
  ImageBuffer simulated_;
  std::optional<LiveView> moved_;  // set once the controls moved the view
  int shot_frame_ = 0, seeked_ = 0;
  bool playing_ = false;
  Clock::time_point play_start_;
  int play_from_ = 0;
  std::vector<live::ScriptedEvent> script_;
  std::unique_ptr<live::Window> window_;
  std::unique_ptr<gpu::GpuRenderer> gpu_;
  std::unique_ptr<gpu::Presenter> presenter_;
  uint64_t image_bytes_ = 0;
  std::optional<gpu::ScenePose> uploaded_;
  gpu::KeptBvh kept_;  // a shot's hierarchy, refitted as its objects move
  std::optional<FrameCamera> camera_;  // as last placed
  gpu::PackParams shown_;
  Showing showing_;
  int frames_ = 0;
  bool quit_ = false;
};

}  // namespace

LiveResult run_live(const Scene& scene, const Camera& camera, const RenderOptions& options, const LiveOptions& live) {
  Session session(still_source(scene, camera, options), options, live);
  return session.run();
}

LiveResult run_live_shot(const std::string& shot, const std::optional<Camera>& camera, const RenderOptions& options,
                         const LiveOptions& live) {
  Session session(shot_source(shot, camera, options), options, live);
  return session.run();
}

}  // namespace holoray::api
