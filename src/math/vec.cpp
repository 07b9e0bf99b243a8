#include "math/vec.hpp"

#include <stdexcept>
#include <utility>

namespace holoray {

Frame Frame::from_normal_up(const Vec3& origin, const Vec3& normal, const Vec3& up) {
  const Vec3 z = normalize(normal);
  if (!(length(normal) > 0) || !is_finite(z)) throw std::invalid_argument("the array normal is zero");
  if (!up_orients(z, up)) throw std::invalid_argument("'up' is zero or parallel to the array normal");
  const Vec3 xr = cross(up, z);
  Frame f;
  f.origin = origin;
  f.z = z;
  f.x = normalize(xr);
  f.y = cross(f.z, f.x);
  return f;
}

}  // namespace holoray
