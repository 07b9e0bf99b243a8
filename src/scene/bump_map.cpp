#include "scene/bump_map.hpp"

#include <cmath>

namespace holoray {

bool is_grey(const ImageMap& image) {
  const std::vector<unsigned char>& c = image.rgb;
  for (size_t i = 0; i + 2 < c.size(); i += 3)
    if (c[i] != c[i + 1] || c[i] != c[i + 2]) return false;
  return true;
}

ImageMap normals_from_heights(const ImageMap& heights, double strength) {
  ImageMap out;
  out.path = heights.path;
  out.width = heights.width;
  out.height = heights.height;
  out.srgb = false;
  out.rgb.resize(heights.rgb.size());
  const int w = heights.width, h = heights.height;
  auto height_at = [&](int x, int y) {
    x = (x % w + w) % w, y = (y % h + h) % h;
    return heights.rgb[(size_t(y) * size_t(w) + size_t(x)) * 3] / 255.0;
  };
  auto code = [](double n) { return static_cast<unsigned char>(std::lround((n + 1) * 0.5 * 255)); };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double dx = (height_at(x + 1, y) - height_at(x - 1, y)) * 0.5;
      const double dy = (height_at(x, y + 1) - height_at(x, y - 1)) * 0.5;
      const double nx = -strength * dx, ny = -strength * dy;
      const double len = std::sqrt(nx * nx + ny * ny + 1);
      unsigned char* p = &out.rgb[(size_t(y) * size_t(w) + size_t(x)) * 3];
      p[0] = code(nx / len), p[1] = code(ny / len), p[2] = code(1 / len);
    }
  return out;
}

}  // namespace holoray
