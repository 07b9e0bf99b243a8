// holoray/math: a node's animation as glTF 2.0 defines it (spec §3.11,
// "Animations"): translation, rotation and scale each keyed on its own
// times, interpolated linearly (rotation by slerp of unit quaternions),
// held before the first key and after the last. What assimp's aiNodeAnim
// carries for glTF, COLLADA and FBX node animation.
#pragma once

#include <utility>
#include <vector>

#include "math/transform.hpp"

namespace holoray {

/// A rotation as a unit quaternion w + xi + yj + zk.
struct Quaternion {
  double w = 1, x = 0, y = 0, z = 0;
};

/// The rotation matrix of `q` (normalised first; a zero quaternion is the
/// identity).
Affine rotation_of(const Quaternion& q);

/// Spherical linear interpolation from a (w = 0) to b (w = 1) along the
/// shorter arc, as glTF's LINEAR rotation sampler.
Quaternion slerp(const Quaternion& a, const Quaternion& b, double w);

/// One node's keys, times in seconds, each list sorted by time. An empty
/// list is the identity for that component.
struct NodeTrack {
  std::vector<std::pair<double, Vec3>> translation, scale;
  std::vector<std::pair<double, Quaternion>> rotation;

  /// The node's frame -> its parent's at `seconds`: T * R * S (scale first).
  Affine at(double seconds) const;
};

}  // namespace holoray
