#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "scene/scene_desc.hpp"

namespace holoray {

namespace {
// The factor from the `fov_axis` side to the vertical one of a w x h image.
double vertical_share(Viewpoint::FovAxis axis, int width, int height) {
  const double aspect = static_cast<double>(width) / height;
  switch (axis) {
    case Viewpoint::FovAxis::vertical: return 1;
    case Viewpoint::FovAxis::horizontal: return 1 / aspect;
    case Viewpoint::FovAxis::larger: return 1 / std::max(aspect, 1.0);
  }
  return 1;
}
}  // namespace

double Viewpoint::vertical_angle_deg(int width, int height) const {
  const double half = angle_deg * std::numbers::pi / 360;
  return 360 / std::numbers::pi * std::atan(std::tan(half) * vertical_share(fov_axis, width, height));
}

double Viewpoint::vertical_ortho_size(int width, int height) const {
  return ortho_size * vertical_share(fov_axis, width, height);
}

Viewpoint Viewpoint::focused_at(double distance) const {
  if (!(distance > 0) || !std::isfinite(distance))
    throw std::invalid_argument(fmt::format("focus distance: expected a positive distance, got {}", distance));
  Viewpoint v = *this;
  v.at = from + normalize(at - from) * distance;
  v.focus = Focus::option;
  return v;
}

}  // namespace holoray
