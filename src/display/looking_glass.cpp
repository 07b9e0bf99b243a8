#include "display/looking_glass.hpp"

#include <numbers>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>

#include "util/parallel.hpp"  // parallel_for_n: rows on all cores
#include "scene/file_text.hpp"

namespace holoray {

namespace {

constexpr double kPi = std::numbers::pi;

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
  if (const auto it = j.find("subpixelCells"); it != j.end()) {
    if (!it->is_array())
      throw std::runtime_error(fmt::format("{}: expected 'subpixelCells' to be an array of cells, found {}", source, it->dump()));
    if (it->size() > kMaxSubpixelCells)
      throw std::runtime_error(fmt::format("{}: expected at most {} 'subpixelCells' (the device shader holds {} floats), found {}",
                                           source, kMaxSubpixelCells, 6 * kMaxSubpixelCells, it->size()));
    for (size_t k = 0; k < it->size(); ++k) {
      const nlohmann::json& cell = (*it)[k];
      const std::string where = fmt::format("{} (subpixelCells[{}])", source, k);
      if (!cell.is_object()) throw std::runtime_error(fmt::format("{}: expected an object of offsets, found {}", where, cell.dump()));
      SubpixelCell sc;
      const char* names[3][2] = {{"ROffsetX", "ROffsetY"}, {"GOffsetX", "GOffsetY"}, {"BOffsetX", "BOffsetY"}};
      for (int s = 0; s < 3; ++s) sc.dx[s] = field(cell, names[s][0], where), sc.dy[s] = field(cell, names[s][1], where);
      c.cells.push_back(sc);
    }
  }
  const double pattern = field(j, "CellPatternMode", source, 1.0);
  if (!(pattern >= 0 && pattern <= 4 && pattern == std::floor(pattern)))
    throw std::runtime_error(fmt::format("{}: expected 'CellPatternMode' to be 0, 1, 2, 3 or 4, found {}", source, pattern));
  c.cell_pattern = static_cast<int>(pattern);
  return c;
}

LookingGlassCalibration read_looking_glass(const std::string& path) { return parse_looking_glass(read_text_file(path), path); }

int looking_glass_cell(const LookingGlassCalibration& c, int i, int j) {
  return camera_lines::hr_looking_glass_cell(c.cell_pattern, static_cast<int>(c.cells.size()), c.height, i, j);
}

double looking_glass_view(const LookingGlassCalibration& c, int i, int j, int s) {
  const double W = c.width, H = c.height;
  const double u = (i + 0.5) / W, v = (H - j - 0.5) / H;
  const double flip = c.flip_x ? -1 : 1;
  const double tilt = H / (W * c.slope) * flip;
  const double lenticules = c.pitch * W / c.dpi * std::cos(std::atan(1 / c.slope));
  double a;
  if (c.cells.empty()) {
    a = u + s * (flip / (3 * W)) + v * tilt;
  } else {
    const SubpixelCell& cell = c.cells[static_cast<size_t>(looking_glass_cell(c, i, j))];
    a = (u + cell.dx[s] / W) + (v + cell.dy[s] / H) * tilt;
  }
  a = a * lenticules - c.center;
  return std::clamp(1 - (a - std::floor(a)), 0.00001, 0.999999);
}

ViewBlend looking_glass_blend(double x, int views) {
  // OldViewFiltering: the view index of x and of x + 1/N (GetViewsColors'
  // int()), and the weight fract(x N); index N is read from a quilt texture
  // that repeats: view 0.
  const double n = views;
  ViewBlend b;
  b.first = static_cast<int>(x * n);
  b.second = static_cast<int>((x + 1 / n) * n);
  if (b.second >= views) b.second = 0;
  b.first = std::min(b.first, views - 1);
  b.w = x * n - std::floor(x * n);
  return b;
}

LookingGlassCamera::LookingGlassCamera(const LookingGlassCalibration& c, const PinholeDesc& centre, int views)
    : c_(c), centre_(centre), views_(views) {
  if (views < 1) throw std::invalid_argument(fmt::format("a Looking Glass quilt has at least 1 view, got {}", views));
  centre_.width = c.width, centre_.height = c.height;
  PinholeCamera check(centre_);  // validates the centre view
  (void)check;
  frame_ = Frame::from_normal_up(centre_.from, centre_.from - centre_.at, centre_.up);
  if (centre_.mirrored) frame_.x = -frame_.x;
  distance_ = length(centre_.at - centre_.from);
  pixel_ = 2 * std::tan(centre_.fov_deg * kPi / 360) / c.height;
  lines_ = {.centre = {.width = c.width,
                       .height = c.height,
                       .ortho = 0,
                       .pixel = pixel_,
                       .sample_u = centre_.sample_u,
                       .sample_v = centre_.sample_v,
                       .shift_x = centre_.shift_x,
                       .shift_y = 0},
            .views = views,
            .view_cone_deg = c.view_cone_deg,
            .distance = distance_};
}

PixelLine LookingGlassCamera::line(int c, int j, double u, double v) const {
  const int i = c / 3, s = c % 3;
  PixelLine l;
  camera_lines::hr_looking_glass_line(lines_, frame_, i, j, u, v, looking_glass_view(c_, i, j, s), l.origin, l.dir);
  return l;
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
  const int qw = quilt.width, qh = quilt.height;
  // The shader's texture(u_texture, quilt_uv): bilinear between texel
  // centres, the texture repeating (GL's default wrap); (s, t) from the
  // bottom-left corner, the image's rows from the top.
  auto texture = [&](double s, double t, int ch) {
    const double x = s * qw - 0.5, y = t * qh - 0.5;
    const double x0 = std::floor(x), y0 = std::floor(y);
    const double fx = x - x0, fy = y - y0;
    auto wrap = [](double k, int size) { return static_cast<int>(k - size * std::floor(k / size)); };
    const int xa = wrap(x0, qw), xb = wrap(x0 + 1, qw);
    const int ya = qh - 1 - wrap(y0, qh), yb = qh - 1 - wrap(y0 + 1, qh);
    auto at = [&](int a, int b) { return double(quilt.at(a, b)[ch]); };
    const double lo = at(xa, ya) + fx * (at(xb, ya) - at(xa, ya));
    const double hi = at(xa, yb) + fx * (at(xb, yb) - at(xa, yb));
    return lo + fy * (hi - lo);
  };
  // GetQuiltCoordinates: view k's tile, with the shader's column count
  // less 0.00001 ("on some platforms this is required"), which shifts the
  // reads of upper rows by a hundred-thousandth of a tile.
  const double tx = q.columns - 0.00001;
  auto sample = [&](int k, double u, double v, int ch) {
    const double view = std::clamp(static_cast<double>(k), 0.0, static_cast<double>(n));
    const double row = std::floor(view / tx), column = view - tx * row;
    return texture((column + u) / tx, (row + v) / q.rows, ch);
  };
  ImageBuffer out(c.width, c.height, 3);
  parallel_for_n(c.height, 0, [&](int j) {
    for (int i = 0; i < c.width; ++i) {
      const double u = (i + 0.5) / c.width, v = (c.height - j - 0.5) / c.height;
      for (int ch = 0; ch < 3; ++ch) {
        const ViewBlend b = looking_glass_blend(looking_glass_view(c, i, j, ch), n);
        // After the last view the shader reads tile N, which the repeating
        // texture turns into view 0 (read a hair to the side).
        const int second = b.first == n - 1 ? n : b.second;
        const double first = sample(b.first, u, v, ch), next = sample(second, u, v, ch);
        out.at(i, j)[ch] = static_cast<float>(first * (1 - b.w) + next * b.w);  // GLSL mix()
      }
    }
  });
  return out;
}

}  // namespace holoray
