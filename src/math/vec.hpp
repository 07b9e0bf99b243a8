// holoray/math: 3-vectors and orthonormal frames in double precision.
//
// The camera and scene work in double so that ray generation and forward
// projection are inverses to ~1e-12 (camera-model.md, property 2); the
// conversion to float happens only at the Embree boundary (accel/).
#pragma once

#include <cmath>
#include <utility>

namespace holoray {

/// A point or direction in 3-space. Frame is given by the variable name
/// (`p_world`, `d_array`), never by the type.
struct Vec3 {
  double x = 0, y = 0, z = 0;

  constexpr Vec3() = default;
  constexpr Vec3(double x_, double y_, double z_) : x(x_), y(y_), z(z_) {}

  constexpr double operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
  constexpr Vec3 operator-() const { return {-x, -y, -z}; }
  constexpr Vec3& operator+=(const Vec3& o) { x += o.x; y += o.y; z += o.z; return *this; }
  constexpr Vec3& operator-=(const Vec3& o) { x -= o.x; y -= o.y; z -= o.z; return *this; }
  constexpr Vec3& operator*=(double s) { x *= s; y *= s; z *= s; return *this; }
  friend constexpr bool operator==(const Vec3&, const Vec3&) = default;
};

constexpr Vec3 operator+(Vec3 a, const Vec3& b) { return a += b; }
constexpr Vec3 operator-(Vec3 a, const Vec3& b) { return a -= b; }
constexpr Vec3 operator*(Vec3 a, double s) { return a *= s; }
constexpr Vec3 operator*(double s, Vec3 a) { return a *= s; }
constexpr Vec3 operator/(Vec3 a, double s) { return a *= (1.0 / s); }
/// Component-wise product (colour modulation).
constexpr Vec3 mul(const Vec3& a, const Vec3& b) { return {a.x * b.x, a.y * b.y, a.z * b.z}; }

constexpr double dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
constexpr Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double length(const Vec3& a) { return std::sqrt(dot(a, a)); }
/// Unit vector along `a`; the zero vector stays zero (callers check degeneracy first).
/// Always inlined: it sits in every per-ray path, and link-time optimisation
/// otherwise left it an out-of-line call in some of them (5.8 % of teapot's
/// cycles spent calling it after an unrelated change to the cone code).
[[gnu::always_inline]] inline Vec3 normalize(const Vec3& a) {
  const double l = length(a);
  return l > 0 ? a / l : a;
}
inline bool is_finite(const Vec3& a) {
  return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z);
}
inline Vec3 min(const Vec3& a, const Vec3& b) {
  return {std::fmin(a.x, b.x), std::fmin(a.y, b.y), std::fmin(a.z, b.z)};
}
inline Vec3 max(const Vec3& a, const Vec3& b) {
  return {std::fmax(a.x, b.x), std::fmax(a.y, b.y), std::fmax(a.z, b.z)};
}

/// Axis-aligned box; empty when lo > hi (the default).
struct Bounds3 {
  Vec3 lo{INFINITY, INFINITY, INFINITY};
  Vec3 hi{-INFINITY, -INFINITY, -INFINITY};

  void extend(const Vec3& p) { lo = min(lo, p); hi = max(hi, p); }
  void extend(const Bounds3& b) { lo = min(lo, b.lo); hi = max(hi, b.hi); }
  bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
  Vec3 centre() const { return (lo + hi) * 0.5; }
  Vec3 diagonal() const { return hi - lo; }
};

/// Parameter interval [t0, t1] where the line o + t*d crosses `b` (slab test);
/// returns false when it misses. d need not be unit; components may be zero.
// Inline: every primary ray is clipped with it (issue 4).
inline bool intersect_line_box(const Vec3& o, const Vec3& d, const Bounds3& b, double& t0, double& t1) {
  t0 = -INFINITY;
  t1 = INFINITY;
  for (int a = 0; a < 3; ++a) {
    const double lo = b.lo[a], hi = b.hi[a], oa = o[a], da = d[a];
    if (da == 0.0) {  // rare (axis-aligned lines): keeps 0 * inf out
      if (oa < lo || oa > hi) return false;
      continue;
    }
    // One division per axis, and min / max instead of a swap: the branch on
    // the sign of d mispredicts from pixel to pixel. Not std::fmin / fmax:
    // no NaN can occur here, and those are library calls.
    const double inv = 1.0 / da;
    const double ta = (lo - oa) * inv, tb = (hi - oa) * inv;
    const double near = ta < tb ? ta : tb, far = ta < tb ? tb : ta;
    t0 = near > t0 ? near : t0;
    t1 = far < t1 ? far : t1;
  }
  return t0 <= t1;
}

/// Right-handed orthonormal frame: `x` right, `y` up, `z` the normal
/// (camera-model.md, "Frame"). Maps between world and frame-local coordinates.
/// Whether `up` orients a view along `dir` (or a frame with normal `dir`):
/// neither is zero and they are more than ~1e-9 rad from parallel, where a
/// frame made from them loses its precision. Every reader and the API check
/// viewpoints with it, so what one format accepts every format accepts.
inline bool up_orients(const Vec3& dir, const Vec3& up) {
  return length(cross(dir, up)) > 1e-9 * length(dir) * length(up);
}

struct Frame {
  Vec3 origin;
  Vec3 x{1, 0, 0}, y{0, 1, 0}, z{0, 0, 1};

  /// Builds the frame from a normal and an "up" hint that need not be
  /// orthogonal to it: x = normalize(up x z), y = z x x. Throws
  /// std::invalid_argument when the normal is zero or up is parallel to it.
  static Frame from_normal_up(const Vec3& origin, const Vec3& normal, const Vec3& up);

  Vec3 to_world_point(const Vec3& p_local) const { return origin + x * p_local.x + y * p_local.y + z * p_local.z; }
  Vec3 to_world_dir(const Vec3& d_local) const { return x * d_local.x + y * d_local.y + z * d_local.z; }
  Vec3 to_local_point(const Vec3& p_world) const {
    const Vec3 r = p_world - origin;
    return {dot(r, x), dot(r, y), dot(r, z)};
  }
  Vec3 to_local_dir(const Vec3& d_world) const { return {dot(d_world, x), dot(d_world, y), dot(d_world, z)}; }
  friend bool operator==(const Frame&, const Frame&) = default;
};

}  // namespace holoray
