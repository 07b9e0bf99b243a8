#include "math/node_track.hpp"

#include <algorithm>
#include <cmath>

namespace holoray {

namespace {

// The keys around `t` and the weight of the later one; held outside the keys.
template <class Key>
void bracket(const std::vector<Key>& keys, double t, size_t& a, size_t& b, double& w) {
  const auto later = std::upper_bound(keys.begin(), keys.end(), t, [](double x, const Key& k) { return x < k.first; });
  b = static_cast<size_t>(later - keys.begin());
  if (b == 0) {
    a = b = 0, w = 0;
  } else if (b == keys.size()) {
    a = b = keys.size() - 1, w = 0;
  } else {
    a = b - 1;
    const double span = keys[b].first - keys[a].first;
    w = span > 0 ? (t - keys[a].first) / span : 1;
  }
}

}  // namespace

Affine rotation_of(const Quaternion& q0) {
  const double n = std::sqrt(q0.w * q0.w + q0.x * q0.x + q0.y * q0.y + q0.z * q0.z);
  if (!(n > 0)) return Affine{};
  const double w = q0.w / n, x = q0.x / n, y = q0.y / n, z = q0.z / n;
  Affine r;
  r.m = {1 - 2 * (y * y + z * z), 2 * (x * y - w * z),     2 * (x * z + w * y),
         2 * (x * y + w * z),     1 - 2 * (x * x + z * z), 2 * (y * z - w * x),
         2 * (x * z - w * y),     2 * (y * z + w * x),     1 - 2 * (x * x + y * y)};
  return r;
}

Quaternion slerp(const Quaternion& a, const Quaternion& b_in, double w) {
  Quaternion b = b_in;
  double c = a.w * b.w + a.x * b.x + a.y * b.y + a.z * b.z;
  if (c < 0) {  // q and -q are one rotation: take the shorter arc
    b = {-b.w, -b.x, -b.y, -b.z};
    c = -c;
  }
  double ka = 1 - w, kb = w;
  if (c < 1 - 1e-12) {
    const double angle = std::acos(std::min(c, 1.0)), s = std::sin(angle);
    ka = std::sin((1 - w) * angle) / s;
    kb = std::sin(w * angle) / s;
  }
  return {ka * a.w + kb * b.w, ka * a.x + kb * b.x, ka * a.y + kb * b.y, ka * a.z + kb * b.z};
}

Affine NodeTrack::at(double t) const {
  size_t a, b;
  double w;
  Affine out;
  if (!scale.empty()) {
    bracket(scale, t, a, b, w);
    out = Affine::scale(scale[a].second + (scale[b].second - scale[a].second) * w);
  }
  if (!rotation.empty()) {
    bracket(rotation, t, a, b, w);
    out = rotation_of(a == b ? rotation[a].second : slerp(rotation[a].second, rotation[b].second, w)) * out;
  }
  if (!translation.empty()) {
    bracket(translation, t, a, b, w);
    out = Affine::translate(translation[a].second + (translation[b].second - translation[a].second) * w) * out;
  }
  return out;
}

}  // namespace holoray
