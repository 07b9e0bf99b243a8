#include "camera/placement.hpp"

#include <numbers>
#include <fmt/format.h>

#include <stdexcept>

namespace holoray {

ViewPlacement place_by_viewpoint(RecordingMode mode, const Viewpoint& vp) {
  ViewPlacement out;
  const Vec3 view = vp.at - vp.from;
  if (mode == RecordingMode::orthoscopic)
    out.frame = Frame::from_normal_up(vp.at, -view, vp.up);
  else
    out.frame = Frame::from_normal_up(vp.from, view, vp.up);
  // Tachyon's screen is left-handed: so is the array it places (its
  // sub-aperture views then show what Tachyon's camera shows).
  if (vp.mirrored) out.frame.x = -out.frame.x;
  // The field across the viewpoint's own fov_axis side (NFF: the vertical
  // angle, the contract's); an orthographic camera's is its extent.
  out.width = vp.ortho_size > 0 ? vp.ortho_size : 2 * length(view) * std::tan(vp.angle_deg * std::numbers::pi / 360);
  return out;
}

std::optional<Frame> explicit_frame(const ArraySettings& s) {
  if (!(s.origin || s.normal || s.up)) return std::nullopt;
  if (!(s.origin && s.normal && s.up))
    throw std::invalid_argument("explicit placement needs all of `origin`, `normal` and `up`");
  return Frame::from_normal_up(*s.origin, *s.normal, *s.up);
}

LensArrayDesc place_array(const ArraySettings& s, const std::optional<Viewpoint>& vp) {
  LensArrayDesc d;
  d.grid = s.grid;
  d.mode = s.mode;
  d.lenses_x = s.lenses_x;
  d.lenses_y = s.lenses_y;
  d.pixels_per_lens = s.pixels_per_lens;
  d.rows = s.rows;
  d.view_distance = s.view_distance;
  if (s.lenses_x < 1 || s.lenses_y < 1)
    throw std::invalid_argument(fmt::format("lens counts must be at least 1, got {}x{}", s.lenses_x, s.lenses_y));

  if (const std::optional<Frame> frame = explicit_frame(s)) {
    if (!s.pitch) throw std::invalid_argument("explicit placement needs `pitch` (the lens pitch in scene units)");
    d.frame = *frame;
    d.pitch = *s.pitch;
  } else {
    if (!vp)
      throw std::invalid_argument(
          "the scene has no viewpoint ('v'); place the array with `origin`, `normal`, `up` and `pitch`");
    const ViewPlacement placed = place_by_viewpoint(s.mode, *vp);
    d.frame = placed.frame;
    d.pitch = s.pitch ? *s.pitch : placed.width / s.lenses_x;
  }

  if (s.gap && s.fov_lens_deg) throw std::invalid_argument("give either `gap` or `fov_lens_deg`, not both");
  if (s.gap) {
    d.gap = *s.gap;
  } else {
    const double fov = s.fov_lens_deg.value_or(kDefaultLensFovDeg);
    if (!(fov > 0 && fov < 180))
      throw std::invalid_argument(fmt::format("lens field of view must be between 0 and 180 degrees, got {}", fov));
    d.gap = d.pitch / (2 * std::tan(fov * std::numbers::pi / 360));
  }
  return d;
}

}  // namespace holoray
