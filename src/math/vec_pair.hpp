// holoray/math: two Vec3 lanes in SSE2 registers (double, lane 0 low), with
// vec.hpp's operations in vec.hpp's order: each lane gets the scalar
// function's bits (x86-64's baseline has no fused multiply-add to change
// one). What the packets' eye rays are generated and refined with, two
// lanes per instruction.
#pragma once

#include <emmintrin.h>

#include "math/vec.hpp"

namespace holoray {

struct Vec3Pair {
  __m128d x, y, z;
};

/// Lanes a (low) and b.
inline Vec3Pair pair_of(const Vec3& a, const Vec3& b) {
  return {_mm_set_pd(b.x, a.x), _mm_set_pd(b.y, a.y), _mm_set_pd(b.z, a.z)};
}
/// Lane l (0 or 1).
inline double lane(__m128d v, int l) { return _mm_cvtsd_f64(l == 0 ? v : _mm_unpackhi_pd(v, v)); }
inline Vec3 lane(const Vec3Pair& v, int l) { return {lane(v.x, l), lane(v.y, l), lane(v.z, l)}; }

inline Vec3Pair operator-(const Vec3Pair& a, const Vec3Pair& b) {
  return {_mm_sub_pd(a.x, b.x), _mm_sub_pd(a.y, b.y), _mm_sub_pd(a.z, b.z)};
}
/// o + d * t, vec.hpp's `o + d * t`.
inline Vec3Pair along(const Vec3Pair& o, const Vec3Pair& d, __m128d t) {
  return {_mm_add_pd(o.x, _mm_mul_pd(d.x, t)), _mm_add_pd(o.y, _mm_mul_pd(d.y, t)), _mm_add_pd(o.z, _mm_mul_pd(d.z, t))};
}
inline __m128d dot(const Vec3Pair& a, const Vec3Pair& b) {
  return _mm_add_pd(_mm_add_pd(_mm_mul_pd(a.x, b.x), _mm_mul_pd(a.y, b.y)), _mm_mul_pd(a.z, b.z));
}
inline Vec3Pair cross(const Vec3Pair& a, const Vec3Pair& b) {
  return {_mm_sub_pd(_mm_mul_pd(a.y, b.z), _mm_mul_pd(a.z, b.y)), _mm_sub_pd(_mm_mul_pd(a.z, b.x), _mm_mul_pd(a.x, b.z)),
          _mm_sub_pd(_mm_mul_pd(a.x, b.y), _mm_mul_pd(a.y, b.x))};
}
/// mask ? a : b, lane by lane.
inline __m128d select(__m128d mask, __m128d a, __m128d b) {
  return _mm_or_pd(_mm_and_pd(mask, a), _mm_andnot_pd(mask, b));
}
/// normalize(): a * (1 / |a|) where |a| > 0, else a.
inline Vec3Pair normalize(const Vec3Pair& a) {
  const __m128d len = _mm_sqrt_pd(dot(a, a));
  const __m128d inv = _mm_div_pd(_mm_set1_pd(1.0), len), positive = _mm_cmpgt_pd(len, _mm_setzero_pd());
  return {select(positive, _mm_mul_pd(a.x, inv), a.x), select(positive, _mm_mul_pd(a.y, inv), a.y),
          select(positive, _mm_mul_pd(a.z, inv), a.z)};
}

/// Frame::to_world_dir() of both lanes: (X d.x + Y d.y) + Z d.z.
inline Vec3Pair to_world_dir(const Frame& f, const Vec3Pair& d) {
  auto row = [&](double ax, double ay, double az) {
    return _mm_add_pd(_mm_add_pd(_mm_mul_pd(_mm_set1_pd(ax), d.x), _mm_mul_pd(_mm_set1_pd(ay), d.y)),
                      _mm_mul_pd(_mm_set1_pd(az), d.z));
  };
  return {row(f.x.x, f.y.x, f.z.x), row(f.x.y, f.y.y, f.z.y), row(f.x.z, f.y.z, f.z.z)};
}

}  // namespace holoray
