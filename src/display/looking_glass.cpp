#include "display/looking_glass.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>

#include "scene/file_text.hpp"

namespace holoray {

namespace {

constexpr double kPi = 3.14159265358979323846;

double field(const nlohmann::json& j, const char* key, const std::string& source, std::optional<double> fallback = {}) {
  const auto it = j.find(key);
  if (it == j.end()) {
    if (fallback) return *fallback;
    throw std::runtime_error(fmt::format("{}: expected the field '{}' ({{\"value\": number}}), found none", source, key));
  }
  const nlohmann::json& v = it->is_object() && it->contains("value") ? (*it)["value"] : *it;
  if (!v.is_number() || !std::isfinite(v.get<double>()))
    throw std::runtime_error(fmt::format("{}: expected '{}' to be a finite number, found {}", source, key, v.dump()));
  return v.get<double>();
}

}  // namespace

LookingGlassCalibration parse_looking_glass(std::string_view text, const std::string& source) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw std::runtime_error(fmt::format("{}: not a Looking Glass calibration (JSON): {}", source, e.what()));
  }
  if (!j.is_object()) throw std::runtime_error(fmt::format("{}: expected a JSON object of calibration fields", source));
  LookingGlassCalibration c;
  c.source = source;
  c.pitch = field(j, "pitch", source);
  c.slope = field(j, "slope", source);
  c.center = field(j, "center", source);
  c.view_cone_deg = field(j, "viewCone", source, 40.0);
  c.inv_view = field(j, "invView", source, 0.0) != 0;
  c.dpi = field(j, "DPI", source);
  const double w = field(j, "screenW", source), h = field(j, "screenH", source);
  c.flip_x = field(j, "flipImageX", source, 0.0) != 0;
  c.flip_y = field(j, "flipImageY", source, 0.0) != 0;
  c.flip_subp = field(j, "flipSubp", source, 0.0) != 0;
  if (!(c.pitch > 0)) throw std::runtime_error(fmt::format("{}: expected a positive 'pitch' (lenticules per inch), found {}", source, c.pitch));
  if (c.slope == 0) throw std::runtime_error(fmt::format("{}: expected a non-zero 'slope' (rows per pixel of lean), found 0", source));
  if (!(c.dpi > 0)) throw std::runtime_error(fmt::format("{}: expected a positive 'DPI' (pixels per inch), found {}", source, c.dpi));
  if (!(w >= 1 && w <= 65536 && h >= 1 && h <= 65536 && w == std::floor(w) && h == std::floor(h)))
    throw std::runtime_error(fmt::format("{}: expected 'screenW' and 'screenH' whole numbers of pixels from 1 to 65536, found {}x{}", source, w, h));
  if (!(c.view_cone_deg > 0 && c.view_cone_deg < 180))
    throw std::runtime_error(fmt::format("{}: expected 'viewCone' from 0 to 180 degrees, found {} degrees", source, c.view_cone_deg));
  c.width = static_cast<int>(w), c.height = static_cast<int>(h);
  return c;
}

LookingGlassCalibration read_looking_glass(const std::string& path) { return parse_looking_glass(read_text_file(path), path); }

double looking_glass_view(const LookingGlassCalibration& c, int i, int j, int s) {
  const double W = c.width, H = c.height;
  double u = (i + 0.5) / W, v = (H - j - 0.5) / H;
  if (c.flip_x) u = 1 - u;
  if (c.flip_y) v = 1 - v;
  const int sub = c.flip_subp ? 2 - s : s;
  const double lenticules = c.pitch * (W / c.dpi) * std::cos(std::atan(1 / c.slope));
  const double a = (u + sub / (3 * W) + v * H / (W * c.slope)) * lenticules - c.center;
  double f = a - std::floor(a);
  if (c.inv_view) f = 1 - f;
  return f >= 1 ? 0 : f;  // 1 - 0 wraps to the same place as 0
}

LookingGlassCamera::LookingGlassCamera(const LookingGlassCalibration& c, const PinholeDesc& centre) : c_(c), centre_(centre) {
  centre_.width = c.width, centre_.height = c.height;
  PinholeCamera check(centre_);  // validates the centre view
  (void)check;
  frame_ = Frame::from_normal_up(centre_.from, centre_.from - centre_.at, centre_.up);
  if (centre_.mirrored) frame_.x = -frame_.x;
  distance_ = length(centre_.at - centre_.from);
  pixel_ = 2 * std::tan(centre_.fov_deg * kPi / 360) / c.height;
}

PixelLine LookingGlassCamera::line(int c, int j, double u, double v) const {
  // PinholeCamera(sheared_view(centre, phi)).line(i, j, u, v), with the
  // centre view's frame computed once instead of per subpixel.
  const int i = c / 3, s = c % 3;
  const double t = std::tan((looking_glass_view(c_, i, j, s) - 0.5) * c_.view_cone_deg * kPi / 180);
  const double x = (i + u + (centre_.sample_u - 0.5) - 0.5 * c_.width) * pixel_ + (centre_.shift_x - t);
  const double y = (0.5 * c_.height - (j + v + (centre_.sample_v - 0.5))) * pixel_;
  return {centre_.from + frame_.x * (distance_ * t), normalize(frame_.to_world_dir({x, y, -1}))};
}

void LookingGlassCamera::project(const Vec3&, std::vector<PanelHit>&) const {
  throw std::logic_error("a Looking Glass panel has one view per subpixel: project through its quilt views instead");
}

ImageBuffer interlace_quilt(const ImageBuffer& quilt, const QuiltDesc& q, const LookingGlassCalibration& c) {
  if (quilt.width != q.columns * q.view_width || quilt.height != q.rows * q.view_height || quilt.channels < 3)
    throw std::invalid_argument(fmt::format("the quilt image is {}x{} ({} channels); a {}x{} quilt of {}x{} views is {}x{} RGB",
                                            quilt.width, quilt.height, quilt.channels, q.columns, q.rows, q.view_width,
                                            q.view_height, q.columns * q.view_width, q.rows * q.view_height));
  const int n = q.columns * q.rows;
  ImageBuffer out(c.width, c.height, 3);
  // Channel ch of view k at (x, y) in view pixels, bilinear, clamped to the view.
  auto sample = [&](int k, double x, double y, int ch) {
    const int x0 = (k % q.columns) * q.view_width, y0 = (q.rows - 1 - k / q.columns) * q.view_height;
    x = std::clamp(x, 0.0, q.view_width - 1.0), y = std::clamp(y, 0.0, q.view_height - 1.0);
    const int ix = static_cast<int>(x), iy = static_cast<int>(y);
    const int ix1 = std::min(ix + 1, q.view_width - 1), iy1 = std::min(iy + 1, q.view_height - 1);
    const double fx = x - ix, fy = y - iy;
    auto at = [&](int a, int b) { return double(quilt.at(x0 + a, y0 + b)[ch]); };
    const double top = at(ix, iy) + fx * (at(ix1, iy) - at(ix, iy));
    const double bottom = at(ix, iy1) + fx * (at(ix1, iy1) - at(ix, iy1));
    return top + fy * (bottom - top);
  };
  for (int j = 0; j < c.height; ++j)
    for (int i = 0; i < c.width; ++i) {
      // The pixel's centre in view pixels (a view spans the whole panel).
      const double x = (i + 0.5) * q.view_width / c.width - 0.5, y = (j + 0.5) * q.view_height / c.height - 0.5;
      for (int ch = 0; ch < 3; ++ch) {
        const double view = n == 1 ? 0 : looking_glass_view(c, i, j, ch) * (n - 1);
        const int k0 = std::min(static_cast<int>(view), n - 1), k1 = std::min(k0 + 1, n - 1);
        const double t = view - k0;
        const double a = sample(k0, x, y, ch);
        out.at(i, j)[ch] = static_cast<float>(t == 0 ? a : a + t * (sample(k1, x, y, ch) - a));
      }
    }
  return out;
}

}  // namespace holoray
