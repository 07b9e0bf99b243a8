#include "render/light_batch.hpp"

#include "render/lane_simd.hpp"

// glibc's vector powf (libmvec, the SSE ABI: four lanes), the function GCC
// calls for powf in a vectorised loop.
extern "C" __m128 _ZGVbN4vv_powf(__m128 x, __m128 y);

namespace holoray {

void NffLanes::set(int k, const Vec3& p, const Vec3& n, const Vec3& above, const Vec3& view, const Vec3& kd_colour,
                   double ks_, double shine_) {
  px[k] = static_cast<float>(p.x), py[k] = static_cast<float>(p.y), pz[k] = static_cast<float>(p.z);
  nx[k] = static_cast<float>(n.x), ny[k] = static_cast<float>(n.y), nz[k] = static_cast<float>(n.z);
  ox[k] = static_cast<float>(above.x), oy[k] = static_cast<float>(above.y), oz[k] = static_cast<float>(above.z);
  vx[k] = static_cast<float>(view.x), vy[k] = static_cast<float>(view.y), vz[k] = static_cast<float>(view.z);
  n_dot_v[k] = static_cast<float>(dot(n, view));
  dr[k] = static_cast<float>(kd_colour.x), dg[k] = static_cast<float>(kd_colour.y), db[k] = static_cast<float>(kd_colour.z);
  ks[k] = static_cast<float>(ks_), shine[k] = static_cast<float>(shine_);
  hit[k] = -1;
}

void NffLanes::clear(int k) {
  px[k] = py[k] = pz[k] = nx[k] = ny[k] = nz[k] = ox[k] = oy[k] = oz[k] = 0;
  vx[k] = vy[k] = vz[k] = n_dot_v[k] = dr[k] = dg[k] = db[k] = ks[k] = shine[k] = 0;
  hit[k] = 0;
}

using lanes::load;
using lanes::select;

int nff_shadow_rays(const NffLanes& g, const Vec3& light, double eps, ShadowPacket& s, NffLightRays& out) {
  const __m128 lx = _mm_set1_ps(static_cast<float>(light.x)), ly = _mm_set1_ps(static_cast<float>(light.y)),
               lz = _mm_set1_ps(static_cast<float>(light.z)), e = _mm_set1_ps(static_cast<float>(eps));
  const __m128 zero = _mm_setzero_ps();
  int cast = 0;
  for (int k = 0; k < kPacketSize; k += 4) {
    const __m128 dx = _mm_sub_ps(lx, load(g.px, k)), dy = _mm_sub_ps(ly, load(g.py, k)), dz = _mm_sub_ps(lz, load(g.pz, k));
    const __m128 dist = _mm_sqrt_ps(_mm_add_ps(_mm_add_ps(_mm_mul_ps(dx, dx), _mm_mul_ps(dy, dy)), _mm_mul_ps(dz, dz)));
    const __m128 inv = _mm_div_ps(_mm_set1_ps(1.0f), dist);
    const __m128 ux = _mm_mul_ps(dx, inv), uy = _mm_mul_ps(dy, inv), uz = _mm_mul_ps(dz, inv);
    const __m128 ndl = _mm_add_ps(_mm_add_ps(_mm_mul_ps(load(g.nx, k), ux), _mm_mul_ps(load(g.ny, k), uy)),
                                  _mm_mul_ps(load(g.nz, k), uz));
    // The light off the surface and in front of it (a NaN N.L casts nothing).
    const __m128 valid = _mm_and_ps(_mm_castsi128_ps(_mm_load_si128(reinterpret_cast<const __m128i*>(g.hit + k))),
                                    _mm_and_ps(_mm_cmpgt_ps(dist, e), _mm_cmpgt_ps(ndl, zero)));
    _mm_store_ps(out.ux + k, ux), _mm_store_ps(out.uy + k, uy), _mm_store_ps(out.uz + k, uz);
    _mm_store_ps(out.n_dot_l + k, ndl);
    cast += lanes::store_shadow_rays(s, k, load(g.ox, k), load(g.oy, k), load(g.oz, k), ux, uy, uz, _mm_sub_ps(dist, e),
                                     valid);
  }
  return cast;
}

void add_nff_light(const NffLanes& g, const NffLightRays& r, const bool seen[kPacketSize], const Vec3& intensity,
                   Vec3 colours[kPacketSize]) {
  const __m128 zero = _mm_setzero_ps(), two = _mm_set1_ps(2.0f);
  const float ir = static_cast<float>(intensity.x), ig = static_cast<float>(intensity.y),
              ib = static_cast<float>(intensity.z);
  for (int k = 0; k < kPacketSize; k += 4) {
    if (!(seen[k] | seen[k + 1] | seen[k + 2] | seen[k + 3])) continue;
    const __m128 ndl = load(r.n_dot_l, k);
    // R.V with R = L reflected about N: 2 (N.L)(N.V) - L.V.
    const __m128 l_dot_v = _mm_add_ps(_mm_add_ps(_mm_mul_ps(load(r.ux, k), load(g.vx, k)), _mm_mul_ps(load(r.uy, k), load(g.vy, k))),
                                      _mm_mul_ps(load(r.uz, k), load(g.vz, k)));
    const __m128 r_dot_v = _mm_sub_ps(_mm_mul_ps(two, _mm_mul_ps(ndl, load(g.n_dot_v, k))), l_dot_v);
    const __m128 ks = load(g.ks, k);
    const __m128 highlight_on = _mm_and_ps(_mm_cmpgt_ps(ks, zero), _mm_cmpgt_ps(r_dot_v, zero));
    __m128 highlight = zero;
    if (_mm_movemask_ps(highlight_on) != 0) {
      // pow of a lane without a highlight is computed on 1 and dropped.
      const __m128 base = select(highlight_on, r_dot_v, _mm_set1_ps(1.0f));
      highlight = _mm_and_ps(highlight_on, _mm_mul_ps(ks, _ZGVbN4vv_powf(base, load(g.shine, k))));
    }
    alignas(16) float tr[4], tg[4], tb[4];
    _mm_store_ps(tr, _mm_add_ps(_mm_mul_ps(load(g.dr, k), ndl), highlight));
    _mm_store_ps(tg, _mm_add_ps(_mm_mul_ps(load(g.dg, k), ndl), highlight));
    _mm_store_ps(tb, _mm_add_ps(_mm_mul_ps(load(g.db, k), ndl), highlight));
    for (int j = 0; j < 4; ++j)
      if (seen[k + j]) colours[k + j] += Vec3{ir * tr[j], ig * tg[j], ib * tb[j]};
  }
}

}  // namespace holoray
