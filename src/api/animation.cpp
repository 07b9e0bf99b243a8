// The orchestration of an animated shot, once for every front end: the
// options resolved into the tracing schedule (temporal/sequence.hpp), the
// shot read, the keyframes placed, the frames' buffers checked against memory.
#include <fmt/format.h>
#include <oneapi/tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <set>
#include <stdexcept>

#include "api/light_options.hpp"
#include "api/gpu_executor.hpp"
#include "api/internal.hpp"
#include "holoray/pick.hpp"
#include "holoray/animate.hpp"
#include "holoray/errors.hpp"
#include "image/image_io.hpp"
#include "render/shadow_cache.hpp"
#include "scene/mesh_reader.hpp"
#include "shot/shot_reader.hpp"
#include "temporal/keyframe_schedule.hpp"
#include "temporal/point_image.hpp"
#include "temporal/report.hpp"

namespace holoray::api {

namespace {

holoray::ImageDifference from_api(const Difference& d) { return {d.mse, d.mse_all, d.pixels, d.nan_mismatches}; }
Difference to_api(const holoray::ImageDifference& d) { return {d.mse, d.mse_all, d.pixels, d.nan_mismatches}; }

}  // namespace

FrameRow to_api(const FrameReport& r) {
  FrameRow o;
  o.frame = r.frame;
  o.keyframe = r.keyframe;
  o.seconds = r.seconds;
  o.reference_seconds = r.reference_seconds;
  o.pixels = r.pixels;
  o.reprojected = r.reprojected, o.missed = r.missed, o.leaks = r.leaks, o.rejected = r.rejected;
  o.traced = r.traced, o.interpolated = r.interpolated;
  o.rays = to_api(r.rays);
  o.stage_seconds = {r.stages.splat, r.stages.merge, r.stages.leaks, r.stages.check, r.stages.fill};
  if (r.difference) o.difference = to_api(*r.difference);
  if (r.hold) o.hold = to_api(*r.hold);
  o.rebuilt = r.rebuilt;
  o.copied_from = r.copied_from;
  return o;
}

FrameReport from_api(const FrameRow& o) {
  FrameReport r;
  r.frame = o.frame;
  r.keyframe = o.keyframe;
  r.seconds = o.seconds;
  r.reference_seconds = o.reference_seconds;
  r.pixels = o.pixels;
  r.reprojected = o.reprojected, r.missed = o.missed, r.leaks = o.leaks, r.rejected = o.rejected;
  r.traced = o.traced, r.interpolated = o.interpolated;
  r.rays = {o.rays.eye, o.rays.shadow, o.rays.reflected, o.rays.refracted, o.rays.shadow_cached, o.rays.cache_samples};
  r.stages = {o.stage_seconds[0], o.stage_seconds[1], o.stage_seconds[2], o.stage_seconds[3], o.stage_seconds[4]};
  if (o.difference) r.difference = from_api(*o.difference);
  if (o.hold) r.hold = from_api(*o.hold);
  r.rebuilt = o.rebuilt;
  r.copied_from = o.copied_from;
  return r;
}

struct AnimationState {
  AnimateOptions options;
  SequenceOptions so;
  std::unique_ptr<ShotFrames> shot;
  std::unique_ptr<ShadowCache> cache;
  Method method = Method::full;
  std::string reuse;
  FrameCameraDesc choice;
  int width = 0, height = 0;
  std::string describe, array_summary;
  std::unique_ptr<GpuExecutor> gpu;  // `device` gpu
  std::unique_ptr<EnvironmentMap> environment;  // the path integrator's (so.environment)
};

namespace {

using Desc = FrameCameraDesc;

// The camera's kind against the method and the options that go with it;
// then the method's reuse, reach and fill. Sets s.method, s.reuse and the
// schedule's method, camera and reuse settings.
void choose_method(const AnimateOptions& o, AnimationState& s) {
  const FrameCameraDesc& choice = s.choice;
  SequenceOptions& so = s.so;
  if (choice.get<Desc::Quilt>()) throw std::invalid_argument("camera: a quilt is rendered as a still (render), not animated");
  if (o.camera && choice.get<Desc::Integral>())
    throw std::invalid_argument("camera: the shot's [array] places the lens array; pass a pinhole, display or Looking Glass camera");
  const bool pinhole = choice.get<Desc::Pinhole>() != nullptr;
  const bool glass = choice.get<Desc::LookingGlass>() != nullptr;
  const bool panel = glass || choice.get<Desc::Display>();
  const char* what = glass ? "`LookingGlass`" : "`Display`";
  if (o.integrator != Integrator::path && (o.seed != 0 || o.animated_seed))
    throw std::invalid_argument(fmt::format("`{}`: Whitted's integrator draws no random samples: go with the path integrator",
                                            o.seed != 0 ? "seed" : "animated_seed"));
  if (o.integrator == Integrator::path) {
    constexpr const char* kWhy = "goes with `method` full (reuse reprojects Whitted's shading; path tracing traces every frame in full)";
    if (o.method == Method::reproject || o.method == Method::reverse)
      throw std::invalid_argument(fmt::format("`integrator` path: {}", kWhy));
    if (!o.reuse.empty()) throw std::invalid_argument(fmt::format("`reuse`: {}", kWhy));
    if (o.reference)
      throw std::invalid_argument("`reference`: goes with `integrator` whitted (path tracing traces every frame in full: no reuse to compare)");
  }
  if (parse_device(o.device).gpu) {
    // Reuse keeps keyframes' point images in host memory and reprojects them
    // on the CPU; on the GPU, tracing the frame is the cheaper of the two.
    constexpr const char* kWhy = "goes with `device` cpu (the GPU path traces every frame in full; reuse reprojects "
                                 "point images on the CPU)";
    if (o.method == Method::reproject || o.method == Method::reverse)
      throw std::invalid_argument(fmt::format("`method` {}: {}", o.method == Method::reproject ? "reproject" : "reverse", kWhy));
    if (!o.reuse.empty()) throw std::invalid_argument(fmt::format("`reuse`: {}", kWhy));
    if (o.reference)
      throw std::invalid_argument("`reference`: goes with `device` cpu (the GPU path traces every frame in full: no reuse to compare)");
  }
  s.method = o.method != Method::automatic         ? o.method
             : pinhole || panel || parse_device(o.device).gpu || o.integrator == Integrator::path ? Method::full
                                                              : Method::reverse;
  so.method = s.method == Method::reverse ? holoray::Method::reverse
              : s.method == Method::reproject ? holoray::Method::reproject
                                              : holoray::Method::full;
  if (pinhole && so.method != holoray::Method::full)
    throw std::invalid_argument("`Pinhole`: goes with `method` full (reuse works on elemental images)");
  if (panel && so.method != holoray::Method::full)
    throw std::invalid_argument(fmt::format("{}: goes with `method` full (reuse works on elemental images)", what));
  if (panel && (o.reference || o.cache.enabled))
    throw std::invalid_argument(fmt::format("{}: goes without `reference` and `cache` (native panels are traced in full, without the cache)", what));
  if (!choice.get<Desc::Integral>()) so.frame_camera = choice;
  if (pinhole && o.reference)
    throw std::invalid_argument("`reference`: goes with the integral camera (pinhole previews are traced in full)");
  if (pinhole && o.cache.enabled)
    throw std::invalid_argument("`cache`: goes with the integral camera (its cells are sized in lens pitches)");
  s.reuse = !o.reuse.empty() ? o.reuse : so.method == holoray::Method::reverse ? "color" : "geometry";
  if (so.method == holoray::Method::reverse)
    so.reverse.reuse = pick<ReverseReuse>("reuse", s.reuse, {{"visibility", ReverseReuse::visibility}, {"color", ReverseReuse::color}});
  else
    so.reproject.reuse = pick<Reuse>("reuse", s.reuse, {{"geometry", Reuse::geometry}, {"color", Reuse::color}});
  if (so.method == holoray::Method::full) s.reuse.clear();
  so.reproject.reach = pick<Reach>("reach", o.reach, {{"near", Reach::near}, {"all", Reach::all}});
  so.fill = pick<Fill>("fill", o.fill, {{"trace", Fill::trace}, {"interpolate", Fill::interpolate}});
  so.reproject.detect_leaks = o.leak_check;
}

// The options' numbers, each in its range; then the schedule's copies.
void check_numbers(const AnimateOptions& o, SequenceOptions& so) {
  if (o.keyframe_interval < 0)
    throw std::invalid_argument(fmt::format("keyframe interval: must be a whole number of frames, at least 1 (0: placed by motion), got {}", o.keyframe_interval));
  if (!(o.keyframe_motion > 0) || !std::isfinite(o.keyframe_motion))
    throw std::invalid_argument(fmt::format("keyframe motion: must be a positive number of pixels, got {}", o.keyframe_motion));
  if (o.max_keyframe_interval < 1)
    throw std::invalid_argument(fmt::format("max keyframe interval: must be at least 1, got {}", o.max_keyframe_interval));
  if (!(o.rebuild_above_percent >= 0 && o.rebuild_above_percent <= 100))
    throw std::invalid_argument(fmt::format("rebuild above: expected a percent in [0, 100], got {}", o.rebuild_above_percent));
  if (o.threads < 0) throw std::invalid_argument(fmt::format("threads: expected 0 (all cores) or more, got {}", o.threads));
  if (!(o.cache.cell > 0) || !std::isfinite(o.cache.cell))
    throw std::invalid_argument(fmt::format("cache cell: must be a positive number of lens pitches, got {}", o.cache.cell));
  if (!(o.cache.memory_mib >= 0) || !std::isfinite(o.cache.memory_mib))
    throw std::invalid_argument(fmt::format("cache memory: must be 0 MiB or more, got {}", o.cache.memory_mib));
  so.max_interpolated_share = o.rebuild_above_percent / 100;
  if (o.keyframe_interval != 0) so.keyframe_interval = o.keyframe_interval;
  so.threads = o.threads;
  so.reproject.threads = o.threads;
  so.reference = o.reference;
}

// The shot file with the caller's camera name and texture folders.
std::unique_ptr<ShotFrames> read_shot(const std::string& shot_path, const AnimateOptions& o) {
  Shot parsed = read_shot_file(shot_path);
  if (!o.load.camera_name.empty()) parsed.read.camera_name = o.load.camera_name;
  parsed.read.texture_paths.insert(parsed.read.texture_paths.end(), o.load.texture_paths.begin(), o.load.texture_paths.end());
  return std::make_unique<ShotFrames>(std::move(parsed));
}

// A pinhole view without a size takes the first scene's resolution, as
// every frame's (a path's viewpoints carry none), else 512x512.
void size_the_view(const ShotFrames& shot, SequenceOptions& so) {
  Desc::Pinhole* view = so.frame_camera ? std::get_if<Desc::Pinhole>(&so.frame_camera->kind) : nullptr;
  if (!view || view->width != 0) return;
  auto first_res = std::find_if(shot.scenes().begin(), shot.scenes().end(),
                                [](const SceneDesc& d) { return d.viewpoint && d.viewpoint->xres > 0; });
  view->width = first_res != shot.scenes().end() ? first_res->viewpoint->xres : 512;
  view->height = first_res != shot.scenes().end() ? first_res->viewpoint->yres : 512;
}

// The frames' size, and their buffers refused before the first trace when
// they would take more than 80% of the machine: two point images, two
// z-buffers and the frame (a panel: its samples, three per pixel, and the
// packed frame).
void size_the_frames(const holoray::LensArray& first, AnimationState& s) {
  const Desc::LookingGlass* glass = s.choice.get<Desc::LookingGlass>();
  const Desc::Display* display = s.choice.get<Desc::Display>();
  const Desc::Pinhole* view = s.so.frame_camera ? s.so.frame_camera->get<Desc::Pinhole>() : nullptr;
  const bool panel = glass || display;
  const int panel_w = glass ? glass->calibration.width : display ? display->display.width : 0;
  const int panel_h = glass ? glass->calibration.height : display ? display->display.height : 0;
  s.width = panel ? panel_w : view ? view->width : first.width();
  s.height = panel ? panel_h : view ? view->height : first.height();
  const uint64_t need = panel ? uint64_t(panel_w) * panel_h * (3 * 12 + 2 * 12)
                              : static_cast<uint64_t>(first.pixel_count()) * (2 * PointImage::kBytesPerPixel + 2 * 8 + 64);
  const uint64_t have = physical_memory_bytes();
  if (have && need > have / 10 * 8)
    throw std::length_error(fmt::format("{}x{} frames need {:.2f} GiB while animating, more than 80% of this machine's {:.2f} GiB",
                                        panel ? panel_w : first.width(), panel ? panel_h : first.height(), need / 1073741824.0,
                                        have / 1073741824.0));
}

// What the CLI prints of the camera and the method.
std::string describe_animation(const AnimateOptions& o, const AnimationState& s) {
  const SequenceOptions& so = s.so;
  std::string d;
  if (s.choice.get<Desc::Display>())
    d += fmt::format("panel      {}x{} px from {}, each frame's viewpoint\n", s.width, s.height,
                     std::get<Display>(*o.camera).path);
  else if (const auto* glass = s.choice.get<Desc::LookingGlass>())
    d += fmt::format("panel      {}x{} px, Looking Glass ({}), each frame's viewpoint, continuous {}-view quilt\n",
                     s.width, s.height, std::get<LookingGlass>(*o.camera).path, glass->views);
  else if (s.choice.get<Desc::Pinhole>())
    d += fmt::format("view       {}x{} px, pinhole, each frame's viewpoint\n", s.width, s.height);
  else
    d += fmt::format("EIA        {}\n", s.array_summary);
  const std::string key_rule =
      o.keyframe_interval == 0 ? fmt::format("{} keyframes placed by motion (at most {:g} px, {} frames apart)", so.keys.size(),
                                             o.keyframe_motion, o.max_keyframe_interval)
                               : fmt::format("keyframe every {}", o.keyframe_interval);
  if (so.method == holoray::Method::reproject)
    d += fmt::format("method     reproject: {}, reuse {}, fill {}, reach {}{}\n", key_rule, s.reuse, o.fill, o.reach,
                     o.leak_check ? "" : ", no leak check");
  else if (so.method == holoray::Method::reverse)
    d += fmt::format("method     reverse: {}, eye rays traced, reuse {}\n", key_rule, s.reuse);
  else if (so.integrator == holoray::Integrator::path)
    d += fmt::format("method     full path tracing{}\n", so.animated_seed ? fmt::format(", seed {} + the frame's number", so.seed)
                                                       : so.seed != 0   ? fmt::format(", seed {}", so.seed)
                                                                        : "");
  else
    d += "method     full ray tracing\n";
  return d;
}

}  // namespace

Animation::Animation(const std::string& shot_path, const AnimateOptions& o) : state_(std::make_unique<AnimationState>()) {
  AnimationState& s = *state_;
  SequenceOptions& so = s.so;
  s.options = o;
  s.choice = o.camera ? frame_camera_desc(*o.camera) : FrameCameraDesc{};
  check_light(o.integrator, o.environment, o.cache.enabled);
  choose_method(o, s);
  check_numbers(o, so);

  s.shot = read_shot(shot_path, o);
  const ShotFrames& shot = *s.shot;
  so.encoding = o.encoding ? (*o.encoding == Encoding::srgb ? holoray::Encoding::srgb : holoray::Encoding::linear)
                : shot.shot().objects.empty() ? holoray::Encoding::linear
                                              : holoray::default_encoding(shot.shot().objects.front().scene);
  if (o.frames) {
    const auto [first, last] = *o.frames;
    if (first < 0 || last < first || last >= shot.frame_count())
      throw std::invalid_argument(fmt::format("frames: the shot has frames 0 to {}, got {}:{}", shot.frame_count() - 1, first, last));
  }
  size_the_view(shot, so);
  if (o.keyframe_interval == 0 && so.method != holoray::Method::full)
    so.keys = KeyframePlanner(shot).keyframes(o.keyframe_motion, o.max_keyframe_interval);
  const holoray::LensArray first(shot.camera(0));
  if (o.cache.enabled) {
    holoray::ShadowCacheOptions co;
    co.cell_size = o.cache.cell * first.desc().pitch;
    co.memory_limit_bytes = static_cast<uint64_t>(o.cache.memory_mib * 1048576.0);
    s.cache = std::make_unique<ShadowCache>(shot.scene(), co);
    so.cache = s.cache.get();
  }
  size_the_frames(first, s);
  if (o.integrator == Integrator::path) {
    s.environment = environment_of(o.environment, shot.scenes().front());
    so.integrator = holoray::Integrator::path;
    so.environment = s.environment.get();
    so.principled = o.blender_principled;
    so.skip_headlights = o.environment.given();
    so.seed = o.seed;
    so.animated_seed = o.animated_seed;
  }
  if (const DeviceChoice device = parse_device(o.device); device.gpu) {
    RenderOptions ro;
    ro.cache = o.cache;
    const FrameCamera camera0 = so.frame_camera ? make_frame_camera(*so.frame_camera, shot.viewpoint(0), "the shot")
                                                : FrameCamera{holoray::LensArray(shot.camera(0))};
    // The frames' settings as far as they are known before the first
    // (its emitters are each frame's own: that frame lays them out).
    holoray::RenderSettings first_settings = file_settings(shot.scene());
    first_settings.integrator = so.integrator;
    first_settings.environment = so.environment;
    first_settings.principled = so.principled;
    first_settings.skip_headlights = so.skip_headlights;
    first_settings.sample_salt = so.seed;
    s.gpu = std::make_unique<GpuExecutor>(device, RenderContext(shot.scene(), first_settings), camera0, ro);
    so.trace = [gpu = s.gpu.get()](const RenderContext& context, const FrameCamera& camera, const holoray::RenderOptions& o,
                                   holoray::RenderStats& stats) {
      RenderStats on_gpu;
      FrameBuffers fb = gpu->render(context, camera, o.aovs, o.spp, std::nullopt, on_gpu);
      stats.rays = {on_gpu.rays.eye, on_gpu.rays.shadow, on_gpu.rays.reflected, on_gpu.rays.refracted, 0, 0};
      stats.trace_seconds = on_gpu.trace_seconds;
      return fb;
    };
  }
  if (o.frames || o.done)
    so.done = [this](int f) {
      const AnimateOptions& opt = state_->options;
      return (opt.frames && (f < (*opt.frames)[0] || f > (*opt.frames)[1])) || (opt.done && opt.done(f));
    };
  so.next_group = o.next_group;
  so.stop = o.stop;

  s.array_summary = fmt::format("{}x{} px, {} grid, {}x{} lenses x {} px, {}", first.width(), first.height(),
                                to_string(first.desc().grid), first.lens_count_x(), first.lens_count_y(),
                                first.desc().pixels_per_lens, to_string(first.desc().mode));
  s.describe = describe_animation(o, s);
}

Animation::~Animation() = default;
Animation::Animation(Animation&&) noexcept = default;
Animation& Animation::operator=(Animation&&) noexcept = default;

int Animation::frame_count() const { return state_->shot->frame_count(); }
double Animation::fps() const { return state_->shot->shot().fps; }
int Animation::width() const { return state_->width; }
int Animation::height() const { return state_->height; }
Method Animation::method() const { return state_->method; }
std::string Animation::reuse() const { return state_->reuse; }
std::string Animation::describe() const { return state_->describe; }
std::string Animation::array_summary() const { return state_->array_summary; }
std::string Animation::device_name() const { return state_->gpu ? state_->gpu->name() : ""; }
Encoding Animation::encoding() const {
  return state_->so.encoding == holoray::Encoding::srgb ? Encoding::srgb : Encoding::linear;
}

std::vector<int> Animation::keyframes() const {
  if (state_->so.method == holoray::Method::full) return {};
  return sequence_keyframes(frame_count(), state_->so);
}

std::vector<Animation::FileWarnings> Animation::warnings() const {
  std::vector<FileWarnings> out;
  std::set<std::string> seen;  // several shot objects may place the same file
  for (const SceneDesc& d : state_->shot->scenes())
    if (seen.insert(d.source).second) out.push_back({d.source, d.warnings, d.warning_count});
  return out;
}

int Animation::object_count() const { return static_cast<int>(state_->shot->shot().objects.size()); }

std::vector<std::array<int, 2>> Animation::groups() const {
  std::vector<std::array<int, 2>> out;
  for (const FrameGroup& g : frame_groups(frame_count(), state_->so)) out.push_back({g.first, g.last});
  return out;
}

void Animation::run(const std::function<void(int, const Image&, const FrameRow&)>& emit) {
  AnimationState& s = *state_;
  std::unique_ptr<tbb::global_control> thread_cap;
  if (s.options.threads > 0)
    thread_cap = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, s.options.threads);
  render_sequence(*s.shot, s.so, [&](int f, const ImageBuffer& colour, const FrameReport& r) {
    // The sequence keeps its frame buffer for the next frame: hand out a copy.
    ImageBuffer copy = colour;
    emit(f, detail::ImageAccess::wrap(std::move(copy)), to_api(r));
  });
}

std::string report_markdown(const std::string& title, const std::vector<std::string>& lines, const std::vector<FrameRow>& rows) {
  std::vector<FrameReport> reports;
  for (const FrameRow& r : rows) reports.push_back(from_api(r));
  return markdown_report(title, lines, reports);
}

RunTotals totals(const std::vector<FrameRow>& rows) {
  std::vector<FrameReport> reports;
  for (const FrameRow& r : rows) reports.push_back(from_api(r));
  const RunSummary s = summarise(reports);
  return {s.accelerated_seconds, s.full_seconds, s.saved_percent(), s.mean_psnr};
}

}  // namespace holoray::api
