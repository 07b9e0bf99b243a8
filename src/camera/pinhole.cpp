#include "camera/pinhole.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace holoray {

PinholeCamera::PinholeCamera(const PinholeDesc& desc) : desc_(desc) {
  if (!is_finite(desc.from) || !is_finite(desc.at) || !is_finite(desc.up))
    throw std::invalid_argument("the pinhole camera's from, at and up must be finite");
  if (length(desc.at - desc.from) == 0)
    throw std::invalid_argument(fmt::format("the pinhole camera looks nowhere: from and at are the same point ({}, {}, {})",
                                            desc.from.x, desc.from.y, desc.from.z));
  if (!std::isfinite(desc.shift_x) || !std::isfinite(desc.shift_y))
    throw std::invalid_argument(fmt::format("the view's window shift must be finite, got {}, {}", desc.shift_x, desc.shift_y));
  if (!(desc.ortho_height >= 0) || !std::isfinite(desc.ortho_height))
    throw std::invalid_argument(fmt::format("the orthographic view's height must be positive, got {}", desc.ortho_height));
  if (!(desc.clip_near >= 0 && desc.clip_far > desc.clip_near) || std::isnan(desc.clip_far))
    throw std::invalid_argument(fmt::format("the clipping range must run from 0 or more to farther, got {} to {}",
                                            desc.clip_near, desc.clip_far));
  if (desc.ortho_height == 0 && !(desc.fov_deg > 0 && desc.fov_deg < 180))
    throw std::invalid_argument(fmt::format("the field of view must be between 0 and 180 degrees, got {}", desc.fov_deg));
  if (desc.width < 1 || desc.height < 1 || static_cast<int64_t>(desc.width) * desc.height > (int64_t{1} << 30))
    throw std::invalid_argument(
        fmt::format("the image must be 1x1 to 2^30 pixels, got {}x{}", desc.width, desc.height));
  // z = -d: x = normalize(up x z) = normalize(d x up) = r, y = z x x = r x d = u.
  try {
    frame_ = Frame::from_normal_up(desc.from, desc.from - desc.at, desc.up);
  } catch (const std::invalid_argument&) {
    throw std::invalid_argument(fmt::format("the up direction ({}, {}, {}) is parallel to the view direction",
                                            desc.up.x, desc.up.y, desc.up.z));
  }
  if (desc.mirrored) frame_.x = -frame_.x;
  pixel_ = desc.ortho_height > 0 ? desc.ortho_height / desc.height
                                 : 2 * std::tan(desc.fov_deg * std::numbers::pi / 360) / desc.height;
  lines_ = {.width = desc.width,
            .height = desc.height,
            .ortho = desc.ortho_height > 0 ? 1 : 0,
            .pixel = pixel_,
            .sample_u = desc.sample_u,
            .sample_v = desc.sample_v,
            .shift_x = desc.shift_x,
            .shift_y = desc.shift_y};
}

PixelLine PinholeCamera::line(int i, int j, double u, double v) const {
  PixelLine l;
  camera_lines::hr_pinhole_line(lines_, frame_, i, j, u, v, l.origin, l.dir);
  return l;
}

bool PinholeCamera::project(const Vec3& p_world, PanelHit& out) const {
  const Vec3 q = frame_.to_local_point(p_world);
  if (!(q.z < 0)) return false;  // behind or beside the eye (plane)
  const bool ortho = desc_.ortho_height > 0;
  const double px = ortho ? q.x : q.x / -q.z, py = ortho ? q.y : q.y / -q.z;
  const double fi = (px - desc_.shift_x) / pixel_ + 0.5 * desc_.width - (desc_.sample_u - 0.5);
  const double fj = 0.5 * desc_.height - (py - desc_.shift_y) / pixel_ - (desc_.sample_v - 0.5);
  if (!(fi >= 0 && fi < desc_.width && fj >= 0 && fj < desc_.height)) return false;
  const int i = static_cast<int>(fi), j = static_cast<int>(fj);
  out = {i, j, fi - i, fj - j, ortho ? -q.z : length(q)};
  return true;
}

void PinholeCamera::project(const Vec3& p_world, std::vector<PanelHit>& out) const {
  out.clear();
  PanelHit h;
  if (project(p_world, h)) out.push_back(h);
}

}  // namespace holoray
