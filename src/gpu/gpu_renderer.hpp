// holoray/gpu: the GPU path's executor. A Vulkan device chosen once, the
// scene's arrays uploaded once (gpu_scene.hpp), then frames rendered by the
// compute shader shaders/trace.comp, band by band of rows (each dispatch
// short enough for a desktop GPU's watchdog), and read back into the CPU
// path's FrameBuffers (or shown in a window: presenter.hpp). Vulkan itself
// is included by src/gpu's .cpp files only (vulkan_device.hpp), and the
// loader is opened at run time: a machine without Vulkan runs everything
// else.
#pragma once

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "gpu/gpu_scene.hpp"

namespace holoray::gpu {

/// The GPU path cannot run here or failed: no loader, no device, not enough
/// memory, a lost device. The message names the fix where there is one.
class GpuError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A Vulkan device as the loader lists it.
struct DeviceInfo {
  std::string name;          ///< e.g. "NVIDIA H100 80GB HBM3", "llvmpipe (LLVM 15.0.6, 256 bits)"
  std::string api;           ///< "Vulkan 1.3"
  bool is_gpu = false;       ///< integrated, discrete or virtual GPU (not a CPU device such as lavapipe)
  uint64_t memory_bytes = 0; ///< its largest device-local heap
  uint32_t subgroup_size = 0;
  /// The most bytes one storage buffer binding reaches (maxStorageBufferRange:
  /// 128 MiB on lavapipe, 4 GiB on NVIDIA): every array and image buffer the
  /// kernel binds must fit, or GpuRenderer refuses it, saying so.
  uint64_t max_storage_buffer_range = 0;
};

/// The devices of this machine, in the loader's order. Throws GpuError
/// when there is no loader or it lists no device.
std::vector<DeviceInfo> list_devices();

/// What one frame cost and did: seconds of the dispatches alone (ray
/// generation, traversal, shading), of the readback, and the work counts.
class GpuRenderer {
 public:
  /// `device`: -1 takes the first device that is a GPU, else the first
  /// device (lavapipe where there is no GPU); N >= 0 the Nth of
  /// list_devices(). Throws GpuError (no loader, no such device).
  /// `instance_extensions`: a window system's surface extensions (GLFW's
  /// glfwGetRequiredInstanceExtensions), for a Presenter on this device;
  /// the device then also gets VK_KHR_swapchain (GpuError without it).
  /// `count_work`: the frames count BVH nodes visited and primitives
  /// tested (RenderStats; 0 when not), in a pipeline of their own
  /// (RenderOptions::count_work says what it costs).
  explicit GpuRenderer(int device = -1, const std::vector<std::string>& instance_extensions = {}, bool count_work = false);
  ~GpuRenderer();
  GpuRenderer(const GpuRenderer&) = delete;
  GpuRenderer& operator=(const GpuRenderer&) = delete;

  const DeviceInfo& device() const;
  /// "NVIDIA H100 80GB HBM3 (Vulkan 1.3)".
  std::string describe() const;
  /// The hierarchy's width that lay_out is to build for this renderer: 4,
  /// or 8 with HOLORAY_GPU_BVH_WIDTH=8 (for measuring, docs/design/gpu.md).
  int bvh_width() const;

  /// Uploads the scene, replacing any before, and compiles the kernel for
  /// its materials and the frames to come: `panel` when they are display
  /// panels' or a Looking Glass's native images (GpuFrame::mode), else lens
  /// arrays, pinhole views or quilts. `image_bytes`: what those frames
  /// will need beside the scene. Throws GpuError, before allocating, when
  /// the two pass the device's memory, naming all three sizes, or when one
  /// array passes its max_storage_buffer_range, naming the array. Returns
  /// the seconds spent compiling (next to none where an earlier load compiled
  /// the same). `moved`: the scene before, its objects moved (a shot's next
  /// frame), so the frames before still tell which schedule pays.
  double load(const SceneArrays& scene, uint64_t image_bytes, bool panel, bool moved = false);
  /// The kernel's pipelines compiled so far: none as the renderer is made,
  /// then those load() compiles for each scene's materials and frames.
  size_t pipelines_compiled() const;
  /// Device buffers made so far, each with memory of its own (for the
  /// tests): a shot's next frame, loaded `moved` with arrays no larger than
  /// the frame before's, makes none.
  size_t buffers_made() const;
  /// Frees the scene and the frames' buffers, keeping the device and its
  /// compiled pipelines for the next load(): a renderer kept idle between
  /// renders holds no more device memory than its pipelines.
  void release();
  /// Device bytes a width x height frame takes (colour, and the AOVs when wanted).
  static uint64_t frame_bytes(int width, int height, bool aovs);

  /// Renders one frame of the loaded scene with `frame`'s camera into
  /// `out` (allocated by the caller, W x H as in `frame`; the AOVs that
  /// `aovs` names). Throws GpuError on a lost device or failed allocation,
  /// and before tracing when the image's colours or AOVs pass the device's
  /// max_storage_buffer_range.
  void render(const GpuFrame& frame, const AovSet& aovs, FrameBuffers& out, RenderStats& stats);
  /// Several cameras into one W x H image, each into its tile
  /// (GpuFrame::tile: a quilt's views), in one submission.
  void render(const std::vector<GpuFrame>& frames, int W, int H, const AovSet& aovs, FrameBuffers& out,
              RenderStats& stats);
  /// render() in two: the frames traced into the device's buffers, where
  /// they stay (a Presenter shows them from there)... Under the path
  /// integrator, `first_sample` > 0 adds samples first_sample to spp - 1
  /// (GpuFrame::mode.w) to the image the last trace left, the mean of its
  /// first_sample samples: a still view refined (live's progressive samples).
  void trace(const std::vector<GpuFrame>& frames, int W, int H, RenderStats& stats, int first_sample = 0);
  /// ...and the last frame traced copied into `out` (W x H; the AOVs that
  /// `aovs` names, which that frame must have traced). Sets
  /// stats.readback_seconds.
  void readback(const AovSet& aovs, FrameBuffers& out, RenderStats& stats);

 private:
  friend class Presenter;
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace holoray::gpu
