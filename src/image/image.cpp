#include "image/image.hpp"

#include <algorithm>

#include "util/parallel.hpp"

namespace holoray {

ImageBuffer::ImageBuffer(int w, int h, int c, float fill) : ImageBuffer(unset(w, h, c)) {
  const size_t n = data.size();
  // In pieces of one 2 MiB page: each page is first touched by one thread.
  constexpr size_t kPiece = (size_t{2} << 20) / sizeof(float);
  parallel_for_n(static_cast<int>((n + kPiece - 1) / kPiece), 0, [&](int slot) {
    const size_t k = static_cast<size_t>(slot);
    std::fill(data.begin() + static_cast<std::ptrdiff_t>(k * kPiece),
              data.begin() + static_cast<std::ptrdiff_t>(std::min(n, (k + 1) * kPiece)), fill);
  });
}

ImageBuffer ImageBuffer::unset(int w, int h, int c) {
  ImageBuffer b;
  b.width = w, b.height = h, b.channels = c;
  const size_t n = static_cast<size_t>(w) * h * c;
  b.data.reserve(n);
  advise_huge_pages(b.data.data(), n * sizeof(float));
  b.data.resize(n);  // FloatSamples: not zeroed
  return b;
}

}  // namespace holoray
