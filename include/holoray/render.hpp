// holoray public API: rendering a scene through a camera, once.
//
//   Renderer r(scene, camera, options);  // validated, placed, built once
//   Result out = r.render();             // colour, AOVs, rays, seconds
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <stop_token>
#include <string>
#include <vector>

#include "holoray/camera.hpp"
#include "holoray/export.hpp"
#include "holoray/image.hpp"
#include "holoray/scene.hpp"

namespace holoray::api {

/// Outputs besides the colour, from each pixel's first (centre) sample.
struct Aovs {
  bool albedo = false;  ///< flat surface colour, unlit; linear RGB
  bool depth = false;   ///< the camera's line parameter t (camera-model.md); NaN for background
  bool normal = false;  ///< unit shading normal, world frame, facing the viewer; 0 for background
  bool id = false;      ///< object index (file order, then add order); -1 for background
};

/// The order pixels are traced in (paper §6); never changes the image.
enum class Style { automatic, packet, subaperture, horizontal, vertical };

/// The shadow cache (docs/guide/performance.md): light visibility reused per
/// surface cell across lenses; lens-array cameras only.
struct ShadowCacheOptions {
  bool enabled = false;
  double cell = 1;           ///< cell size in lens pitches
  double memory_mib = 512;   ///< bound on its storage
};

/// What of an image one process holds: rows held at once, rows copied once
/// more on output, and where, for the message (" on rank 0 of 4").
struct MemoryShare {
  int64_t held_rows = 0, copied_rows = 0;
  std::string where;
};

/// How light is computed (docs/lights.md). `whitted`: the paper's recursive
/// ray tracing (point, spot and directional lights, hard shadows, mirror
/// and refraction rays), exact and fast. `path`: path tracing with next-event
/// estimation and multiple importance sampling (Veach 1997), soft light from
/// an environment and emissive surfaces, light bouncing between surfaces,
/// noise falling as 1 / sqrt(spp); on the CPU and the GPU, from one text
/// of the integrator (src/render/path_integrator.h).
enum class Integrator { whitted, path };

/// The light around the scene that the path integrator sees (docs/lights.md,
/// "Environment"): an equirectangular image (Radiance .hdr or OpenEXR,
/// linear RGB; `file`), else a constant `colour` (linear RGB), else the
/// scene's background colour. The image is mapped as Blender maps an
/// Environment Texture, its top row toward the scene's up (+y for mesh
/// files, +z where the scene's viewpoint has z up), times `strength`, turned
/// by `rotation_deg` about the up axis (a Mapping node's Z rotation).
struct Environment {
  std::string file;
  std::optional<std::array<double, 3>> colour;
  double strength = 1;
  double rotation_deg = 0;
  /// Whether anything was given (file or colour).
  bool given() const { return !file.empty() || colour.has_value(); }
};

/// The deepest ray tree RenderOptions::max_depth allows: past it a
/// refracting scene's rays only multiply.
inline constexpr int kMaxDepth = 16;

/// The most views on each side RenderOptions::share_views takes samples from.
inline constexpr int kMaxShareViews = 16;

struct RenderOptions {
  int threads = 0;    ///< worker threads; 0: all cores
  int spp = 1;        ///< samples per pixel, >= 1 (sample 0 at the centre)
  int max_depth = 0;  ///< ray-tree depth, eye ray = 1, at most kMaxDepth; 0: the scene's (Tachyon raydepth), else 5
  /// Whitted (the default) or path. The path integrator: sample 0 at the
  /// pixel centre (the AOVs'), the others spread by a scrambled Sobol
  /// sequence; lens arrays of every grid, pinhole views,
  /// quilts and panels; max_depth counts the eye ray as 1 (Cycles' bounces
  /// plus 1). Not with the shadow cache (std::invalid_argument).
  Integrator integrator = Integrator::whitted;
  /// The path integrator's environment; given with Whitted's, refused.
  Environment environment;
  /// The path integrator shades glTF materials as Blender 3.x's Principled
  /// BSDF does (Burley's diffuse, whole under the specular layer) rather
  /// than as glTF's Appendix B (diffuse times 1 - F): for a scene exported
  /// from Blender, to render what Cycles renders (docs/lights.md). The
  /// Blender add-on sets it.
  bool blender_principled = false;
  /// A quilt under the path integrator on the CPU: each view also takes the
  /// samples of this many views on each side (0 to kMaxShareViews) whose
  /// first surface point it sees, with the BSDF evaluated for its own eye
  /// (docs/guide/light.md, "Quilts: views sharing samples"). About 1 + 2S
  /// samples a pixel for the price of one and a little, where the views
  /// see the same surface; mirror and glass are not shared. 0: none.
  int share_views = 0;
  /// The path integrator's seed: renders with different seeds draw
  /// unrelated samples, so their noise is independent (Cycles' Seed); one
  /// seed gives the same image every time. Whitted's integrator draws no
  /// random samples: a seed other than 0 with it is refused
  /// (std::invalid_argument).
  uint32_t seed = 0;
  Aovs aovs;
  Style style = Style::automatic;
  ShadowCacheOptions cache;
  /// Called from worker threads with the fraction done; must be thread-safe.
  std::function<void(double)> progress;
  /// Checked between tiles: once stop is requested, render() throws Cancelled.
  std::stop_token stop;
  /// Where the rays are traced: "cpu" (Embree, the default), "gpu" (the
  /// first Vulkan device that is a GPU, else the first device: lavapipe
  /// where there is no GPU) or "gpu:N" (the Nth Vulkan device). The GPU
  /// path (docs/guide/gpu.md) renders every camera, material and texture
  /// the CPU path does, in float; the shadow cache stays the CPU's. A
  /// process keeps a GPU's device and compiled kernels, idle, for its next
  /// render on that device (the scene's and image's memory is freed).
  std::string device = "cpu";
  /// On the GPU: count the BVH nodes each ray visits and the primitives it
  /// tests (RenderStats), which the kernel does only when asked: the two
  /// counters cost it 24 registers a thread and 1.07x the trace time on an
  /// H100 (docs/design/gpu.md). The CPU path ignores it.
  bool count_work = false;
  /// The rows of the image this process holds, for the memory bound (a
  /// rank's bands under mpirun): asked once the camera is placed, with the
  /// image's height and Renderer::band_rows(). Null: the whole image.
  std::function<MemoryShare(int height, int band_rows)> memory_share;
};

/// Rays traced, by kind.
struct RayCounts {
  uint64_t eye = 0, shadow = 0, reflected = 0, refracted = 0;
  uint64_t shadow_cached = 0;  ///< shadow questions the cache answered
  uint64_t cache_samples = 0;  ///< rays the cache traced to fill its cells
  /// Rays traced through the acceleration structure.
  uint64_t total() const { return eye + shadow + reflected + refracted + cache_samples; }
};

struct RenderStats {
  RayCounts rays;
  double build_seconds = 0;  ///< the scene's acceleration structure and the camera (Renderer)
  /// On the GPU, part of build_seconds: the device's set-up, its Vulkan
  /// device made (or an idle one of this process taken) and the kernel
  /// compiled for the scene's materials and camera; 0 on the CPU.
  double gpu_setup_seconds = 0;
  double trace_seconds = 0;  ///< on the GPU: the dispatches alone (ray generation, traversal, shading)
  double readback_seconds = 0;  ///< on the GPU: the image copied back to the host
  /// On the GPU with RenderOptions::count_work: BVH nodes visited and
  /// primitives tested, over all rays; 0 otherwise.
  uint64_t nodes_visited = 0, primitives_tested = 0;
  /// With count_work, where the GPU's path integrator ran as a wavefront
  /// (docs/design/gpu.md): the node steps its traversals' lanes took, busy
  /// or waiting for their subgroup; nodes_visited over it is their lanes'
  /// use. 0 otherwise.
  uint64_t lane_steps = 0;
};

/// One rendered image. colour: (H, W, 3) linear RGB; the requested AOVs,
/// the others empty: albedo (H, W, 3), depth (H, W, 1), normal (H, W, 3),
/// id (H, W, 1). A band (Renderer::render's rows) holds only its rows.
struct Result {
  Image colour, albedo, depth, normal, id;
  RenderStats stats;
  /// The shadow cache's line of the CLI's summary; empty without the cache.
  std::string cache_summary;
};

struct RendererState;  // internal
class World;           // world.hpp
namespace detail {
struct RendererAccess;  // internal
}

/// A scene through one camera: validated, placed and built once, then
/// rendered any number of times (whole, or in bands of rows). The camera is
/// placed and the image's buffers checked against 80 % of this machine's
/// memory (std::length_error naming both sizes) before the scene is built.
/// Throws std::invalid_argument naming the option for a bad value or a
/// camera that needs a viewpoint the scene lacks; SceneError for a bad
/// display or calibration file.
class HOLORAY_API Renderer {
 public:
  /// Builds `scene` for this renderer alone: Renderer(World(scene, options), camera, options).
  Renderer(const Scene& scene, const Camera& camera, const RenderOptions& options = {});
  /// Renders a World built before, which it keeps alive; many renderers may
  /// share one (world.hpp). The options' light fields (`integrator`,
  /// `environment`, `blender_principled`, `max_depth`) are the world's:
  /// each left at its default takes the world's, one given otherwise is
  /// refused (std::invalid_argument naming it). build_stats() then counts
  /// this renderer's set-up, not the world's build.
  Renderer(const World& world, const Camera& camera, const RenderOptions& options = {});
  ~Renderer();
  Renderer(Renderer&&) noexcept;
  Renderer& operator=(Renderer&&) noexcept;

  /// The image's size in pixels (a panel's pixels, not its subpixels).
  int width() const;
  int height() const;
  /// Rows of one tile of work: bands of rows are best cut on multiples.
  int band_rows() const;
  /// What will be rendered, as `holoray render` prints it (one or two lines,
  /// each ending in '\n').
  std::string describe() const;
  /// Zero-area polygons the scene's build left out.
  size_t skipped_polygons() const;
  /// The pixel-tracing style in use ("packet", "subaperture", ...).
  const char* style_name() const;
  /// The GPU the render runs on, e.g. "NVIDIA H100 80GB HBM3 (Vulkan 1.3)";
  /// empty on the CPU.
  std::string device_name() const;
  /// Renders the image, or rows [rows[0], rows[1]) of it (pixels exactly as
  /// in the whole image). Throws Cancelled when options.stop was requested.
  Result render(std::optional<std::array<int, 2>> rows = std::nullopt) const;
  const RenderStats& build_stats() const;

 private:
  friend struct detail::RendererAccess;
  // What follows the camera's placement: the renderer's settings on the
  // world, its shadow cache, its executor. `shared`: the world was built
  // before, for any number of renderers (its GPU layout is kept for them).
  void set_up(const World& world, const RenderOptions& options, std::chrono::steady_clock::time_point t_build, bool shared);
  std::unique_ptr<RendererState> state_;
};

/// Renderer(scene, camera, options).render().
HOLORAY_API Result render(const Scene& scene, const Camera& camera, const RenderOptions& options = {});

/// Checks a RenderOptions::device value: throws std::invalid_argument
/// naming `device` unless it is cpu, gpu or gpu:N (N >= 0).
HOLORAY_API void check_device(const std::string& device);

/// The device one of several processes on a machine takes (each rank of an
/// `mpirun` launch): for "gpu", the machine's GPUs in gpu_devices() order,
/// the (local_rank mod their number)th as "gpu:N", or "gpu" (the first
/// device: lavapipe) where there is none; any other value as it is. Throws
/// as gpu_devices() for "gpu" when there is no loader or device.
HOLORAY_API std::string device_of_local_rank(const std::string& device, int local_rank);

/// The Vulkan devices of this machine ("0: llvmpipe (LLVM 15.0.6, 256
/// bits), CPU, Vulkan 1.3"), in the order gpu:N counts them. Throws
/// std::runtime_error saying what to install when there is no loader or no
/// device, or that this build has no GPU path.
HOLORAY_API std::vector<std::string> gpu_devices();

/// Frees the GPU devices this process keeps idle between renders
/// (RenderOptions::device) with their compiled kernels, so that the memory
/// their contexts hold on the GPU goes back to the driver: for a host
/// application (Blender) that hands the GPU to other work. A render under
/// way keeps its own; the next GPU render makes its device again (on
/// lavapipe, 1.3 s). Returns how many were freed; 0 in a build without the
/// GPU path. Does not throw.
HOLORAY_API int release_gpu_devices() noexcept;

/// Installed memory in bytes; 0 when unknown (the bound on buffers).
HOLORAY_API uint64_t physical_memory_bytes();

}  // namespace holoray::api
