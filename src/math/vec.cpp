#include "math/vec.hpp"

#include <stdexcept>
#include <utility>

namespace holoray {

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
