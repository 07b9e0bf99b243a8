#include "math/transform.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace holoray {

Affine operator*(const Affine& a, const Affine& b) {
  Affine r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      r.m[3 * i + j] = a.m[3 * i] * b.m[j] + a.m[3 * i + 1] * b.m[3 + j] + a.m[3 * i + 2] * b.m[6 + j];
  r.translation = a.point(b.translation);
  return r;
}

Affine Affine::inverse() const {
  const auto& a = m;
  const double c00 = a[4] * a[8] - a[5] * a[7], c01 = a[5] * a[6] - a[3] * a[8], c02 = a[3] * a[7] - a[4] * a[6];
  const double det = a[0] * c00 + a[1] * c01 + a[2] * c02;
  if (!(std::fabs(det) > 1e-300) || !std::isfinite(det))
    throw std::invalid_argument(fmt::format("the transform is singular (determinant {})", det));
  const double k = 1.0 / det;
  Affine r;
  r.m = {c00 * k, (a[2] * a[7] - a[1] * a[8]) * k, (a[1] * a[5] - a[2] * a[4]) * k,
         c01 * k, (a[0] * a[8] - a[2] * a[6]) * k, (a[2] * a[3] - a[0] * a[5]) * k,
         c02 * k, (a[1] * a[6] - a[0] * a[7]) * k, (a[0] * a[4] - a[1] * a[3]) * k};
  r.translation = -r.dir(translation);
  return r;
}

Vec3 Affine::normal(const Vec3& n) const {
  // The inverse transpose is the cofactor matrix over the determinant; the
  // determinant's magnitude drops out on normalising, its sign must not.
  const auto& a = m;
  const double c[9] = {a[4] * a[8] - a[5] * a[7], a[5] * a[6] - a[3] * a[8], a[3] * a[7] - a[4] * a[6],
                       a[2] * a[7] - a[1] * a[8], a[0] * a[8] - a[2] * a[6], a[1] * a[6] - a[0] * a[7],
                       a[1] * a[5] - a[2] * a[4], a[2] * a[3] - a[0] * a[5], a[0] * a[4] - a[1] * a[3]};
  const double det = a[0] * c[0] + a[1] * c[1] + a[2] * c[2];
  const Vec3 r{c[0] * n.x + c[1] * n.y + c[2] * n.z, c[3] * n.x + c[4] * n.y + c[5] * n.z,
               c[6] * n.x + c[7] * n.y + c[8] * n.z};
  return normalize(det < 0 ? -r : r);
}

bool Affine::is_identity() const { return m == Affine{}.m && translation == Vec3{}; }

Affine Affine::translate(const Vec3& t) {
  Affine r;
  r.translation = t;
  return r;
}

Affine Affine::scale(const Vec3& s) {
  Affine r;
  r.m = {s.x, 0, 0, 0, s.y, 0, 0, 0, s.z};
  return r;
}

Affine Affine::rotate_axis(int axis, double degrees) {
  const double a = degrees * std::numbers::pi / 180.0;
  // Exact values at multiples of 90 degrees keep rotated scenes bit-stable.
  double c = std::cos(a), s = std::sin(a);
  if (std::fmod(degrees, 90.0) == 0) {
    const long q = ((std::lround(degrees / 90.0) % 4) + 4) % 4;
    c = q == 0 ? 1 : (q == 2 ? -1 : 0);
    s = q == 1 ? 1 : (q == 3 ? -1 : 0);
  }
  Affine r;
  switch (axis) {
    case 0: r.m = {1, 0, 0, 0, c, -s, 0, s, c}; break;
    case 1: r.m = {c, 0, s, 0, 1, 0, -s, 0, c}; break;
    default: r.m = {c, -s, 0, s, c, 0, 0, 0, 1}; break;
  }
  return r;
}

Affine TransformKey::matrix() const {
  return Affine::translate(translate) * Affine::rotate_axis(2, rotate_deg.z) * Affine::rotate_axis(1, rotate_deg.y) *
         Affine::rotate_axis(0, rotate_deg.x) * Affine::scale(scale);
}

double key_weight(double frame, double a, double b, Interpolation mode) {
  if (!(b > a)) return 0;
  const double w = std::clamp((frame - a) / (b - a), 0.0, 1.0);
  return mode == Interpolation::smooth ? w * w * (3 - 2 * w) : w;
}

TransformKey TransformTrack::at(double frame) const {
  if (keys.empty()) {
    TransformKey k;
    k.frame = frame;
    return k;
  }
  if (frame <= keys.front().frame) return keys.front();
  if (frame >= keys.back().frame) return keys.back();
  const auto hi = std::upper_bound(keys.begin(), keys.end(), frame,
                                   [](double f, const TransformKey& k) { return f < k.frame; });
  const TransformKey& b = *hi;
  const TransformKey& a = *(hi - 1);
  const double w = key_weight(frame, a.frame, b.frame, interpolation);
  auto mix = [w](const Vec3& x, const Vec3& y) { return x + (y - x) * w; };
  return {frame, mix(a.translate, b.translate), mix(a.rotate_deg, b.rotate_deg), mix(a.scale, b.scale)};
}

bool TransformTrack::is_static() const {
  return std::all_of(keys.begin(), keys.end(), [](const TransformKey& k) { return k.matrix().is_identity(); });
}

}  // namespace holoray
