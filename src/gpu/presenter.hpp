// holoray/gpu: a window's swapchain on the GPU path's own device (issue 56).
// The frame GpuRenderer::trace left in its buffers is packed into 8-bit
// pixels by shaders/pack.comp and copied to the window's image on the
// device: the rendered frame never travels through host memory. Presents
// with vsync (FIFO), letterboxed, scaled by the nearest pixel.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "gpu/gpu_renderer.hpp"

namespace holoray::gpu {

struct Buffer;  // a device buffer (vulkan_device.hpp)

/// What a shown frame is made of (shaders/pack.comp's push constants).
struct PackParams {
  enum What : int32_t { colour = 0, albedo = 1, depth = 2, normal = 3, id = 4 };
  /// Shown pixel (x, y) is the traced frame's pixel first + (x, y) * step:
  /// step {1, 1} the whole frame, step the lens's pixels for a sub-aperture view.
  std::array<int32_t, 2> source{0, 0};  ///< the traced frame's size (set by show())
  std::array<int32_t, 2> shown{0, 0}, first{0, 0}, step{1, 1};
  int32_t what = colour;  ///< the AOVs need a frame traced with them
  float depth_scale = 1;  ///< depth shown as depth_scale / (depth_scale + |t|)
};

/// The 255 thresholds of an 8-bit encoding: threshold[k] is the least float
/// v whose code is k + 1 or more (image_io.hpp's encode_8bit), so that
/// code(v) = the number of thresholds <= v, exactly.
using CodeThresholds = std::array<float, 255>;

class Presenter {
 public:
  /// `make_surface(instance)`: the window's VkSurfaceKHR for the renderer's
  /// VkInstance (GLFW's glfwCreateWindowSurface), owned by the Presenter
  /// from then on. `renderer` must have been made with the window system's
  /// instance extensions and outlive the Presenter. Throws GpuError when
  /// the device cannot present to that window. An empty `make_surface`:
  /// offscreen, each frame packed and copied as shown into an image of the
  /// window's size on the device, and not presented (no window system).
  /// Offscreen, the copy is waited on as a shown frame's is, without vsync.
  Presenter(GpuRenderer& renderer, const std::function<uint64_t(void* instance)>& make_surface, const CodeThresholds& codes);
  ~Presenter();
  Presenter(const Presenter&) = delete;
  Presenter& operator=(const Presenter&) = delete;

  /// Packs the last traced frame as `pack` says and shows it in a window
  /// whose framebuffer is `window` pixels (its size now: the swapchain is
  /// made again when it changed). Returns false when nothing could be shown
  /// (a minimised window). Throws GpuError on a lost device.
  bool show(const PackParams& pack, std::array<int, 2> window);
  /// The same for an image made on the host (`rgb`: width x height x 3
  /// linear floats, rows top down, e.g. what an eye sees through the
  /// display): uploaded, then packed and shown whole, as colour.
  bool show_image(const float* rgb, int width, int height, std::array<int, 2> window);
  /// The last frame shown as packed, before scaling: pack.shown pixels,
  /// RGB, 8 bits, rows top down (read back from the device).
  std::vector<uint8_t> shown_rgb() const;

 private:
  // Packs `source` (colour, p.source pixels) as `p` says and presents it.
  bool present(const PackParams& p, std::array<int, 2> window, const Buffer& source);
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace holoray::gpu
