// holoray/math: affine transforms and keyframed rigid motion for animation
// (paper §3: scene transformations between frames).
#pragma once

#include <array>
#include <vector>

#include "math/vec.hpp"

namespace holoray {

/// p' = M p + translation (3x3 matrix row-major, double). Maps an object's
/// local ("object space") coordinates to the world.
struct Affine {
  std::array<double, 9> m{1, 0, 0, 0, 1, 0, 0, 0, 1};
  Vec3 translation;
  friend bool operator==(const Affine&, const Affine&) = default;

  Vec3 point(const Vec3& p) const { return dir(p) + translation; }
  Vec3 dir(const Vec3& d) const {
    return {m[0] * d.x + m[1] * d.y + m[2] * d.z, m[3] * d.x + m[4] * d.y + m[5] * d.z,
            m[6] * d.x + m[7] * d.y + m[8] * d.z};
  }
  /// Normals map with the inverse transpose; the result is unit.
  Vec3 normal(const Vec3& n) const;
  bool is_identity() const;
  /// Throws std::invalid_argument when the matrix is singular (a zero scale).
  Affine inverse() const;

  static Affine translate(const Vec3& t);
  static Affine scale(const Vec3& s);
  /// Rotation by `degrees` about the x (0), y (1) or z (2) axis, right-handed.
  static Affine rotate_axis(int axis, double degrees);
};

/// a*b: applies b first, then a.
Affine operator*(const Affine& a, const Affine& b);

/// How values between two keys are found: straight lines, or a smoothstep
/// ease (zero speed at every key: starts and stops without a jerk).
enum class Interpolation { linear, smooth };

/// One key of a rigid (plus scale) transform: scale, then rotate about x, y
/// and z in that order (degrees), then translate. Frame numbers are integers
/// in the shot, stored as double so tracks can be sampled between frames.
struct TransformKey {
  double frame = 0;
  Vec3 translate;
  Vec3 rotate_deg;
  Vec3 scale{1, 1, 1};

  Affine matrix() const;
};

/// A keyframed transform. Before the first key and after the last it holds
/// that key; with no keys it is the identity. Keys must be sorted by frame
/// with no repeats (the shot reader checks).
struct TransformTrack {
  std::vector<TransformKey> keys;
  Interpolation interpolation = Interpolation::linear;

  /// The interpolated key at `frame` (components interpolated one by one).
  TransformKey at(double frame) const;
  Affine matrix(double frame) const { return at(frame).matrix(); }
  /// True when every key is the identity (the object never moves).
  bool is_static() const;
};

/// The fraction of the way from key a to key b at `frame`, eased per `mode`.
double key_weight(double frame, double a, double b, Interpolation mode);

}  // namespace holoray
