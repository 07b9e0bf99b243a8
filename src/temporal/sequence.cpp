#include "temporal/sequence.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <stdexcept>
#include <tuple>

#include "holoray/stopwatch.hpp"
#include "render/emitters.hpp"
#include "render/shadow_cache.hpp"

namespace holoray {

namespace {

struct Traced {
  LensArray camera;
  FrameBuffers buffers;
  RenderStats stats;
  double seconds = 0;
};

// Frame `frame` traced in full through `scene` (the shot moved there).
Traced trace_frame(const ShotFrames& shot, const RenderContext& scene, int frame, bool keep_points, int threads) {
  scene.accel().build();  // before the clock, on all cores (AccelScene::build)
  RenderOptions ro;
  ro.spp = shot.shot().spp;
  ro.threads = threads;
  ro.primary_hits = keep_points;
  Traced t{LensArray(shot.camera(frame)), {}, {}, 0};
  ro.style = preferred_style(t.camera.desc());  // as the keyframes of reuse are traced
  const auto start = Clock::now();
  t.buffers = render_frame(scene, t.camera, ro, t.stats);
  t.seconds = seconds_since(start);
  return t;
}

// The groups this worker renders: SequenceOptions::next_group's, else all
// `count` of them in order.
std::function<std::optional<size_t>()> group_source(const SequenceOptions& opt, size_t count) {
  if (opt.next_group) return opt.next_group;
  return [count, g = size_t{0}]() mutable { return g < count ? std::optional(g++) : std::nullopt; };
}

}  // namespace

std::vector<int> keyframes(int frames, int interval) {
  std::vector<int> keys;
  if (frames < 1 || interval < 1) return keys;
  for (int f = 0; f < frames; f += interval) keys.push_back(f);
  if (keys.back() != frames - 1) keys.push_back(frames - 1);
  return keys;
}

std::vector<int> sequence_keyframes(int frames, const SequenceOptions& opt) {
  if (opt.keyframe_interval < 1)
    throw std::invalid_argument(fmt::format("the keyframe interval must be at least 1, got {}", opt.keyframe_interval));
  const std::vector<int> keys = opt.keys.empty() ? keyframes(frames, opt.keyframe_interval) : opt.keys;
  if (keys.empty() || keys.front() != 0 || keys.back() != frames - 1 || !std::is_sorted(keys.begin(), keys.end()) ||
      std::adjacent_find(keys.begin(), keys.end()) != keys.end())
    throw std::invalid_argument(fmt::format("the keyframes must rise strictly from frame 0 to the last frame, {}", frames - 1));
  return keys;
}

std::vector<FrameGroup> frame_groups(int frames, const SequenceOptions& opt) {
  std::vector<FrameGroup> groups;
  if (opt.method == Method::full) {
    for (int f = 0; f < frames; ++f) groups.push_back({f, f});
    return groups;
  }
  const std::vector<int> keys = sequence_keyframes(frames, opt);
  if (keys.size() == 1) return {{0, 0}};
  for (size_t k = 0; k + 1 < keys.size(); ++k)
    groups.push_back({keys[k], k + 2 == keys.size() ? keys[k + 1] : keys[k + 1] - 1});
  return groups;
}

namespace {

using Emit = std::function<void(int, const ImageBuffer&, const FrameReport&)>;

// One call of render_sequence: the shot, its options, and the steps that
// trace, reproject and report its frames.
class SequenceRun {
 public:
  SequenceRun(ShotFrames& shot, const SequenceOptions& opt, const Emit& emit)
      : shot_(shot), opt_(opt), emit_(emit), panel_frames_(opt.frame_camera.has_value()) {
    // What each frame's render asks of the scene (render_context.hpp). EIA
    // frames share the shot's pitch, gap and pixels: one pixel footprint.
    settings_ = shot.settings();
    settings_.shadow_cache = opt.cache;
    settings_.integrator = opt.integrator;
    settings_.environment = opt.environment;
    settings_.principled = opt.principled;
    settings_.skip_headlights = opt.skip_headlights;
    if (!panel_frames_) settings_.footprint = {0, pixel_angle(shot.camera(0))};
  }

  /// Method::full: every frame traced, a group each (frame_groups).
  void trace_every_frame() {
    auto next_group = group_source(opt_, static_cast<size_t>(shot_.frame_count()));
    while (const auto g = next_group()) {
      const int f = static_cast<int>(*g);
      if (done(f)) continue;
      if (stop()) return;
      if (panel_frames_ || opt_.trace) {
        trace_view(f);
        continue;
      }
      const Traced t = trace_frame(shot_, seek(f), f, false, opt_.threads);
      emit_(f, t.buffers.colour, keyframe_report(f, t.buffers.colour, t.stats, t.seconds));
    }
  }

  /// Reuse: keyframes traced, the frames between them reprojected. Group k
  /// (frame_groups) owns keyframe keys[k] and the frames up to the next
  /// keyframe, the last group also the last keyframe. A group that follows
  /// the previous one on this worker starts from its later keyframe.
  void reproject_between_keyframes(const std::vector<int>& keys) {
    if (keys.size() == 1) {  // a one-frame shot: one group, its only keyframe
      auto next_group = group_source(opt_, 1);
      while (next_group()) {
        if (done(0) || stop()) continue;
        auto [image, report] = trace_key(0);
        emit_(0, image->colour, report);
      }
      return;
    }
    std::unique_ptr<PointImage> prev;
    FrameReport prev_report;
    const size_t groups = keys.size() - 1;
    auto next_group = group_source(opt_, groups);
    while (const auto g = next_group()) {
      const size_t k = *g;
      const int f0 = keys[k], f1 = keys[k + 1];
      const bool last = k + 1 == groups;
      bool need_points = false;
      for (int f = f0 + 1; f < f1; ++f) need_points = need_points || !done(f);
      const bool emit_f1 = last && !done(f1);
      if (!need_points && !emit_f1 && done(f0)) continue;
      if (!prev || prev->frame != f0) {
        if (stop()) return;
        std::tie(prev, prev_report) = trace_key(f0);
      }
      if (!done(f0)) emit_(f0, prev->colour, prev_report);
      if (!need_points && !emit_f1) continue;
      if (stop()) return;
      auto [next, key1_report] = trace_key(f1);
      for (int f = f0 + 1; f < f1; ++f) {
        if (done(f)) continue;
        if (stop()) return;
        reproject_frame(f, *prev, *next);
      }
      if (emit_f1) emit_(f1, next->colour, key1_report);
      prev = std::move(next);
      prev_report = std::move(key1_report);
    }
  }

 private:
  bool done(int f) const { return opt_.done && opt_.done(f); }
  bool stop() const { return opt_.stop && opt_.stop(); }

  // The scene moved to frame f, the cache cleared if anything moved there.
  RenderContext seek(int f) {
    shot_.seek(f);
    if (opt_.cache) opt_.cache->sync();
    if (settings_.integrator == Integrator::path) {
      // The emitters where this frame's transforms put them.
      emitters_ = std::make_unique<EmissiveTriangles>(shot_.scene());
      settings_.emitters = emitters_->empty() ? nullptr : emitters_.get();
      settings_.skip_headlights = opt_.skip_headlights || !emitters_->empty();
      settings_.sample_salt = opt_.seed + (opt_.animated_seed ? static_cast<uint32_t>(f) : 0u);
    }
    return RenderContext(shot_.scene(), settings_);
  }

  // Full ray tracing of a frame for the report: the baseline, without the
  // cache (the same scene, another render of it).
  Traced reference(int f) {
    RenderSettings full = settings_;
    full.shadow_cache = nullptr;
    shot_.seek(f);
    return trace_frame(shot_, RenderContext(shot_.scene(), full), f, false, opt_.threads);
  }

  FrameReport keyframe_report(int f, const ImageBuffer& colour, const RenderStats& stats, double seconds) {
    FrameReport r;
    r.frame = f;
    r.keyframe = true;
    r.seconds = r.reference_seconds = seconds;
    r.pixels = static_cast<int64_t>(colour.width) * colour.height;
    r.traced = r.pixels;
    r.rays = stats.rays;
    if (opt_.reference) {
      if (opt_.cache) {
        const Traced ref = reference(f);
        r.reference_seconds = ref.seconds;
        r.difference = compare_images(quantize_8bit(ref.buffers.colour, opt_.encoding), quantize_8bit(colour, opt_.encoding));
      } else {
        r.difference = ImageDifference{{0, 0, 0}, 0, r.pixels};
      }
    }
    return r;
  }

  // A view of frame f's viewpoint: a pinhole preview, a Looking Glass, or a
  // display's panel (through the integral camera when it is an ordinary
  // EIA, as `render --display` does); or, traced by SequenceOptions::trace,
  // the shot's own lens array.
  void trace_view(int f) {
    RenderContext scene = seek(f);
    const Viewpoint vp = shot_.viewpoint(f);
    RenderOptions ro;
    ro.spp = shot_.shot().spp;
    ro.threads = opt_.threads;
    RenderStats stats;
    const auto start = Clock::now();
    const FrameCamera camera =
        opt_.frame_camera ? make_frame_camera(*opt_.frame_camera, vp, "the shot") : FrameCamera{LensArray(shot_.camera(f))};
    // Mesh textures take the MIP level of what one pixel sees, as in `render`.
    if (const auto angle = camera.pixel_angle()) {
      RenderSettings s = scene.settings();
      s.footprint = {0, *angle};
      scene = RenderContext(scene.scene(), s);
    }
    const FrameBuffers b = opt_.trace ? opt_.trace(scene, camera, ro, stats) : render_through(scene, camera, ro, stats);
    emit_(f, b.colour, keyframe_report(f, b.colour, stats, seconds_since(start)));
  }

  // A keyframe traced, with its point image (transforms at its time) and its report.
  std::pair<std::unique_ptr<PointImage>, FrameReport> trace_key(int f) {
    if (opt_.method == Method::reverse) {
      const RenderContext scene = seek(f);
      RenderStats stats;
      const auto start = Clock::now();
      auto image = std::make_unique<PointImage>(
          trace_point_image(scene, LensArray(shot_.camera(f)), f, opt_.reverse.reuse, opt_.threads, stats));
      const double seconds = seconds_since(start);
      FrameReport report = keyframe_report(f, image->colour, stats, seconds);
      return {std::move(image), std::move(report)};
    }
    Traced t = trace_frame(shot_, seek(f), f, true, opt_.threads);
    FrameReport report = keyframe_report(f, t.buffers.colour, t.stats, t.seconds);
    auto image = std::make_unique<PointImage>(
        PointImage{f, t.camera, std::move(t.buffers.primary), std::move(t.buffers.colour), {}, {}, {}, {}, {}, {}});
    image->record_groups(shot_.scene().accel());
    return {std::move(image), std::move(report)};
  }

  // Frame f between keyframes prev and next: reprojected, its holes filled
  // (Method::reproject), reported, emitted.
  void reproject_frame(int f, const PointImage& prev, const PointImage& next) {
    const RenderContext scene = seek(f);
    const LensArray camera(shot_.camera(f));
    const auto start = Clock::now();
    ReprojectedFrame rf = opt_.method == Method::reverse
                              ? reverse_reproject(scene, camera, f, &prev, &next, opt_.reverse)
                              : reproject(scene, camera, f, &prev, &next, opt_.reproject);
    FrameReport r;
    r.frame = f;
    r.pixels = camera.pixel_count();
    r.missed = static_cast<int64_t>(rf.count(PixelStatus::missed));
    r.leaks = static_cast<int64_t>(rf.count(PixelStatus::leak));
    r.rejected = static_cast<int64_t>(rf.count(PixelStatus::rejected));
    r.reprojected = static_cast<int64_t>(rf.count(PixelStatus::reprojected));
    r.copied_from = rf.copied_from;
    Fill fill = opt_.fill;
    const int64_t holes = r.missed + r.leaks + r.rejected;
    if (fill == Fill::interpolate && static_cast<double>(holes) > opt_.max_interpolated_share * r.pixels) {
      fill = Fill::trace;
      r.rebuilt = true;
    }
    if (opt_.method == Method::reproject) fill_missed(scene, camera, fill, opt_.threads, rf);
    r.seconds = seconds_since(start);
    r.traced = static_cast<int64_t>(rf.count(PixelStatus::traced));
    r.interpolated = static_cast<int64_t>(rf.count(PixelStatus::interpolated));
    r.rays = rf.rays;
    r.stages = rf.seconds;
    if (opt_.reference) {
      const Traced ref = reference(f);
      r.reference_seconds = ref.seconds;
      const ImageBuffer truth = quantize_8bit(ref.buffers.colour, opt_.encoding);
      r.difference = compare_images(truth, quantize_8bit(rf.colour, opt_.encoding));
      const PointImage& nearest = f - prev.frame <= next.frame - f ? prev : next;
      r.hold = compare_images(truth, quantize_8bit(nearest.colour, opt_.encoding));
    }
    emit_(f, rf.colour, r);
  }

  ShotFrames& shot_;
  const SequenceOptions& opt_;
  const Emit& emit_;
  const bool panel_frames_;
  RenderSettings settings_;
  std::unique_ptr<EmissiveTriangles> emitters_;  // the path integrator's, at the frame sought
};

}  // namespace

void render_sequence(ShotFrames& shot, const SequenceOptions& opt, const Emit& emit) {
  if (opt.frame_camera && opt.method != Method::full)
    throw std::invalid_argument("pinhole and display frames are traced in full (reuse works on elemental images)");
  if (opt.method == Method::full) {
    SequenceRun(shot, opt, emit).trace_every_frame();
    return;
  }
  if (shot.shot().spp > 1)
    throw std::invalid_argument(fmt::format(
        "reprojection needs spp = 1 (the shot asks for {}): point images hold the pixel-centre sample", shot.shot().spp));
  const std::vector<int> keys = sequence_keyframes(shot.frame_count(), opt);
  SequenceRun(shot, opt, emit).reproject_between_keyframes(keys);
}

}  // namespace holoray
