// holoray public API: an animated shot (docs/shot-format.md) frame by frame,
// with the keyframe reuse of `holoray animate` (paper §4, §7).
//
//   Animation a("shot.toml", options);   // shot read, options checked
//   a.run([](int frame, const Image& colour, const FrameRow& row) { ... });
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "holoray/camera.hpp"
#include "holoray/export.hpp"
#include "holoray/image.hpp"
#include "holoray/render.hpp"

namespace holoray::api {

/// How frames between keyframes are made (docs/guide/animation.md).
enum class Method {
  automatic,  ///< reverse for lens arrays, full for the other cameras
  full,       ///< trace every frame
  reproject,  ///< the paper's forward reprojection of keyframe point images
  reverse,    ///< every eye ray traced, keyframe shading reused
};

struct AnimateOptions {
  Method method = Method::automatic;
  /// reproject: "geometry" (default) or "color"; reverse: "color" (default)
  /// or "visibility". Empty: the method's default.
  std::string reuse;
  std::string fill = "trace";  ///< missed pixels: "trace" or "interpolate"
  std::string reach = "near";  ///< reproject: "near" (one lens per point) or "all"
  bool leak_check = true;
  double rebuild_above_percent = 5;  ///< fill interpolate: trace a frame's holes past this share
  int keyframe_interval = 8;         ///< K >= 1; 0: placed by motion (keyframe_motion)
  double keyframe_motion = 4;        ///< pixels a point image may move from its keyframe
  int max_keyframe_interval = 32;
  /// A pinhole, display or Looking Glass camera placed by each frame's
  /// viewpoint (traced in full); default: the shot's lens array.
  std::optional<Camera> camera;
  int threads = 0;  ///< 0: all cores
  /// How the shot's scene files are read: a camera_name replaces the shot
  /// file's `camera_name`; texture_paths are searched after its `texture_path`.
  LoadOptions load;
  ShadowCacheOptions cache;
  /// Also trace every reused frame in full and compare (FrameRow::difference,
  /// reference_seconds): the report's measurements.
  bool reference = false;
  /// PNG encoding the comparisons quantise to; nullopt: srgb when the shot's
  /// first scene is a mesh file, else linear (the CLI's --encoding auto).
  std::optional<Encoding> encoding;
  std::optional<std::array<int, 2>> frames;  ///< only frames [first, last] and the keyframes they need
  /// Frames already finished (resume): not rendered again.
  std::function<bool(int frame)> done;
  /// The frame groups this worker renders, asked before each (an index into
  /// Animation::groups()); nullopt: no more. Null: every group, in order.
  std::function<std::optional<size_t>()> next_group;
  /// Asked before each frame: true ends the run after the frames already
  /// emitted (a signal, a closed iterator).
  std::function<bool()> stop;
  /// Where frames are traced, as RenderOptions::device: "cpu", "gpu" or
  /// "gpu:N". On a GPU every frame is traced in full (reuse, `reference` and
  /// the cache are the CPU path's and refused), the scene laid out again on
  /// the frames where something in it moved.
  std::string device = "cpu";
  /// As RenderOptions': Whitted's (the default) or path tracing. Path
  /// tracing traces every frame in full on the CPU (`method` full: reuse
  /// reprojects Whitted's shading, which a path's light is not; no
  /// `reference`, no `cache`), each frame's samples placed as the first's
  /// (Cycles' default: the noise stays put from frame to frame).
  Integrator integrator = Integrator::whitted;
  Environment environment;  ///< as RenderOptions::environment
  bool blender_principled = false;  ///< as RenderOptions::blender_principled
  /// The path integrator's seed, as RenderOptions::seed: every frame's, or,
  /// with `animated_seed`, seed + the frame's number (mod 2^32; Cycles'
  /// Animated Seed), so that each frame draws noise of its own. Whitted's
  /// integrator draws no random samples: either is refused with it
  /// (std::invalid_argument).
  uint32_t seed = 0;
  bool animated_seed = false;
};

/// What one frame cost and how it was made (the paper's Tables 1 and 2).
struct FrameRow {
  int frame = 0;
  bool keyframe = false;
  double seconds = 0;            ///< tracing, or reprojection and filling (no file I/O)
  double reference_seconds = 0;  ///< full ray tracing (keyframes: = seconds)
  int64_t pixels = 0, reprojected = 0, missed = 0, leaks = 0, rejected = 0, traced = 0, interpolated = 0;
  RayCounts rays;
  /// Reprojected frames: seconds per stage (splat, merge, leaks, check, fill).
  std::array<double, 5> stage_seconds{};
  std::optional<Difference> difference;  ///< against full ray tracing (reference only)
  std::optional<Difference> hold;        ///< holding the nearest keyframe instead: the do-nothing baseline
  bool rebuilt = false;                  ///< its holes were traced, not interpolated
  int copied_from = -1;                  ///< a copy of this keyframe (nothing moved); -1 otherwise
};

struct AnimationState;  // internal

/// A shot ready to render: the shot file and its scenes read, the options
/// checked, the keyframes placed, the frames' buffers checked against memory.
/// Throws SceneError for a malformed shot or scene file, std::invalid_argument
/// naming the option, std::length_error for frames too large.
class HOLORAY_API Animation {
 public:
  Animation(const std::string& shot_path, const AnimateOptions& options = {});
  ~Animation();
  Animation(Animation&&) noexcept;
  Animation& operator=(Animation&&) noexcept;

  int frame_count() const;
  double fps() const;
  int width() const;  ///< a frame's size in pixels
  int height() const;
  Method method() const;  ///< as resolved
  std::string reuse() const;  ///< as resolved ("" for full)
  /// The keyframes (frame indices) the reuse starts from; empty for full.
  std::vector<int> keyframes() const;
  /// The shot's scene files' warnings ("file:line:col: warning: ..."),
  /// each file once: the first ones as text, and how many there were.
  struct FileWarnings {
    std::string source;
    std::vector<std::string> text;
    size_t count = 0;
  };
  std::vector<FileWarnings> warnings() const;
  /// Objects (scene files placed) in the shot.
  int object_count() const;
  /// Encoding of the shot's 8-bit outputs (options.encoding or the auto rule).
  Encoding encoding() const;
  /// The camera and method, as `holoray animate` prints them.
  std::string describe() const;
  /// The GPU the frames are traced on ("NVIDIA H100 80GB HBM3 (Vulkan 1.3)"),
  /// empty on the CPU path.
  std::string device_name() const;
  /// The shot's lens array at frame 0: "WxH px, G grid, NXxNY lenses x P px, MODE".
  std::string array_summary() const;
  /// The units of scheduling: frames [first, last] rendered together.
  std::vector<std::array<int, 2>> groups() const;

  /// Renders the frames in order (with next_group: the groups it hands out)
  /// and hands each to emit(frame, colour, row) on the calling thread.
  void run(const std::function<void(int frame, const Image& colour, const FrameRow& row)>& emit);

 private:
  std::unique_ptr<AnimationState> state_;
};

/// The markdown tables `holoray animate --report` writes (paper Tables 1
/// and 2): a title, lines under it, and one row per frame.
HOLORAY_API std::string report_markdown(const std::string& title, const std::vector<std::string>& lines,
                                        const std::vector<FrameRow>& rows);

/// Totals over rows: seconds with reuse, with full tracing, the share saved
/// (percent) and the mean PSNR of the reused frames.
struct RunTotals {
  double seconds = 0, full_seconds = 0, saved_percent = 0, mean_psnr = 0;
};
HOLORAY_API RunTotals totals(const std::vector<FrameRow>& rows);

}  // namespace holoray::api
