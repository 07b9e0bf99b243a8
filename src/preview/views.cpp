#include "preview/views.hpp"

#include <algorithm>

#include "camera/subaperture.hpp"

namespace holoray {

ImageBuffer view_grid(const ImageBuffer& eia, const LensArray& camera) {
  const int P = camera.desc().pixels_per_lens;
  const int rows = camera.desc().grid == Grid::lenticular ? 1 : P;
  ImageBuffer out;
  for (int v = 0; v < rows; ++v)
    for (int u = 0; u < P; ++u) {
      const ImageBuffer view = extract_subaperture(eia, camera, u, camera.desc().grid == Grid::lenticular ? P / 2 : v);
      if (out.empty()) out = ImageBuffer(view.width * P, view.height * rows, view.channels);
      for (int y = 0; y < view.height; ++y)
        std::copy_n(view.at(0, y), size_t(view.width) * view.channels, out.at(u * view.width, v * view.height + y));
    }
  return out;
}

std::vector<ImageBuffer> view_sweep(const ImageBuffer& eia, const LensArray& camera) {
  const int P = camera.desc().pixels_per_lens;
  std::vector<ImageBuffer> frames;
  for (int u = 0; u < P; ++u) frames.push_back(extract_subaperture(eia, camera, u, P / 2));
  for (int u = P - 2; u > 0; --u) frames.push_back(frames[static_cast<size_t>(u)]);
  return frames;
}

}  // namespace holoray
