#include "math/vec.hpp"

#include <stdexcept>
#include <utility>

namespace holoray {

bool intersect_line_box(const Vec3& o, const Vec3& d, const Bounds3& b, double& t0, double& t1) {
  t0 = -INFINITY;
  t1 = INFINITY;
  for (int a = 0; a < 3; ++a) {
    const double lo = b.lo[a], hi = b.hi[a], oa = o[a], da = d[a];
    if (da == 0.0) {
      if (oa < lo || oa > hi) return false;
      continue;
    }
    double ta = (lo - oa) / da, tb = (hi - oa) / da;
    if (ta > tb) std::swap(ta, tb);
    t0 = std::fmax(t0, ta);
    t1 = std::fmin(t1, tb);
    if (t0 > t1) return false;
  }
  return true;
}

Frame Frame::from_normal_up(const Vec3& origin, const Vec3& normal, const Vec3& up) {
  const Vec3 z = normalize(normal);
  if (!(length(normal) > 0) || !is_finite(z)) throw std::invalid_argument("the array normal is zero");
  const Vec3 xr = cross(up, z);
  // Parallel within ~1e-9 rad is as unusable as exactly parallel.
  if (!(length(xr) > 1e-9 * length(up))) throw std::invalid_argument("'up' is zero or parallel to the array normal");
  Frame f;
  f.origin = origin;
  f.z = z;
  f.x = normalize(xr);
  f.y = cross(f.z, f.x);
  return f;
}

}  // namespace holoray
