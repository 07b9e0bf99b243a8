// holoray/temporal: the tracing schedule of an animated shot (paper §4, §7).
// `full` ray traces every frame. `reproject` and `reverse` ray trace every
// K-th frame and the last (the keyframes), keep their point images, and build
// each frame between two keyframes from them: `reproject` by the paper's
// forward splat (reproject.hpp) and filling (fill.hpp), `reverse` by tracing
// its eye rays and reusing the keyframes' shading (reverse.hpp).
#pragma once

#include <array>
#include <functional>
#include <optional>
#include <vector>

#include "display/display_desc.hpp"
#include "render/frame_camera.hpp"
#include "image/image_io.hpp"
#include "image/metrics.hpp"
#include "shot/shot_frames.hpp"
#include "temporal/fill.hpp"
#include "temporal/reproject.hpp"
#include "temporal/reverse.hpp"

namespace holoray {

enum class Method {
  full,       ///< trace every frame
  reproject,  ///< keyframes + forward reprojection of their point images (paper §4-5, reproject.hpp)
  reverse,    ///< keyframes + reverse reprojection: eye rays traced, shading reused (reverse.hpp)
};

struct SequenceOptions {
  Method method = Method::full;
  int keyframe_interval = 8;  ///< K >= 1
  /// The keyframes, when not every K-th (KeyframePlanner::keyframes): sorted,
  /// from frame 0 to the last frame.
  std::vector<int> keys;
  ReprojectOptions reproject;  ///< Method::reproject
  ReverseOptions reverse;      ///< Method::reverse
  Fill fill = Fill::trace;
  /// Fill::interpolate only: a frame whose holes (missed, leaks, rejected)
  /// exceed this share of its pixels is rebuilt by tracing them instead
  /// (FrameReport::rebuilt). Interpolating across holes that wide scored
  /// below holding the nearest keyframe (issue 12: 62 % holes, 20.5 dB
  /// against 31.8 dB held); no reference is needed to apply it.
  double max_interpolated_share = 0.05;
  int threads = 0;
  /// Also ray trace every reprojected frame in full, time it and compare
  /// (for the report): FrameReport::reference and ::difference.
  bool reference = false;
  Encoding encoding = Encoding::linear;  ///< the 8-bit quantisation compared against
  /// Method::full only: render each frame through this camera placed by the
  /// frame's viewpoint (ShotFrames::viewpoint) instead of the shot's array:
  /// pinhole previews of a shot's camera path (a size of 0 is the first
  /// scene's, filled in by the caller), a display's native panel images, a
  /// Looking Glass's, as `render` renders them.
  std::optional<FrameCameraDesc> frame_camera;
  /// Method::full only: traces each frame in place of the CPU path (the GPU
  /// path: api/gpu_executor.hpp), given the frame's scene (moved there) and
  /// camera; what render_through() gives. Null: the CPU path.
  std::function<FrameBuffers(const RenderContext&, const FrameCamera&, const RenderOptions&, RenderStats&)> trace;
  /// Shadow cache (render/shadow_cache.hpp) for traced frames, filling and
  /// geometry reuse; null: trace every shadow ray. Built on the shot's scene;
  /// it lives across frames while nothing moves. The reference frames
  /// (`reference`) are always traced without it.
  ShadowCache* cache = nullptr;
  /// Frames already finished (resume): not emitted; a keyframe among them is
  /// still traced when a frame after it needs its point image.
  std::function<bool(int frame)> done;
  /// The groups (frame_groups) this worker renders, asked before each: the
  /// next group's index, nullopt when there are no more. Null: every group,
  /// in order. Reuse stays inside a worker: a group that starts at the
  /// keyframe the previous one ended on reuses its point image; any other
  /// traces its first keyframe (a group costs one keyframe more when it does
  /// not follow on). Frames outside the groups handed out are not rendered.
  std::function<std::optional<size_t>()> next_group;
  /// Asked before each frame is started (keyframe or reprojected): true stops
  /// the sequence there, after the frames already emitted (SIGINT, SIGTERM).
  std::function<bool()> stop;
  /// Method::full only: the path integrator (render_context.hpp,
  /// RenderSettings), its environment (not owned; null: the background
  /// colour), glTF materials as Blender's Principled, and the readers'
  /// headlights left out. Each frame's emissive surfaces are drawn as lights
  /// where that frame's transforms put them.
  Integrator integrator = Integrator::whitted;
  const EnvironmentMap* environment = nullptr;
  bool principled = false;
  bool skip_headlights = false;
  /// The path integrator's samples (RenderSettings::sample_salt): `seed` for
  /// every frame, plus the frame's number with `animated_seed`.
  uint32_t seed = 0;
  bool animated_seed = false;
};

/// What one frame cost and how it was made (the paper's Tables 1 and 2).
struct FrameReport {
  int frame = 0;
  bool keyframe = false;
  double seconds = 0;            ///< tracing, or reprojection + filling (no file I/O)
  double reference_seconds = 0;  ///< full ray tracing of this frame (keyframes: = seconds)
  int64_t pixels = 0;
  int64_t reprojected = 0, missed = 0, leaks = 0, rejected = 0, traced = 0, interpolated = 0;
  RayCounts rays;
  ReprojectedFrame::Seconds stages;  ///< reprojected frames: time per stage
  std::optional<ImageDifference> difference;  ///< against the reference (when asked)
  /// Holding the nearest keyframe instead (the do-nothing baseline) against
  /// the same reference; reprojected frames only.
  std::optional<ImageDifference> hold;
  bool rebuilt = false;  ///< its holes were traced, not interpolated (max_interpolated_share)
  int copied_from = -1;  ///< a copy of this keyframe (ReprojectedFrame::copied_from); -1 otherwise
};

/// The keyframes of a shot of `frames` frames at interval K: 0, K, 2K, ... and the last.
std::vector<int> keyframes(int frames, int interval);

/// A unit of scheduling (issue 15): the frames [first, last] that one worker
/// renders together so that reuse stays inside it. Full tracing: one frame.
/// Reuse: keyframe keys[k] and the frames before keys[k + 1]; the last group
/// also holds the last keyframe. A one-frame shot is one group.
struct FrameGroup {
  int first = 0, last = 0;
};

/// The keyframes render_sequence uses: options.keys, else every K-th frame
/// and the last. Throws std::invalid_argument as render_sequence does.
std::vector<int> sequence_keyframes(int frames, const SequenceOptions& options);

/// The groups of a shot of `frames` frames under `options`, in frame order
/// (SequenceOptions::next_group hands out their indices).
std::vector<FrameGroup> frame_groups(int frames, const SequenceOptions& options);

/// Renders the shot in frame order and hands each finished frame to
/// `emit(frame, colour, report)` (with next_group: the groups it hands
/// out, each in frame order). Throws std::invalid_argument for K < 1 or a
/// shot with spp > 1 under reprojection (point images hold the centre sample).
void render_sequence(ShotFrames& shot, const SequenceOptions& options,
                     const std::function<void(int, const ImageBuffer&, const FrameReport&)>& emit);

}  // namespace holoray
