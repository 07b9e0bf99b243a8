#include "temporal/keyframe_schedule.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "render/render_scene.hpp"

namespace holoray {

KeyframePlanner::KeyframePlanner(const ShotFrames& shot) : shot_(shot) {
  std::optional<Vec3> eye;
  for (const SceneDesc& d : shot.scenes())
    if (d.viewpoint) {
      eye = d.viewpoint->from;
      break;
    }
  for (const SceneDesc& d : shot.scenes()) {
    std::vector<Vec3>& p = probes_.emplace_back();
    const Bounds3 b = finite_bounds(d, eye);
    if (b.empty()) continue;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        for (int k = 0; k < 3; ++k)
          p.push_back({b.lo.x + (b.hi.x - b.lo.x) * i / 2, b.lo.y + (b.hi.y - b.lo.y) * j / 2,
                       b.lo.z + (b.hi.z - b.lo.z) * k / 2});
  }
}

KeyframePlanner::View KeyframePlanner::view_at(int frame) const {
  View v;
  const std::vector<Affine> xf = shot_.transforms(frame);
  for (size_t e = 0; e < probes_.size() && e < xf.size(); ++e)
    for (const Vec3& p : probes_[e]) v.probes.push_back(xf[e].point(p));
  const LensArrayDesc cam = shot_.camera(frame);
  const double hw = 0.5 * cam.lenses_x * cam.pitch, hh = 0.5 * cam.lenses_y * cam.pitch;
  for (int i = -1; i <= 1; ++i)
    for (int j = -1; j <= 1; ++j) v.lenses.push_back(cam.frame.to_world_point({i * hw, j * hh, 0}));
  v.pitch = cam.pitch;
  v.pixel_angle = cam.pitch / cam.pixels_per_lens / cam.gap;
  return v;
}

double KeyframePlanner::image_motion(int a, int b) const { return motion(view_at(a), view_at(b)); }

double KeyframePlanner::motion(const View& va, const View& vb) {
  double worst = 0;
  for (size_t l = 0; l < va.lenses.size(); ++l)
    for (size_t p = 0; p < va.probes.size(); ++p) {
      const Vec3 da = va.probes[p] - va.lenses[l], db = vb.probes[p] - vb.lenses[l];
      const double la = length(da), lb = length(db);
      if (!(la > va.pitch && lb > vb.pitch)) continue;
      // atan2 of |cross| and dot: accurate at small angles, where acos is not.
      const double angle = std::atan2(length(cross(da, db)), dot(da, db));
      worst = std::fmax(worst, angle / std::fmin(va.pixel_angle, vb.pixel_angle));
    }
  return worst;
}

std::vector<int> KeyframePlanner::keyframes(double max_pixels, int max_interval) const {
  if (!(max_pixels > 0))
    throw std::invalid_argument(fmt::format("the keyframe motion must be a positive number of pixels, got {}", max_pixels));
  if (max_interval < 1)
    throw std::invalid_argument(fmt::format("the longest keyframe interval must be at least 1, got {}", max_interval));
  const int frames = shot_.frame_count();
  std::vector<int> keys{0};
  int k = 0;
  while (k < frames - 1) {
    const View from = view_at(k);  // once per keyframe, not per candidate
    int f = k + 1;
    while (f < frames - 1 && f + 1 - k <= max_interval && motion(from, view_at(f + 1)) <= max_pixels) ++f;
    keys.push_back(f);
    k = f;
  }
  return keys;
}

}  // namespace holoray
