// holoray/temporal: which elemental images can see what moved. A lens's
// lines all pass through its centre within its field of view; whatever
// moved is bounded by spheres. A lens none of whose lines (either way along
// them) meets a sphere sees exactly what it saw before.
#pragma once

#include <cmath>
#include <vector>

#include "camera/lens_array.hpp"

namespace holoray {

/// A sphere bounding something that moved (world centre and radius).
struct BoundingSphere {
  Vec3 centre;
  double radius = 0;
};

/// The half-angle of the double cone of a lens's lines about the array
/// normal: the corners of a square elemental image, pitch / sqrt(2) off axis.
inline double lens_half_angle(const LensArrayDesc& d) { return std::atan(d.pitch / (std::sqrt(2.0) * d.gap)); }

/// Whether a line of `lens` can meet one of `spheres`: the double cone of
/// its lines misses a sphere when the angle from the axis to the sphere's
/// centre, less the sphere's angular radius, exceeds `half_angle`.
inline bool lens_reaches(const LensArray& camera, LensIndex lens, const std::vector<BoundingSphere>& spheres,
                         double half_angle) {
  const Frame& f = camera.desc().frame;
  const Vec3 c = f.to_world_point(camera.lens_centre_local(lens));
  for (const BoundingSphere& s : spheres) {
    const Vec3 v = s.centre - c;
    const double dist = length(v);
    if (dist <= s.radius) return true;
    const double off_axis = std::acos(std::fmin(1.0, std::fabs(dot(v, f.z)) / dist));
    if (off_axis - std::asin(s.radius / dist) <= half_angle) return true;
  }
  return false;
}

}  // namespace holoray
