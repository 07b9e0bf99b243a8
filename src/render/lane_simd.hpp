// holoray/render (internal): what the float shading batches (light_batch,
// gltf_batch) share: SSE loads, selects and dot products over a packet's
// lane arrays (16-byte aligned, four lanes at a time), and four lanes'
// shadow rays written into Embree's 16-wide layout.
#pragma once

#include <immintrin.h>

#include "accel/accel_scene.hpp"

namespace holoray::lanes {

static_assert(kPacketSize % 4 == 0);

inline __m128 load(const float* p, int k) { return _mm_load_ps(p + k); }
/// mask ? a : b, lane by lane.
inline __m128 select(__m128 mask, __m128 a, __m128 b) { return _mm_or_ps(_mm_and_ps(mask, a), _mm_andnot_ps(mask, b)); }
inline __m128 dot3(__m128 ax, __m128 ay, __m128 az, __m128 bx, __m128 by, __m128 bz) {
  return _mm_add_ps(_mm_add_ps(_mm_mul_ps(ax, bx), _mm_mul_ps(ay, by)), _mm_mul_ps(az, bz));
}

/// Lanes k..k+3 of `s`: from (ox, oy, oz) along unit (ux, uy, uz) to tfar,
/// tnear 0, traced where `valid` (all bits set) and ignored elsewhere.
/// Returns how many are traced.
[[gnu::always_inline]] inline int store_shadow_rays(ShadowPacket& s, int k, __m128 ox, __m128 oy, __m128 oz, __m128 ux,
                                                    __m128 uy, __m128 uz, __m128 tfar, __m128 valid) {
  const __m128 zero = _mm_setzero_ps();
  _mm_store_ps(s.org_x + k, ox), _mm_store_ps(s.org_y + k, oy), _mm_store_ps(s.org_z + k, oz);
  _mm_store_ps(s.tnear + k, zero), _mm_store_ps(s.time + k, zero);
  _mm_store_ps(s.dir_x + k, ux), _mm_store_ps(s.dir_y + k, uy), _mm_store_ps(s.dir_z + k, uz);
  _mm_storeu_ps(s.tfar + k, tfar);
  _mm_storeu_si128(reinterpret_cast<__m128i*>(s.mask + k), _mm_set1_epi32(-1));
  _mm_storeu_si128(reinterpret_cast<__m128i*>(s.id + k), _mm_add_epi32(_mm_setr_epi32(0, 1, 2, 3), _mm_set1_epi32(k)));
  _mm_storeu_si128(reinterpret_cast<__m128i*>(s.flags + k), _mm_setzero_si128());
  _mm_store_si128(reinterpret_cast<__m128i*>(s.valid + k), _mm_castps_si128(valid));
  // Bits set in a 4-bit mask (no POPCNT in the baseline instruction set).
  return static_cast<int>((0x4332322132212110ull >> (4 * _mm_movemask_ps(valid))) & 0xf);
}

}  // namespace holoray::lanes
