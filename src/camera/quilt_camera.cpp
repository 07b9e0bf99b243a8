#include "camera/quilt_camera.hpp"

#include <numbers>
#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <stdexcept>

namespace holoray {

namespace {
constexpr double kPi = std::numbers::pi;
}

PinholeDesc sheared_view(const PinholeDesc& centre, double phi_rad, int width, int height) {
  const double t = std::tan(phi_rad);
  // The image's right vector, as PinholeCamera builds it (mirrored screens too).
  Frame f = Frame::from_normal_up(centre.from, centre.from - centre.at, centre.up);
  if (centre.mirrored) f.x = -f.x;
  const Vec3 move = f.x * (length(centre.at - centre.from) * t);
  PinholeDesc v = centre;
  v.from = centre.from + move;
  v.at = centre.at + move;
  v.width = width;
  v.height = height;
  v.shift_x = centre.shift_x - t;
  return v;
}

PinholeDesc quilt_view(const QuiltDesc& q, const PinholeDesc& centre, int k) {
  const int n = q.columns * q.rows;
  if (k < 0 || k >= n) throw std::invalid_argument(fmt::format("quilt view {} outside 0 to {}", k, n - 1));
  if (!(q.view_cone_deg >= 0 && q.view_cone_deg < 180))
    throw std::invalid_argument(fmt::format("the view cone must be from 0 to 180 degrees, got {}", q.view_cone_deg));
  const double phi = n == 1 ? 0 : (-q.view_cone_deg / 2 + q.view_cone_deg * k / (n - 1)) * kPi / 180;
  return sheared_view(centre, phi, q.view_width, q.view_height);
}

std::string quilt_file_name(const std::string& path, const QuiltDesc& q) {
  const std::filesystem::path p(path);
  if (p.stem().string().find("_qs") != std::string::npos) return path;
  const std::string aspect = fmt::format("{:.4g}", static_cast<double>(q.view_width) / q.view_height);
  return (p.parent_path() / fmt::format("{}_qs{}x{}a{}{}", p.stem().string(), q.columns, q.rows, aspect,
                                        p.extension().string()))
      .string();
}

QuiltCamera::QuiltCamera(const QuiltDesc& q, const PinholeDesc& centre) : q_(q) {
  if (q.columns < 1 || q.rows < 1 || q.view_width < 1 || q.view_height < 1)
    throw std::invalid_argument(fmt::format("a quilt needs at least one view of at least one pixel, got {}x{} views of {}x{}",
                                            q.columns, q.rows, q.view_width, q.view_height));
  if (int64_t{q.columns} * q.rows > 4096)
    throw std::invalid_argument(fmt::format("a quilt of {}x{} views is over 4096 views", q.columns, q.rows));
  constexpr int64_t kMaxSide = int64_t{1} << 30;
  if (int64_t{q.columns} * q.view_width > kMaxSide || int64_t{q.rows} * q.view_height > kMaxSide)
    throw std::invalid_argument(fmt::format("a quilt of {}x{} views of {}x{} pixels is over 2^30 pixels a side",
                                            q.columns, q.rows, q.view_width, q.view_height));
  const int n = q.columns * q.rows;
  views_.reserve(static_cast<size_t>(n));
  for (int k = 0; k < n; ++k) views_.emplace_back(quilt_view(q, centre, k));
}

void QuiltCamera::project(const Vec3& p_world, std::vector<PanelHit>& out) const {
  out.clear();
  for (int k = 0; k < static_cast<int>(views_.size()); ++k) {
    PanelHit h;
    if (!views_[static_cast<size_t>(k)].project(p_world, h)) continue;
    h.i = quilt_x(k, h.i);
    h.j = quilt_y(k, h.j);
    out.push_back(h);
  }
}

}  // namespace holoray
