#include "camera/lens_array.hpp"

#include "math/vec_pair.hpp"

#include <numbers>
#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

namespace holoray {

namespace {
constexpr double kSqrt3 = 1.7320508075688772;
constexpr double kPi = std::numbers::pi;
}  // namespace

const char* to_string(Grid g) {
  switch (g) {
    case Grid::square: return "square";
    case Grid::hex: return "hex";
    case Grid::lenticular: return "lenticular";
  }
  return "?";
}

const char* to_string(RecordingMode m) {
  return m == RecordingMode::orthoscopic ? "orthoscopic" : "pseudoscopic";
}

LensArray::LensArray(const LensArrayDesc& d) : desc_(d) {
  if (!(d.pitch > 0) || !std::isfinite(d.pitch))
    throw std::invalid_argument(fmt::format("lens pitch must be positive and finite, got {}", d.pitch));
  if (!(d.gap > 0) || !std::isfinite(d.gap))
    throw std::invalid_argument(fmt::format("gap must be positive and finite, got {}", d.gap));
  if (d.lenses_x < 1 || (d.grid != Grid::lenticular && d.lenses_y < 1))
    throw std::invalid_argument(fmt::format("lens counts must be at least 1, got {}x{}", d.lenses_x, d.lenses_y));
  if (d.pixels_per_lens < 1)
    throw std::invalid_argument(fmt::format("pixels per lens must be at least 1, got {}", d.pixels_per_lens));
  if (d.rows < 0) throw std::invalid_argument(fmt::format("rows must be at least 1, got {}", d.rows));
  if (!(d.view_distance > 0))
    throw std::invalid_argument(fmt::format("view distance must be positive, got {}", d.view_distance));

  const int64_t w = static_cast<int64_t>(d.lenses_x) * d.pixels_per_lens;
  int64_t h = 0;
  switch (d.grid) {
    case Grid::square: h = static_cast<int64_t>(d.lenses_y) * d.pixels_per_lens; break;
    case Grid::hex: h = d.rows > 0 ? d.rows : std::llround(d.lenses_y * d.pixels_per_lens * kSqrt3 / 2); break;
    case Grid::lenticular: h = d.rows > 0 ? d.rows : w; break;
  }
  constexpr int64_t kMaxDim = int64_t{1} << 30;
  if (w > kMaxDim || h > kMaxDim || h < 1)
    throw std::invalid_argument(fmt::format("image of {}x{} pixels: each side must be between 1 and {}", w, h, kMaxDim));
  width_ = static_cast<int>(w);
  height_ = static_cast<int>(h);
  s_ = d.pitch / d.pixels_per_lens;
  inv_s_ = 1 / s_;
  half_w_ = width_ * s_ / 2;
  half_h_ = height_ * s_ / 2;
  row_step_ = d.pitch * kSqrt3 / 2;
  grid_ = {.grid = d.grid == Grid::square ? HR_LINE_GRID_SQUARE : d.grid == Grid::hex ? HR_LINE_GRID_HEX : HR_LINE_GRID_LENTICULAR,
           .pixels_per_lens = d.pixels_per_lens,
           .lenses_x = d.lenses_x,
           .lenses_y = d.lenses_y,
           .converging = std::isinf(d.view_distance) ? 0 : 1,
           .pitch = d.pitch,
           .gap = d.gap,
           .s = s_,
           .half_w = half_w_,
           .half_h = half_h_,
           .row_step = row_step_,
           .view_distance = d.view_distance};
  switch (d.grid) {
    case Grid::square:
      reach_x_ = reach_y_ = d.pitch / 2;
      break;
    case Grid::hex:
      // Border pixels belong to the nearest centre even outside its hexagon.
      reach_x_ = d.pitch;
      reach_y_ = std::max({d.pitch / kSqrt3, d.pitch / 2, height_ * s_ - d.pitch / 2 - (d.lenses_y - 1) * row_step_});
      break;
    case Grid::lenticular:
      reach_x_ = d.pitch / 2;
      reach_y_ = INFINITY;
      break;
  }
}

double LensArray::lens_fov_deg() const { return 2 * std::atan(desc_.pitch / (2 * desc_.gap)) * 180 / kPi; }

LensIndex LensArray::hex_lens_of_pixel(int i, int j) const {
  const shading::ivec2 l = camera_lines::hr_hex_lens_of_pixel(grid_, i, j);
  return {l.x, l.y};
}

PixelLine LensArray::line_local(int i, int j, double u, double v) const {
  PixelLine l;
  camera_lines::hr_lens_array_line(grid_, i, j, u, v, l.origin, l.dir);
  return l;
}

PixelLine LensArray::line(int i, int j, double u, double v) const {
  const PixelLine l = line_local(i, j, u, v);
  return {desc_.frame.to_world_point(l.origin), desc_.frame.to_world_dir(l.dir)};
}

void LensArray::lines(const int i[], const int j[], const double u[], const double v[], int n,
                      PixelLineLanes& out) const {
  if (n > PixelLineLanes::kLaneCount)
    throw std::invalid_argument(fmt::format("at most {} lines at once, got {}", PixelLineLanes::kLaneCount, n));
  auto put = [&](int k, const PixelLine& l) {
    out.ox[k] = l.origin.x, out.oy[k] = l.origin.y, out.oz[k] = l.origin.z;
    out.dx[k] = l.dir.x, out.dy[k] = l.dir.y, out.dz[k] = l.dir.z;
  };
  if (desc_.grid == Grid::lenticular) {  // the origin moves with the pixel row
    for (int k = 0; k < n; ++k) put(k, line(i[k], j[k], u[k], v[k]));
    return;
  }
  // Lens centres lane by lane (the grid's integer work, once per lens), in
  // the array frame for the directions and in the world for the origins.
  alignas(16) double cx[PixelLineLanes::kLaneCount], cy[PixelLineLanes::kLaneCount];
  LensIndex lens{-1, -1};
  Vec3 c, c_world;
  const bool square = desc_.grid == Grid::square;
  for (int k = 0; k < n; ++k) {
    // A square lens's own pixels skip lens_of_pixel's two integer
    // divisions (a sixth of the eye rays' generation).
    if (!(square && lens.x >= 0 && pixel_in_lens(i[k], j[k], lens))) {
      const LensIndex l = lens_of_pixel(i[k], j[k]);
      if (!(l == lens)) {
        lens = l;
        c = lens_centre_local(l);
        c_world = desc_.frame.to_world_point(c);
      }
    }
    cx[k] = c.x, cy[k] = c.y;
    out.ox[k] = c_world.x, out.oy[k] = c_world.y, out.oz[k] = c_world.z;
  }
  // line(): d = normalize(c - p), p = ((i + u) s - W s/2, H s/2 - (j + v) s,
  // -g), so d's z before normalising is 0 - (-g) = g exactly.
  const Frame& f = desc_.frame;
  const __m128d s = _mm_set1_pd(s_), hw = _mm_set1_pd(half_w_), hh = _mm_set1_pd(half_h_), g = _mm_set1_pd(desc_.gap);
  int k = 0;
  for (; k + 1 < n; k += 2) {
    const __m128d fi = _mm_set_pd(i[k + 1], i[k]), fj = _mm_set_pd(j[k + 1], j[k]);
    const __m128d px = _mm_sub_pd(_mm_mul_pd(_mm_add_pd(fi, _mm_loadu_pd(u + k)), s), hw);
    const __m128d py = _mm_sub_pd(hh, _mm_mul_pd(_mm_add_pd(fj, _mm_loadu_pd(v + k)), s));
    const Vec3Pair d = to_world_dir(
        f, normalize(Vec3Pair{_mm_sub_pd(_mm_load_pd(cx + k), px), _mm_sub_pd(_mm_load_pd(cy + k), py), g}));
    _mm_store_pd(out.dx + k, d.x);
    _mm_store_pd(out.dy + k, d.y);
    _mm_store_pd(out.dz + k, d.z);
  }
  for (; k < n; ++k) {
    const Vec3 d = f.to_world_dir(normalize(Vec3{cx[k], cy[k], 0} - panel_point_local(i[k], j[k], u[k], v[k])));
    out.dx[k] = d.x, out.dy[k] = d.y, out.dz[k] = d.z;
  }
}

void LensArray::project(const Vec3& p_world, std::vector<PanelHit>& out) const {
  out.clear();
  project_local(desc_.frame.to_local_point(p_world), out);
}

void LensArray::project_local(const Vec3& x, std::vector<PanelHit>& out) const {
  if (x.z == 0 || !is_finite(x)) return;
  const double g = desc_.gap, pitch = desc_.pitch;
  const bool lenticular = desc_.grid == Grid::lenticular;
  // Lenses whose panel pixels can lie on a line through x: |c - x| <= reach * |x.z| / g per axis.
  const double rx = reach_x_ * std::fabs(x.z) / g, ry = reach_y_ * std::fabs(x.z) / g;
  const double half_array_w = desc_.lenses_x * pitch / 2;
  const auto clamp_x = [&](double v) { return static_cast<int>(std::clamp(v, -1.0, double(desc_.lenses_x))); };
  const int lx_lo = std::max(0, clamp_x(std::floor((x.x - rx + half_array_w) / pitch - 1)));
  const int lx_hi = std::min(desc_.lenses_x - 1, clamp_x(std::ceil((x.x + rx + half_array_w) / pitch)));
  int ly_lo = 0, ly_hi = 0;
  if (!lenticular) {
    const double top = desc_.grid == Grid::hex ? half_h_ - pitch / 2 : desc_.lenses_y * pitch / 2 - pitch / 2;
    const double step = desc_.grid == Grid::hex ? row_step_ : pitch;
    const auto clamp_y = [&](double v) { return static_cast<int>(std::clamp(v, -1.0, double(desc_.lenses_y))); };
    ly_lo = std::max(0, clamp_y(std::floor((top - (x.y + ry)) / step - 1)));
    ly_hi = std::min(desc_.lenses_y - 1, clamp_y(std::ceil((top - (x.y - ry)) / step + 1)));
  }
  PanelHit h;
  for (int ly = ly_lo; ly <= ly_hi; ++ly)
    for (int lx = lx_lo; lx <= lx_hi; ++lx)
      if (project_through(x, LensIndex{lx, ly}, h)) out.push_back(h);
}

namespace {
// floor(v) clamped to [0, n - 1] (NaN: 0). Truncation is floor once v > 0;
// std::floor is a call-free instruction only from SSE4.1 on.
inline int clamped_index(double v, int n) {
  if (!(v > 0)) return 0;
  return v < n - 1 ? static_cast<int>(v) : n - 1;
}
}  // namespace

LensIndex LensArray::lens_near(const Vec3& p_local) const {
  return lens_of_pixel(clamped_index((p_local.x + half_w_) * inv_s_, width_),
                       clamped_index((half_h_ - p_local.y) * inv_s_, height_));
}

bool LensArray::project_along(const Vec3& x, const Vec3& d, PanelHit& out, LensIndex* lens_out) const {
  if (d.z == 0) return false;
  const LensIndex lens = lens_near(x - d * (x.z / d.z));
  LensIndex landed{-1, -1};
  if (!project_through(x, lens, out, &landed) &&
      (landed.x < 0 || landed == lens || !project_through(x, landed, out)))
    return false;
  if (lens_out) *lens_out = landed;  // project_through sets it to the lens it succeeded through
  return true;
}

bool LensArray::project_through(const Vec3& x, LensIndex lens, PanelHit& out, LensIndex* landing_lens) const {
  if (x.z == 0 || !is_finite(x)) return false;
  const double g = desc_.gap;
  const Vec3 c = lens_centre_local(lens);
  double px, py;
  if (desc_.grid == Grid::lenticular) {
    px = c.x - g * (x.x - c.x) / x.z;
    const double k = std::isinf(desc_.view_distance) ? 1.0 : 1.0 - x.z / desc_.view_distance;
    if (k == 0) return false;
    py = x.y / k;
  } else {
    const double sc = g / x.z;  // p = c + (c - x) * g / x.z lies on z = -g
    px = c.x + (c.x - x.x) * sc;
    py = c.y + (c.y - x.y) * sc;
  }
  const double fi = (px + half_w_) * inv_s_, fj = (half_h_ - py) * inv_s_;
  if (!(fi >= 0 && fi < width_ && fj >= 0 && fj < height_)) {
    if (landing_lens && std::isfinite(fi) && std::isfinite(fj)) {
      const int ci = static_cast<int>(std::clamp(fi, 0.0, width_ - 1.0));
      const int cj = static_cast<int>(std::clamp(fj, 0.0, height_ - 1.0));
      *landing_lens = lens_of_pixel(ci, cj);
    }
    return false;
  }
  const int i = static_cast<int>(fi), j = static_cast<int>(fj);
  if (!pixel_in_lens(i, j, lens)) {
    if (landing_lens) *landing_lens = lens_of_pixel(i, j);
    return false;
  }
  if (landing_lens) *landing_lens = lens;
  double t;
  if (desc_.grid == Grid::lenticular) {
    const PixelLine l = line_local(i, j, fi - i, fj - j);
    t = dot(x - l.origin, l.dir);
  } else {
    // x lies on the line from the lens centre along its unit direction
    // toward +z, so t is the signed distance from the centre.
    t = std::copysign(length(x - c), x.z);
  }
  if (desc_.mode == RecordingMode::pseudoscopic && !(t > 0)) return false;
  out = {i, j, fi - i, fj - j, t};
  return true;
}

}  // namespace holoray
