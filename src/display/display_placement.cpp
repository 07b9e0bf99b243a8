#include "display/display_placement.hpp"

#include <numbers>
#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "camera/placement.hpp"

namespace holoray {

namespace {

constexpr double kPi = std::numbers::pi;

struct Placed {
  Frame frame;
  double units_per_mm = 0;
};

Placed place(const DisplayDesc& d, const std::optional<Viewpoint>& vp, const std::optional<Frame>& explicit_frame) {
  Placed out;
  if (explicit_frame) {
    if (!d.units_per_mm)
      throw std::invalid_argument(fmt::format(
          "{}: placing the array with `origin`, `normal` and `up` needs [scene] units_per_mm in the display file",
          d.source));
    out.frame = *explicit_frame;
    out.units_per_mm = *d.units_per_mm;
  } else {
    if (!vp)
      throw std::invalid_argument(
          "the scene has no viewpoint to place the display by; give `origin`, `normal` and `up` (and units_per_mm "
          "in the display file)");
    const ViewPlacement view = place_by_viewpoint(d.mode, *vp);
    out.frame = view.frame;
    out.units_per_mm = d.units_per_mm ? *d.units_per_mm : view.width / (d.width * d.pixel_pitch_mm);
  }
  if (d.depth != 0) out.frame.origin += out.frame.z * d.depth;
  return out;
}

}  // namespace

DisplayGeometry place_display(const DisplayDesc& d, const std::optional<Viewpoint>& vp,
                              const std::optional<Frame>& explicit_frame) {
  const Placed at = place(d, vp, explicit_frame);
  const double k = at.units_per_mm;
  DisplayGeometry g;
  g.width = d.width;
  g.height = d.height;
  g.samples_per_pixel = d.samples_per_pixel();
  g.pixel_pitch = d.pixel_pitch_mm * k;
  g.grid = d.grid;
  g.pitch = d.pitch_mm * k;
  g.slant_rad = d.slant_deg * kPi / 180;
  g.gap = d.gap_mm * k;
  g.offset = d.offset_mm * k;
  g.view_distance = d.view_distance_mm * k;
  g.mode = d.mode;
  g.frame = at.frame;
  return g;
}

std::optional<LensArrayDesc> as_lens_array(const DisplayDesc& d, const std::optional<Viewpoint>& vp,
                                           const std::optional<Frame>& explicit_frame) {
  if (d.subpixels != SubpixelOrder::none || d.slant_deg != 0 || d.offset_mm != 0 || d.grid == Grid::hex)
    return std::nullopt;
  const double ratio = d.pitch_mm / d.pixel_pitch_mm;
  const double P = std::round(ratio);
  if (P < 1 || std::fabs(ratio - P) > 1e-9 * P) return std::nullopt;
  const int p = static_cast<int>(P);
  if (d.width % p != 0 || (d.grid == Grid::square && d.height % p != 0)) return std::nullopt;
  const Placed at = place(d, vp, explicit_frame);
  ArraySettings s;
  s.grid = d.grid;
  s.mode = d.mode;
  s.lenses_x = d.width / p;
  s.lenses_y = d.grid == Grid::square ? d.height / p : 1;
  s.pixels_per_lens = p;
  s.rows = d.grid == Grid::lenticular ? d.height : 0;
  s.gap = d.gap_mm * at.units_per_mm;
  s.view_distance = d.view_distance_mm * at.units_per_mm;
  // Without units_per_mm the viewpoint's field sets the pitch, as it does
  // for `render` without --pitch.
  if (d.units_per_mm || explicit_frame) s.pitch = d.pitch_mm * at.units_per_mm;
  std::optional<Viewpoint> view = vp;
  if (explicit_frame) {
    s.origin = at.frame.origin, s.normal = at.frame.z, s.up = at.frame.y;
    view.reset();
  }
  LensArrayDesc desc = place_array(s, view);
  if (!explicit_frame && d.depth != 0) desc.frame.origin += desc.frame.z * d.depth;
  return desc;
}

}  // namespace holoray
