// holoray/image: a plain float image buffer (row-major, interleaved channels,
// row 0 at the top). Colour is linear; encodings happen only on output.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace holoray {

struct ImageBuffer {
  int width = 0, height = 0, channels = 0;
  std::vector<float> data;  ///< width * height * channels values

  ImageBuffer() = default;
  ImageBuffer(int w, int h, int c, float fill = 0.0f)
      : width(w), height(h), channels(c), data(static_cast<size_t>(w) * h * c, fill) {}

  bool empty() const { return data.empty(); }
  float* at(int x, int y) { return &data[(static_cast<size_t>(y) * width + x) * channels]; }
  const float* at(int x, int y) const { return &data[(static_cast<size_t>(y) * width + x) * channels]; }
};

}  // namespace holoray
