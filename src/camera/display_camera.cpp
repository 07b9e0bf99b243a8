#include "camera/display_camera.hpp"

#include <numbers>
#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

namespace holoray {

namespace {
constexpr double kSqrt3 = 1.7320508075688772;
constexpr double kPi = std::numbers::pi;

bool positive_finite(double v) { return v > 0 && std::isfinite(v); }
}  // namespace

DisplayCamera::DisplayCamera(const DisplayGeometry& g) : g_(g) {
  if (!positive_finite(g.pixel_pitch))
    throw std::invalid_argument(fmt::format("pixel pitch must be positive and finite, got {} scene units", g.pixel_pitch));
  if (!positive_finite(g.pitch))
    throw std::invalid_argument(fmt::format("lens pitch must be positive and finite, got {} scene units", g.pitch));
  if (!positive_finite(g.gap))
    throw std::invalid_argument(fmt::format("gap must be positive and finite, got {} scene units", g.gap));
  if (g.pitch < g.pixel_pitch)
    throw std::invalid_argument(fmt::format("a lens of pitch {} is narrower than a pixel ({}), scene units", g.pitch,
                                            g.pixel_pitch));
  if (!(std::fabs(g.slant_rad) <= kPi / 4))
    throw std::invalid_argument(
        fmt::format("slant must be from -45 to 45 degrees, got {} degrees", g.slant_rad * 180 / kPi));
  if (g.slant_rad != 0 && g.grid != Grid::lenticular)
    throw std::invalid_argument(fmt::format("a slant goes with a lenticular sheet, not a {} grid", to_string(g.grid)));
  if (!std::isfinite(g.offset)) throw std::invalid_argument("lens offset must be finite");
  if (!(g.view_distance > 0))
    throw std::invalid_argument(fmt::format("view distance must be positive, got {} scene units", g.view_distance));
  if (g.samples_per_pixel != 1 && g.samples_per_pixel != 3)
    throw std::invalid_argument(fmt::format("samples per pixel must be 1 or 3, got {}", g.samples_per_pixel));
  constexpr int64_t kMaxDim = int64_t{1} << 30;
  const int64_t w = int64_t{g.width} * g.samples_per_pixel;
  if (g.width < 1 || g.height < 1 || w > kMaxDim || g.height > kMaxDim)
    throw std::invalid_argument(
        fmt::format("panel of {}x{} pixels: each side must be between 1 and {} samples", g.width, g.height, kMaxDim));
  width_ = static_cast<int>(w);
  sw_ = g.pixel_pitch / g.samples_per_pixel;
  half_w_ = g.width * g.pixel_pitch / 2;
  half_h_ = g.height * g.pixel_pitch / 2;
  sin_ = std::sin(g.slant_rad);
  cos_ = std::cos(g.slant_rad);
  // The lens grid starts at the panel's left edge (moved by the offset) on
  // the middle row; a lenticule's strip is measured across its axis.
  left_ = g.grid == Grid::lenticular ? (-half_w_ + g.offset) * cos_ : -half_w_ + g.offset;
  row_step_ = g.pitch * kSqrt3 / 2;
  grid_ = {.grid = g.grid == Grid::square ? HR_LINE_GRID_SQUARE : g.grid == Grid::hex ? HR_LINE_GRID_HEX : HR_LINE_GRID_LENTICULAR,
           .converging = std::isinf(g.view_distance) ? 0 : 1,
           .pitch = g.pitch,
           .gap = g.gap,
           .sample_width = sw_,
           .pixel_pitch = g.pixel_pitch,
           .half_w = half_w_,
           .half_h = half_h_,
           .left = left_,
           .row_step = row_step_,
           .sin_slant = sin_,
           .cos_slant = cos_,
           .view_distance = g.view_distance};
}

Vec3 DisplayCamera::panel_point_local(int c, int j, double u, double v) const {
  return camera_lines::hr_panel_sample_point(grid_, c, j, u, v);
}

DisplayLens DisplayCamera::lens_at(const Vec3& p) const {
  const shading::ivec2 l = camera_lines::hr_panel_lens_at(grid_, p);
  return {l.x, l.y};
}

Vec3 DisplayCamera::lens_centre_local(DisplayLens l) const { return camera_lines::hr_panel_lens_centre(grid_, l.x, l.y); }

Vec3 DisplayCamera::axis_point_local(DisplayLens l, const Vec3& p) const {
  return camera_lines::hr_panel_axis_point(grid_, l.x, p);
}

PixelLine DisplayCamera::line_local(int c, int j, double u, double v) const {
  PixelLine l;
  camera_lines::hr_panel_line(grid_, c, j, u, v, l.origin, l.dir);
  return l;
}

PixelLine DisplayCamera::line(int c, int j, double u, double v) const {
  const PixelLine l = line_local(c, j, u, v);
  return {g_.frame.to_world_point(l.origin), g_.frame.to_world_dir(l.dir)};
}

bool DisplayCamera::sample_at(const Vec3& p, PanelHit& h) const {
  const double x = (p.x + half_w_) / sw_, y = (half_h_ - p.y) / g_.pixel_pitch;
  if (!(x >= 0 && x < width_ && y >= 0 && y < g_.height)) return false;
  h.i = static_cast<int>(x), h.j = static_cast<int>(y);
  h.u = x - h.i, h.v = y - h.j;
  return true;
}

void DisplayCamera::project(const Vec3& p_world, std::vector<PanelHit>& out) const {
  out.clear();
  const Vec3 X = g_.frame.to_local_point(p_world);
  if (X.z == 0 || !std::isfinite(X.z)) return;
  if (g_.mode == RecordingMode::pseudoscopic && X.z < 0) return;
  const double P = g_.pitch, scale = std::fabs(X.z) / g_.gap;
  // A landing point counts when it lies on the panel under the lens it came
  // through; every line crosses the lens plane at t = 0.
  auto keep = [&](const Vec3& p_panel, DisplayLens l) {
    PanelHit h;
    if (!sample_at(p_panel, h) || !(lens_at(panel_point_local(h.i, h.j, h.u, h.v)) == l)) return;
    h.t = X.z / line_local(h.i, h.j, h.u, h.v).dir.z;
    out.push_back(h);
  };
  if (g_.grid == Grid::lenticular) {
    // Lenticule n (axis at across-coordinate a_n) sends X to the panel point
    // under it at a_p = a_n - g * alpha, alpha the across slope; along the
    // axis the line keeps its crossing point b. Both from X = q + z d.
    const double aX = across(X), bX = along(X), zv = X.z / g_.view_distance;
    const double denom = 1 - zv * cos_ * cos_;
    if (std::fabs(denom) < 1e-12) return;
    const double reach = (P / 2) * scale + P;
    const int n0 = static_cast<int>(std::floor((aX - reach - left_) / P)),
              n1 = static_cast<int>(std::floor((aX + reach - left_) / P));
    for (int n = n0; n <= n1; ++n) {
      const double an = left_ + (n + 0.5) * P;
      const double b = (bX - zv * an * sin_ * cos_) / denom;
      const double qy = -an * sin_ + b * cos_;
      const double alpha = (aX - an - zv * qy * sin_) / X.z;
      const double ap = an - g_.gap * alpha;
      const Vec3 p{ap * cos_ + b * sin_, -ap * sin_ + b * cos_, -g_.gap};
      keep(p, {n, 0});
    }
    return;
  }
  // Square and hex: the line through centre c lands at c - (g / z)(X - c);
  // only lenses within a cell's reach (scaled by z / g) of X can hold it.
  const double reach = P * scale + P;
  const int lx0 = static_cast<int>(std::floor((X.x - reach - left_) / P)) - 1,
            lx1 = static_cast<int>(std::floor((X.x + reach - left_) / P)) + 1;
  const double row = g_.grid == Grid::hex ? row_step_ : P;
  const int ly0 = static_cast<int>(std::floor((half_h_ - X.y - reach) / row)) - 1,
            ly1 = static_cast<int>(std::floor((half_h_ - X.y + reach) / row)) + 1;
  for (int ly = ly0; ly <= ly1; ++ly)
    for (int lx = lx0; lx <= lx1; ++lx) {
      const Vec3 c = lens_centre_local({lx, ly});
      const double k = g_.gap / X.z;
      keep(Vec3{c.x - k * (X.x - c.x), c.y - k * (X.y - c.y), -g_.gap}, {lx, ly});
    }
}

}  // namespace holoray
