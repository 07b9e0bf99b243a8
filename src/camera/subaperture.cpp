#include "camera/subaperture.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace holoray {

ImageBuffer extract_subaperture(const ImageBuffer& eia, const LensArray& cam, int u, int v) {
  const int P = cam.desc().pixels_per_lens;
  if (eia.width != cam.width() || eia.height != cam.height())
    throw std::invalid_argument(fmt::format("the EIA is {}x{} pixels but the lens array describes {}x{}", eia.width,
                                            eia.height, cam.width(), cam.height()));
  if (u < 0 || u >= P || v < 0 || v >= P)
    throw std::invalid_argument(fmt::format("sub-aperture pixel ({}, {}) is outside the {}x{} elemental image", u, v, P, P));
  const bool lenticular = cam.desc().grid == Grid::lenticular;
  const int nx = cam.lens_count_x(), ny = lenticular ? cam.height() : cam.lens_count_y();
  ImageBuffer out(nx, ny, eia.channels);
  const double s = cam.pixel_pitch();
  for (int ly = 0; ly < ny; ++ly) {
    for (int lx = 0; lx < nx; ++lx) {
      const Vec3 c = cam.lens_centre_local({lx, lenticular ? 0 : ly});
      // Lens centre in pixel units from the top-left corner; (u, v) counted from the cell's corner.
      const double cx = c.x / s + cam.width() / 2.0, cy = cam.height() / 2.0 - c.y / s;
      const int i = std::clamp(static_cast<int>(std::floor(cx - P / 2.0 + u + 0.5)), 0, cam.width() - 1);
      const int j = lenticular ? ly : std::clamp(static_cast<int>(std::floor(cy - P / 2.0 + v + 0.5)), 0, cam.height() - 1);
      std::copy_n(eia.at(i, j), eia.channels, out.at(lx, ly));
    }
  }
  return out;
}

LensArrayDesc eia_layout(int width, int height, Grid grid, int P) {
  if (P < 1) throw std::invalid_argument(fmt::format("`pixels_per_lens`: must be at least 1, got {}", P));
  LensArrayDesc d;
  d.pixels_per_lens = P;
  d.grid = grid;
  if (width % P != 0)
    throw std::invalid_argument(fmt::format("the EIA is {} pixels wide, not a multiple of {} pixels per lens", width, P));
  d.lenses_x = width / P;
  if (grid == Grid::square) {
    if (height % P != 0)
      throw std::invalid_argument(fmt::format("the EIA is {} pixels high, not a multiple of {} pixels per lens", height, P));
    d.lenses_y = height / P;
  } else if (grid == Grid::hex) {
    d.lenses_y = std::max(1, static_cast<int>(std::lround(height / (P * std::sqrt(3.0) / 2))));
    d.rows = height;
  } else {
    d.rows = height;  // lenticular
  }
  return d;
}

}  // namespace holoray
