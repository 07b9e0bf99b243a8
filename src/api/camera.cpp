#include <fmt/format.h>

#include <cmath>
#include <stdexcept>
#include <system_error>

#include "api/internal.hpp"
#include "display/display_file.hpp"
#include "display/looking_glass.hpp"
#include "holoray/errors.hpp"

namespace holoray::api {

namespace {

Vec3 vec(const std::array<double, 3>& v) { return {v[0], v[1], v[2]}; }

void place_explicitly(ArraySettings& s, const std::optional<Placement>& p) {
  if (!p) return;
  s.origin = vec(p->origin);
  s.normal = vec(p->normal);
  s.up = vec(p->up);
}

ArraySettings settings_of(const LensArray& a) {
  ArraySettings s;
  s.grid = a.grid == Grid::hex ? holoray::Grid::hex : a.grid == Grid::lenticular ? holoray::Grid::lenticular : holoray::Grid::square;
  s.mode = a.mode == Mode::pseudoscopic ? RecordingMode::pseudoscopic : RecordingMode::orthoscopic;
  if (a.lenses_x < 1 || a.lenses_y < 1)
    throw std::invalid_argument(fmt::format("lenses: expected at least 1x1, got {}x{}", a.lenses_x, a.lenses_y));
  if (a.pixels_per_lens < 1)
    throw std::invalid_argument(fmt::format("pixels_per_lens: expected at least 1, got {}", a.pixels_per_lens));
  if (a.rows < 0) throw std::invalid_argument(fmt::format("rows: expected at least 1 (0: the contract's), got {}", a.rows));
  s.lenses_x = a.lenses_x;
  s.lenses_y = a.lenses_y;
  s.pixels_per_lens = a.pixels_per_lens;
  s.rows = a.rows;
  s.pitch = a.pitch;
  s.gap = a.gap;
  s.fov_lens_deg = a.fov_lens_deg;
  s.view_distance = a.view_distance;
  place_explicitly(s, a.placement);
  return s;
}

// A display or calibration file read by `read`: its errors are SceneErrors,
// with a position where the reader knows one (syntax), without (a value);
// a file that cannot be read is a std::system_error, as everywhere.
template <class Read>
auto read_file(const std::string& path, Read&& read) {
  try {
    return read(path);
  } catch (const SceneError&) {
    throw;
  } catch (const std::system_error&) {  // I/O stays I/O
    throw;
  } catch (const std::runtime_error& e) {
    throw SceneError(path, 0, 0, e.what(), e.what());
  }
}

}  // namespace

DisplayDesc read_display(const std::string& path) { return read_file(path, read_display_file); }

LookingGlassCalibration read_calibration(const std::string& path) { return read_file(path, read_looking_glass); }

FrameCameraDesc frame_camera_desc(const Camera& camera) {
  using Desc = FrameCameraDesc;
  FrameCameraDesc d;
  if (const auto* a = std::get_if<LensArray>(&camera)) {
    d.kind = Desc::Integral{settings_of(*a)};
    if (a->focus_distance && a->placement)
      throw std::invalid_argument("focus_distance: goes with the viewpoint's placement, not an explicit one");
    d.focus_distance = a->focus_distance;
  } else if (const auto* p = std::get_if<Pinhole>(&camera)) {
    if (p->width < 0 || p->height < 0 || (p->width == 0) != (p->height == 0) || p->width > 65536 || p->height > 65536)
      throw std::invalid_argument(
          fmt::format("resolution: expected 1 to 65536 pixels each way (or 0x0: the scene's), got {}x{}", p->width, p->height));
    if (!std::isfinite(p->shift_x) || !std::isfinite(p->shift_y))
      throw std::invalid_argument(fmt::format("shift: expected finite fractions of the larger side, got {}, {}", p->shift_x, p->shift_y));
    d.kind = Desc::Pinhole{p->width, p->height, p->tachyon_samples, p->shift_x, p->shift_y};
  } else if (const auto* q = std::get_if<Quilt>(&camera)) {
    if (q->columns < 1 || q->rows < 1 || int64_t{q->columns} * q->rows > 4096)
      throw std::invalid_argument(fmt::format("quilt: expected 1 to 4096 views, got {}x{}", q->columns, q->rows));
    if (q->view_width < 1 || q->view_height < 1 || q->view_width > 65536 || q->view_height > 65536)
      throw std::invalid_argument(
          fmt::format("view_resolution: expected 1 to 65536 pixels each way, got {}x{}", q->view_width, q->view_height));
    if (!(q->view_cone_deg >= 0 && q->view_cone_deg <= 180))
      throw std::invalid_argument(fmt::format("view_cone: expected degrees in [0, 180], got {}", q->view_cone_deg));
    if (q->view >= q->columns * q->rows)
      throw std::invalid_argument(fmt::format("view: a {}x{} quilt has views 0 to {}, got {}", q->columns, q->rows,
                                              q->columns * q->rows - 1, q->view));
    QuiltDesc layout;
    layout.columns = q->columns;
    layout.rows = q->rows;
    layout.view_width = q->view_width;
    layout.view_height = q->view_height;
    layout.view_cone_deg = q->view_cone_deg;
    d.kind = Desc::Quilt{layout, q->view};
    d.focus_distance = q->focus_distance;
  } else if (const auto* s = std::get_if<Display>(&camera)) {
    DisplayDesc display = read_display(s->path);
    if (s->focus_distance && s->placement)
      throw std::invalid_argument("focus_distance: goes with the viewpoint's placement, not an explicit one");
    ArraySettings placement;
    place_explicitly(placement, s->placement);
    d.kind = Desc::Display{std::move(display), explicit_frame(placement)};
    d.focus_distance = s->focus_distance;
  } else if (const auto* g = std::get_if<LookingGlass>(&camera)) {
    if (g->views < 1 || g->views > 4096) throw std::invalid_argument(fmt::format("views: expected 1 to 4096, got {}", g->views));
    d.kind = Desc::LookingGlass{read_calibration(g->path), g->views};
    d.focus_distance = g->focus_distance;
  }
  return d;
}

}  // namespace holoray::api
