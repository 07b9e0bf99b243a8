// holoray/image: a plain float image buffer (row-major, interleaved channels,
// row 0 at the top). Colour is linear; encodings happen only on output.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

#include <sys/mman.h>

namespace holoray {

/// Asks the kernel to back [p, p + bytes) with 2 MiB pages when it is large
/// and not yet touched (transparent huge pages in "madvise" mode, Debian's
/// default): a 2048x2048 EIA's buffers then take a few dozen page faults
/// instead of tens of thousands, which cost a still 8 % of its whole time.
/// A hint only; nothing changes where the kernel declines.
inline void advise_huge_pages(void* p, size_t bytes) {
  constexpr size_t kPage = 4096, kLarge = size_t{4} << 20;
  if (bytes < kLarge) return;
  const auto begin = (reinterpret_cast<uintptr_t>(p) + kPage - 1) & ~(kPage - 1);
  const auto end = (reinterpret_cast<uintptr_t>(p) + bytes) & ~(kPage - 1);
  if (end > begin) ::madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
}

/// std::allocator, except that resize() leaves new trivial elements as they
/// are instead of zeroing them: ImageBuffer then writes its fill value on
/// every core, so that a large buffer's first touch (page faults and the
/// kernel's zeroing: 3 to 60 ms for a 2048x2048 EIA's 48 MiB of colour on
/// our VMs) is shared by the threads rather than paid by one while the
/// others wait.
template <class T>
struct DefaultInitAllocator : std::allocator<T> {
  template <class U>
  struct rebind {
    using other = DefaultInitAllocator<U>;
  };
  DefaultInitAllocator() = default;
  template <class U>
  DefaultInitAllocator(const DefaultInitAllocator<U>&) noexcept {}
  template <class U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

/// An image's samples: a vector that resize() does not zero.
using FloatSamples = std::vector<float, DefaultInitAllocator<float>>;

struct ImageBuffer {
  int width = 0, height = 0, channels = 0;
  FloatSamples data;  ///< width * height * channels values

  ImageBuffer() = default;
  /// Every sample set to `fill`, written on every core (image.cpp).
  ImageBuffer(int w, int h, int c, float fill = 0.0f);
  /// A w x h x c buffer whose samples are left unset, for a renderer that
  /// writes every one of them: filling a 512x512 frame that is then
  /// overwritten was 2 % of a reprojected frame (image.cpp).
  static ImageBuffer unset(int w, int h, int c);

  bool empty() const { return data.empty(); }
  float* at(int x, int y) { return &data[(static_cast<size_t>(y) * width + x) * channels]; }
  const float* at(int x, int y) const { return &data[(static_cast<size_t>(y) * width + x) * channels]; }
};

}  // namespace holoray
