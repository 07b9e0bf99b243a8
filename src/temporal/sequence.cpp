#include "temporal/sequence.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <stdexcept>
#include <tuple>

#include "holoray/stopwatch.hpp"
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

void render_sequence(ShotFrames& shot, const SequenceOptions& opt,
                     const std::function<void(int, const ImageBuffer&, const FrameReport&)>& emit) {
  const int frames = shot.frame_count();
  const bool panel_frames = opt.frame_camera.has_value();
  // What each frame's render asks of the scene (render_context.hpp). EIA
  // frames share the shot's pitch, gap and pixels: one pixel footprint.
  RenderSettings settings = shot.settings();
  settings.shadow_cache = opt.cache;
  if (!panel_frames) settings.footprint = {0, pixel_angle(shot.camera(0))};
  // The scene moved to frame f, the cache cleared if anything moved there.
  auto seek = [&](int f) {
    shot.seek(f);
    if (opt.cache) opt.cache->sync();
    return RenderContext(shot.scene(), settings);
  };
  // Full ray tracing of a frame for the report: the baseline, without the
  // cache (the same scene, another render of it).
  auto reference = [&](int f) {
    RenderSettings full = settings;
    full.shadow_cache = nullptr;
    shot.seek(f);
    return trace_frame(shot, RenderContext(shot.scene(), full), f, false, opt.threads);
  };
  auto done = [&](int f) { return opt.done && opt.done(f); };
  auto stop = [&] { return opt.stop && opt.stop(); };
  auto keyframe_report = [&](int f, const ImageBuffer& colour, const RenderStats& stats, double seconds) {
    FrameReport r;
    r.frame = f;
    r.keyframe = true;
    r.seconds = r.reference_seconds = seconds;
    r.pixels = static_cast<int64_t>(colour.width) * colour.height;
    r.traced = r.pixels;
    r.rays = stats.rays;
    if (opt.reference) {
      if (opt.cache) {
        const Traced ref = reference(f);
        r.reference_seconds = ref.seconds;
        r.difference = compare_images(quantize_8bit(ref.buffers.colour, opt.encoding),
                                      quantize_8bit(colour, opt.encoding));
      } else {
        r.difference = ImageDifference{{0, 0, 0}, 0, r.pixels};
      }
    }
    return r;
  };

  if (panel_frames && opt.method != Method::full)
    throw std::invalid_argument("pinhole and display frames are traced in full (reuse works on elemental images)");
  if (opt.method == Method::full) {
    // One group per frame (frame_groups).
    auto next_group = group_source(opt, static_cast<size_t>(frames));
    while (const auto g = next_group()) {
      const int f = static_cast<int>(*g);
      if (done(f)) continue;
      if (stop()) return;
      if (panel_frames) {
        // A view of the frame's viewpoint: a pinhole preview, a Looking Glass, or a display's
        // panel (through the integral camera when it is an ordinary EIA, as
        // `render --display` does).
        RenderContext scene = seek(f);
        const Viewpoint vp = shot.viewpoint(f);
        RenderOptions ro;
        ro.spp = shot.shot().spp;
        ro.threads = opt.threads;
        RenderStats stats;
        const auto start = Clock::now();
        const FrameCamera camera = make_frame_camera(*opt.frame_camera, vp, "the shot");
        // Mesh textures take the MIP level of what one pixel sees, as in `render`.
        if (const auto angle = camera.pixel_angle()) {
          RenderSettings s = scene.settings();
          s.footprint = {0, *angle};
          scene = RenderContext(scene.scene(), s);
        }
        const FrameBuffers b = render_through(scene, camera, ro, stats);
        emit(f, b.colour, keyframe_report(f, b.colour, stats, seconds_since(start)));
        continue;
      }
      const Traced t = trace_frame(shot, seek(f), f, false, opt.threads);
      emit(f, t.buffers.colour, keyframe_report(f, t.buffers.colour, t.stats, t.seconds));
    }
    return;
  }

  if (shot.shot().spp > 1)
    throw std::invalid_argument(fmt::format(
        "reprojection needs spp = 1 (the shot asks for {}): point images hold the pixel-centre sample", shot.shot().spp));
  const std::vector<int> keys = sequence_keyframes(frames, opt);

  // A keyframe traced, with its point image (transforms at its time) and its report.
  auto trace_key = [&](int f) {
    if (opt.method == Method::reverse) {
      const RenderContext scene = seek(f);
      RenderStats stats;
      const auto start = Clock::now();
      auto image = std::make_unique<PointImage>(
          trace_point_image(scene, LensArray(shot.camera(f)), f, opt.reverse.reuse, opt.threads, stats));
      const double seconds = seconds_since(start);
      FrameReport report = keyframe_report(f, image->colour, stats, seconds);
      return std::pair{std::move(image), std::move(report)};
    }
    Traced t = trace_frame(shot, seek(f), f, true, opt.threads);
    FrameReport report = keyframe_report(f, t.buffers.colour, t.stats, t.seconds);
    auto image = std::make_unique<PointImage>(
        PointImage{f, t.camera, std::move(t.buffers.primary), std::move(t.buffers.colour), {}, {}, {}, {}, {}, {}});
    image->record_groups(shot.scene().accel());
    return std::pair{std::move(image), std::move(report)};
  };

  if (keys.size() == 1) {  // a one-frame shot: one group, its only keyframe
    auto next_group = group_source(opt, 1);
    while (next_group()) {
      if (done(0) || stop()) continue;
      auto [image, report] = trace_key(0);
      emit(0, image->colour, report);
    }
    return;
  }
  // Group k (frame_groups) owns keyframe keys[k] and the frames up to the
  // next keyframe, the last group also the last keyframe. A group that
  // follows the previous one on this worker starts from its later keyframe.
  std::unique_ptr<PointImage> prev;
  FrameReport prev_report;
  const size_t groups = keys.size() - 1;
  auto next_group = group_source(opt, groups);
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
    if (!done(f0)) emit(f0, prev->colour, prev_report);
    if (!need_points && !emit_f1) continue;
    if (stop()) return;
    auto [next, key1_report] = trace_key(f1);

    for (int f = f0 + 1; f < f1; ++f) {
      if (done(f)) continue;
      if (stop()) return;
      const RenderContext scene = seek(f);
      const LensArray camera(shot.camera(f));
      const auto start = Clock::now();
      ReprojectedFrame rf = opt.method == Method::reverse
                                ? reverse_reproject(scene, camera, f, prev.get(), next.get(), opt.reverse)
                                : reproject(scene, camera, f, prev.get(), next.get(), opt.reproject);
      FrameReport r;
      r.frame = f;
      r.pixels = camera.pixel_count();
      r.missed = static_cast<int64_t>(rf.count(PixelStatus::missed));
      r.leaks = static_cast<int64_t>(rf.count(PixelStatus::leak));
      r.rejected = static_cast<int64_t>(rf.count(PixelStatus::rejected));
      r.reprojected = static_cast<int64_t>(rf.count(PixelStatus::reprojected));
      r.copied_from = rf.copied_from;
      Fill fill = opt.fill;
      const int64_t holes = r.missed + r.leaks + r.rejected;
      if (fill == Fill::interpolate && static_cast<double>(holes) > opt.max_interpolated_share * r.pixels) {
        fill = Fill::trace;
        r.rebuilt = true;
      }
      if (opt.method == Method::reproject) fill_missed(scene, camera, fill, opt.threads, rf);
      r.seconds = seconds_since(start);
      r.traced = static_cast<int64_t>(rf.count(PixelStatus::traced));
      r.interpolated = static_cast<int64_t>(rf.count(PixelStatus::interpolated));
      r.rays = rf.rays;
      r.stages = rf.seconds;
      if (opt.reference) {
        const Traced ref = reference(f);
        r.reference_seconds = ref.seconds;
        const ImageBuffer truth = quantize_8bit(ref.buffers.colour, opt.encoding);
        r.difference = compare_images(truth, quantize_8bit(rf.colour, opt.encoding));
        const PointImage& nearest = f - f0 <= f1 - f ? *prev : *next;
        r.hold = compare_images(truth, quantize_8bit(nearest.colour, opt.encoding));
      }
      emit(f, rf.colour, r);
    }
    if (emit_f1) emit(f1, next->colour, key1_report);
    prev = std::move(next);
    prev_report = std::move(key1_report);
  }
}

}  // namespace holoray
