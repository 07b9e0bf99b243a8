#include "live/view_controls.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace holoray::live {

namespace {

// v turned by `angle` radians about the unit axis k (Rodrigues).
Vec3 turn(const Vec3& v, const Vec3& k, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return v * c + cross(k, v) * s + k * (dot(k, v) * (1 - c));
}

}  // namespace

double focus(const LiveView& view) {
  return view.focus_distance.value_or(length(view.viewpoint.at - view.viewpoint.from));
}

void orbit(LiveView& view, double dx, double dy, int width, int height) {
  Viewpoint& vp = view.viewpoint;
  const Vec3 up = normalize(vp.up);
  Vec3 offset = vp.from - vp.at;
  // Dragging right turns the scene right: the eye goes left about up.
  offset = turn(offset, up, -std::numbers::pi * dx / std::max(1, width));
  // Dragging down tips the scene's top toward the viewer: the eye rises.
  const double r = length(offset);
  const double elevation = std::asin(std::clamp(dot(offset, up) / r, -1.0, 1.0));
  const double limit = std::numbers::pi / 2 - std::numbers::pi / 180;
  const double wanted = std::clamp(elevation + std::numbers::pi / 2 * dy / std::max(1, height), -limit, limit);
  const Vec3 right = cross(up, offset);  // the eye's left seen from at; the axis the elevation turns about
  if (length(right) > 0) offset = turn(offset, normalize(right), -(wanted - elevation));
  vp.from = vp.at + offset;
}

void pan(LiveView& view, double dx, double dy, int height) {
  Viewpoint& vp = view.viewpoint;
  const Vec3 forward = normalize(vp.at - vp.from);
  const Vec3 right = normalize(cross(forward, vp.up)), up = cross(right, forward);
  const double per_pixel =
      2 * focus(view) * std::tan(vp.angle_deg * std::numbers::pi / 360) / std::max(1, height);
  // The scene follows the pointer: the eye moves the other way.
  const Vec3 move = (right * -dx + up * dy) * per_pixel * (vp.mirrored ? -1.0 : 1.0);
  vp.from += move, vp.at += move;
}

void dolly(LiveView& view, double clicks) {
  Viewpoint& vp = view.viewpoint;
  const double s = std::pow(0.9, clicks);
  vp.from = vp.at + (vp.from - vp.at) * s;
  if (view.focus_distance) *view.focus_distance *= s;
}

void move_plane(LiveView& view, double steps) { view.focus_distance = focus(view) * std::pow(1.05, steps); }

void widen_lenses(LiveView& view, double degrees, double current) {
  view.lens_fov_deg = std::clamp(view.lens_fov_deg.value_or(current) + degrees, 1.0, 120.0);
}

std::string describe(const LiveView& view) {
  const Viewpoint& vp = view.viewpoint;
  auto v = [](const Vec3& p) { return fmt::format("{:.17g},{:.17g},{:.17g}", p.x, p.y, p.z); };
  return fmt::format("eye {} at {} up {} fov {:.17g}{}{}", v(vp.from), v(vp.at), v(vp.up), vp.angle_deg,
                     view.focus_distance ? fmt::format(" focus {:.17g}", *view.focus_distance) : "",
                     view.lens_fov_deg ? fmt::format(" lens-fov {:.17g}", *view.lens_fov_deg) : "");
}

}  // namespace holoray::live
