#include "render/gltf_batch.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "render/lane_simd.hpp"

namespace holoray {

void GltfLanes::set(int k, const Vec3& p, const Vec3& n, const Vec3& above, const Vec3& view, const GltfSurface& s,
                    double transmittance) {
  px[k] = static_cast<float>(p.x), py[k] = static_cast<float>(p.y), pz[k] = static_cast<float>(p.z);
  nx[k] = static_cast<float>(n.x), ny[k] = static_cast<float>(n.y), nz[k] = static_cast<float>(n.z);
  ox[k] = static_cast<float>(above.x), oy[k] = static_cast<float>(above.y), oz[k] = static_cast<float>(above.z);
  vx[k] = static_cast<float>(view.x), vy[k] = static_cast<float>(view.y), vz[k] = static_cast<float>(view.z);
  n_dot_v[k] = static_cast<float>(std::fmax(std::fabs(dot(n, view)), 1e-6));
  br[k] = static_cast<float>(s.base.x), bg[k] = static_cast<float>(s.base.y), bb[k] = static_cast<float>(s.base.z);
  metallic[k] = static_cast<float>(std::clamp(s.metallic, 0.0, 1.0));
  const double a = s.roughness * s.roughness;
  a2[k] = static_cast<float>(std::fmax(a * a, 1e-12));
  f0[k] = static_cast<float>(s.f0);
  diffuse[k] = static_cast<float>(1 - std::clamp(s.transmission, 0.0, 1.0));
  cover[k] = static_cast<float>(1 - transmittance);
  hit[k] = -1;
}

void GltfLanes::clear(int k) {
  px[k] = py[k] = pz[k] = nx[k] = ny[k] = nz[k] = ox[k] = oy[k] = oz[k] = 0;
  vx[k] = vy[k] = vz[k] = br[k] = bg[k] = bb[k] = metallic[k] = f0[k] = diffuse[k] = cover[k] = 0;
  n_dot_v[k] = a2[k] = 1;
  hit[k] = 0;
}

bool can_batch(const PointLight& light) { return light.kind != LightKind::spot || light.smooth_cone; }

using lanes::dot3;
using lanes::load;
using lanes::select;

namespace {
inline __m128 clamp01(__m128 v) { return _mm_min_ps(_mm_max_ps(v, _mm_setzero_ps()), _mm_set1_ps(1.0f)); }
}  // namespace

// Four lanes per SSE instruction, every lane's every term computed and the
// lanes' answers selected (GCC left the same loops scalar: the selects of
// light kinds and clamps read to it as control flow).
int gltf_shadow_rays(const GltfLanes& g, const PointLight& light, double eps, ShadowPacket& s, GltfLightRays& out) {
  const bool directional = light.kind == LightKind::directional;
  const __m128 lx = _mm_set1_ps(static_cast<float>(light.position.x)), ly = _mm_set1_ps(static_cast<float>(light.position.y)),
               lz = _mm_set1_ps(static_cast<float>(light.position.z));
  // Toward a directional light: -direction, the same for every lane.
  const __m128 dlx = _mm_set1_ps(static_cast<float>(-light.direction.x)),
               dly = _mm_set1_ps(static_cast<float>(-light.direction.y)),
               dlz = _mm_set1_ps(static_cast<float>(-light.direction.z));
  const __m128 e = _mm_set1_ps(static_cast<float>(eps)), zero = _mm_setzero_ps(), one = _mm_set1_ps(1.0f);
  // light_falloff()'s terms: attenuation where it is not 1, the range
  // window, glTF's smooth spot cone.
  const bool attenuated = light.kc != 1 || light.kl != 0 || light.kq != 0;
  const __m128 kc = _mm_set1_ps(static_cast<float>(light.kc)), kl = _mm_set1_ps(static_cast<float>(light.kl)),
               kq = _mm_set1_ps(static_cast<float>(light.kq));
  const bool ranged = light.range > 0;
  const __m128 inv_range = _mm_set1_ps(ranged ? static_cast<float>(1 / light.range) : 0.0f);
  const bool spot = light.kind == LightKind::spot;
  const __m128 ax = _mm_set1_ps(static_cast<float>(light.direction.x)), ay = _mm_set1_ps(static_cast<float>(light.direction.y)),
               az = _mm_set1_ps(static_cast<float>(light.direction.z));
  const __m128 cos_outer = _mm_set1_ps(static_cast<float>(light.cos_fall_end));
  const __m128 inv_cone = _mm_set1_ps(static_cast<float>(1 / std::fmax(1e-3, light.cos_fall_start - light.cos_fall_end)));
  int cast = 0;
  for (int k = 0; k < kPacketSize; k += 4) {
    __m128 ux = dlx, uy = dly, uz = dlz, falloff = one, tfar = _mm_set1_ps(INFINITY);
    __m128 valid = _mm_castsi128_ps(_mm_load_si128(reinterpret_cast<const __m128i*>(g.hit + k)));
    if (!directional) {
      const __m128 dx = _mm_sub_ps(lx, load(g.px, k)), dy = _mm_sub_ps(ly, load(g.py, k)), dz = _mm_sub_ps(lz, load(g.pz, k));
      const __m128 dist = _mm_sqrt_ps(dot3(dx, dy, dz, dx, dy, dz));
      const __m128 inv = _mm_div_ps(one, dist);
      ux = _mm_mul_ps(dx, inv), uy = _mm_mul_ps(dy, inv), uz = _mm_mul_ps(dz, inv);
      if (attenuated) falloff = _mm_div_ps(one, _mm_add_ps(kc, _mm_mul_ps(_mm_add_ps(kl, _mm_mul_ps(kq, dist)), dist)));
      if (ranged) {
        const __m128 x = _mm_mul_ps(dist, inv_range), x2 = _mm_mul_ps(x, x);
        const __m128 w = clamp01(_mm_sub_ps(one, _mm_mul_ps(x2, x2)));
        falloff = _mm_mul_ps(falloff, _mm_mul_ps(w, w));
      }
      if (spot) {
        const __m128 cos_a = _mm_sub_ps(zero, dot3(ax, ay, az, ux, uy, uz));
        const __m128 t = clamp01(_mm_mul_ps(_mm_sub_ps(cos_a, cos_outer), inv_cone));
        falloff = _mm_mul_ps(falloff, _mm_mul_ps(t, t));
      }
      valid = _mm_and_ps(valid, _mm_cmpgt_ps(dist, e));
      tfar = _mm_sub_ps(dist, e);
    }
    const __m128 ndl = dot3(load(g.nx, k), load(g.ny, k), load(g.nz, k), ux, uy, uz);
    // In front of the surface and lit at all (a NaN casts nothing).
    valid = _mm_and_ps(valid, _mm_and_ps(_mm_cmpgt_ps(ndl, zero), _mm_cmpgt_ps(falloff, zero)));
    _mm_store_ps(out.ux + k, ux), _mm_store_ps(out.uy + k, uy), _mm_store_ps(out.uz + k, uz);
    _mm_store_ps(out.n_dot_l + k, ndl), _mm_store_ps(out.falloff + k, falloff);
    cast += lanes::store_shadow_rays(s, k, load(g.ox, k), load(g.oy, k), load(g.oz, k), ux, uy, uz, tfar, valid);
  }
  return cast;
}

void add_gltf_light(const GltfLanes& g, const GltfLightRays& r, const bool seen[kPacketSize], const Vec3& intensity,
                    Vec3 colours[kPacketSize]) {
  const __m128 zero = _mm_setzero_ps(), one = _mm_set1_ps(1.0f), pi = _mm_set1_ps(std::numbers::pi_v<float>);
  const float ir = static_cast<float>(intensity.x), ig = static_cast<float>(intensity.y),
              ib = static_cast<float>(intensity.z);
  for (int k = 0; k < kPacketSize; k += 4) {
    if (!(seen[k] | seen[k + 1] | seen[k + 2] | seen[k + 3])) continue;
    const __m128 ux = load(r.ux, k), uy = load(r.uy, k), uz = load(r.uz, k);
    const __m128 nx = load(g.nx, k), ny = load(g.ny, k), nz = load(g.nz, k);
    const __m128 vx = load(g.vx, k), vy = load(g.vy, k), vz = load(g.vz, k);
    const __m128 ndl = load(r.n_dot_l, k), ndv = load(g.n_dot_v, k), a2 = load(g.a2, k);
    // H = normalize(L + V).
    __m128 hx = _mm_add_ps(ux, vx), hy = _mm_add_ps(uy, vy), hz = _mm_add_ps(uz, vz);
    const __m128 inv_h = _mm_div_ps(one, _mm_sqrt_ps(dot3(hx, hy, hz, hx, hy, hz)));
    hx = _mm_mul_ps(hx, inv_h), hy = _mm_mul_ps(hy, inv_h), hz = _mm_mul_ps(hz, inv_h);
    const __m128 ndh = dot3(nx, ny, nz, hx, hy, hz);
    const __m128 vdh = _mm_andnot_ps(_mm_set1_ps(-0.0f), dot3(vx, vy, vz, hx, hy, hz));
    // (N.H)^2 (a^2 - 1) + 1 as sin^2 + cos^2 a^2, the sine from N x H;
    // N.H clamped at 0 as gltf_direct clamps it (the denominator is then 1).
    const __m128 cx = _mm_sub_ps(_mm_mul_ps(ny, hz), _mm_mul_ps(nz, hy)),
                 cy = _mm_sub_ps(_mm_mul_ps(nz, hx), _mm_mul_ps(nx, hz)),
                 cz = _mm_sub_ps(_mm_mul_ps(nx, hy), _mm_mul_ps(ny, hx));
    const __m128 peak = _mm_add_ps(dot3(cx, cy, cz, cx, cy, cz), _mm_mul_ps(_mm_mul_ps(ndh, ndh), a2));
    const __m128 d_denom = select(_mm_cmpgt_ps(ndh, zero), peak, one);
    const __m128 d = _mm_div_ps(a2, _mm_mul_ps(pi, _mm_mul_ps(d_denom, d_denom)));
    // Smith's V = 1 / ((N.L + sqrt(a2 + (1 - a2) N.L^2)) (N.V + sqrt(a2 + (1 - a2) N.V^2))).
    const __m128 rest = _mm_sub_ps(one, a2);
    const __m128 gl = _mm_add_ps(ndl, _mm_sqrt_ps(_mm_add_ps(a2, _mm_mul_ps(rest, _mm_mul_ps(ndl, ndl)))));
    const __m128 gv = _mm_add_ps(ndv, _mm_sqrt_ps(_mm_add_ps(a2, _mm_mul_ps(rest, _mm_mul_ps(ndv, ndv)))));
    const __m128 spec_pi = _mm_div_ps(_mm_mul_ps(d, pi), _mm_mul_ps(gl, gv));
    // Schlick's (1 - |V.H|)^5.
    const __m128 m1 = _mm_sub_ps(one, _mm_min_ps(vdh, one)), m2 = _mm_mul_ps(m1, m1);
    const __m128 w = _mm_mul_ps(_mm_mul_ps(m2, m2), m1);
    const __m128 f0 = load(g.f0, k), f_d = _mm_add_ps(f0, _mm_mul_ps(_mm_sub_ps(one, f0), w));
    const __m128 m = load(g.metallic, k), dielectric = _mm_sub_ps(one, m);
    const __m128 scale = _mm_mul_ps(_mm_mul_ps(load(r.falloff, k), load(g.cover, k)), ndl);
    const __m128 keep = _mm_mul_ps(_mm_mul_ps(_mm_sub_ps(one, f_d), load(g.diffuse, k)), dielectric);
    const __m128 spec_d = _mm_mul_ps(_mm_mul_ps(f_d, spec_pi), dielectric), spec_m = _mm_mul_ps(spec_pi, m);
    // dielectric (1 - m) + metal m, the metal's Fresnel c + (1 - c) w per channel.
    auto channel = [&](const float* base) {
      const __m128 c = load(base, k);
      const __m128 f_m = _mm_add_ps(c, _mm_mul_ps(_mm_sub_ps(one, c), w));
      return _mm_mul_ps(scale, _mm_add_ps(_mm_add_ps(_mm_mul_ps(c, keep), spec_d), _mm_mul_ps(f_m, spec_m)));
    };
    alignas(16) float tr[4], tg[4], tb[4];
    _mm_store_ps(tr, channel(g.br)), _mm_store_ps(tg, channel(g.bg)), _mm_store_ps(tb, channel(g.bb));
    for (int j = 0; j < 4; ++j)
      if (seen[k + j]) colours[k + j] += Vec3{ir * tr[j], ig * tg[j], ib * tb[j]};
  }
}

}  // namespace holoray
