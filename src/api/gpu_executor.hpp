// holoray/api: the GPU path behind Renderer (issue 55): the device named by
// RenderOptions::device, the scene laid out and uploaded once, frames of any
// camera rendered there. Built without the GPU path (no Vulkan
// headers or glslc), it refuses, saying how to get it.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "holoray/render.hpp"
#include "render/frame_camera.hpp"
#include "render/render_context.hpp"
#include "render/renderer.hpp"

namespace holoray::api {

/// RenderOptions::device parsed: the CPU, or a GPU (index -1: the first GPU).
struct DeviceChoice {
  bool gpu = false;
  int index = -1;
};
/// Throws std::invalid_argument naming `device` for anything but cpu, gpu, gpu:N.
DeviceChoice parse_device(const std::string& device);

/// device_of_local_rank's choice among devices whose GPU-ness is `is_gpu`
/// (in gpu_devices() order): the index of the (local_rank mod GPUs)th GPU,
/// -1 when none is a GPU.
int gpu_of_local_rank(const std::vector<bool>& is_gpu, int local_rank);

/// The GPU path's layouts of one World's scene (gpu::lay_out: its records
/// and hierarchy, in host memory), one per hierarchy width, made by the
/// world's first GPU renderer of that width and kept for the next: a
/// World's scene does not move, so its layout stands. Thread-safe; a
/// second renderer asking while the first lays out waits for it. Empty in
/// a build without the GPU path.
class GpuLayouts {
 public:
  GpuLayouts();
  ~GpuLayouts();
  /// How many layouts it holds.
  size_t size() const;
  struct Impl;
  std::unique_ptr<Impl> impl;
};

class GpuExecutor {
 public:
  /// Chooses the device and uploads `context`'s scene, with the path
  /// integrator's lights where its settings ask for that integrator (a
  /// render whose settings differ lays the scene out again). Throws
  /// std::invalid_argument for the shadow cache (the CPU path's), and
  /// std::runtime_error when the GPU cannot run (no loader, no device, not
  /// enough memory: the message says what to do).
  /// `layouts`: the world's, whose layout of the scene it takes where one
  /// stands (null: it lays the scene out itself).
  GpuExecutor(const DeviceChoice& device, const RenderContext& context, const FrameCamera& camera, const RenderOptions& options,
              GpuLayouts* layouts = nullptr);
  ~GpuExecutor();
  /// "NVIDIA H100 80GB HBM3 (Vulkan 1.3)".
  std::string name() const;
  /// Seconds the constructor spent setting up the device: the renderer
  /// made or taken from the idle ones, and the kernel compiled
  /// (RenderStats::gpu_setup_seconds).
  double setup_seconds() const;
  /// The frame, or rows [rows[0], rows[1]) of it; colour and the AOVs asked for.
  FrameBuffers render(const RenderContext& context, const FrameCamera& camera, const AovSet& aovs, int spp,
                      std::optional<std::array<int, 2>> rows, RenderStats& stats);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace holoray::api
