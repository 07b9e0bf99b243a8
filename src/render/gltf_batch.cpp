#include "render/gltf_batch.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

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

int gltf_shadow_rays(const GltfLanes& g, const PointLight& light, double eps, ShadowPacket& s, GltfLightRays& out) {
  const bool directional = light.kind == LightKind::directional;
  const float lx = static_cast<float>(light.position.x), ly = static_cast<float>(light.position.y),
              lz = static_cast<float>(light.position.z);
  // Toward a directional light: -direction, the same for every lane.
  const float dlx = static_cast<float>(-light.direction.x), dly = static_cast<float>(-light.direction.y),
              dlz = static_cast<float>(-light.direction.z);
  const float e = static_cast<float>(eps);
  // light_falloff()'s terms: attenuation where it is not 1, the range
  // window, glTF's smooth spot cone.
  const bool attenuated = light.kc != 1 || light.kl != 0 || light.kq != 0;
  const float kc = static_cast<float>(light.kc), kl = static_cast<float>(light.kl), kq = static_cast<float>(light.kq);
  const float inv_range = light.range > 0 ? static_cast<float>(1 / light.range) : 0;
  const bool spot = light.kind == LightKind::spot;
  const float ax = static_cast<float>(light.direction.x), ay = static_cast<float>(light.direction.y),
              az = static_cast<float>(light.direction.z);
  const float cos_outer = static_cast<float>(light.cos_fall_end);
  const float inv_cone = static_cast<float>(1 / std::fmax(1e-3, light.cos_fall_start - light.cos_fall_end));
  int cast = 0;
  for (int k = 0; k < kPacketSize; ++k) {
    const float dx = lx - g.px[k], dy = ly - g.py[k], dz = lz - g.pz[k];
    const float dist = std::sqrt(dx * dx + dy * dy + dz * dz);
    const float inv = 1.0f / dist;
    const float ux = directional ? dlx : dx * inv, uy = directional ? dly : dy * inv, uz = directional ? dlz : dz * inv;
    const float ndl = g.nx[k] * ux + g.ny[k] * uy + g.nz[k] * uz;
    float falloff = 1;
    if (!directional) {
      if (attenuated) falloff = 1.0f / (kc + (kl + kq * dist) * dist);
      const float x = dist * inv_range, x2 = x * x;
      const float w = std::clamp(1 - x2 * x2, 0.0f, 1.0f);
      falloff *= inv_range > 0 ? w * w : 1.0f;
      const float t = std::clamp((-(ax * ux + ay * uy + az * uz) - cos_outer) * inv_cone, 0.0f, 1.0f);
      falloff *= spot ? t * t : 1.0f;
    }
    const bool ok = g.hit[k] != 0 && (directional || dist > e) && ndl > 0 && falloff > 0;
    out.ux[k] = ux, out.uy[k] = uy, out.uz[k] = uz, out.n_dot_l[k] = ndl, out.falloff[k] = falloff;
    s.org_x[k] = g.ox[k], s.org_y[k] = g.oy[k], s.org_z[k] = g.oz[k], s.tnear[k] = 0, s.time[k] = 0;
    s.dir_x[k] = ux, s.dir_y[k] = uy, s.dir_z[k] = uz;
    s.tfar[k] = directional ? INFINITY : dist - e;
    s.mask[k] = ~0u, s.id[k] = static_cast<unsigned>(k), s.flags[k] = 0;
    s.valid[k] = ok ? -1 : 0;
    cast += ok;
  }
  return cast;
}

void add_gltf_light(const GltfLanes& g, const GltfLightRays& r, const bool seen[kPacketSize], const Vec3& intensity,
                    Vec3 colours[kPacketSize]) {
  constexpr float kPi = std::numbers::pi_v<float>;
  alignas(16) float tr[kPacketSize], tg[kPacketSize], tb[kPacketSize];
  for (int k = 0; k < kPacketSize; ++k) {
    const float ux = r.ux[k], uy = r.uy[k], uz = r.uz[k], nx = g.nx[k], ny = g.ny[k], nz = g.nz[k];
    const float ndl = r.n_dot_l[k], ndv = g.n_dot_v[k], a2 = g.a2[k];
    // H = normalize(L + V).
    float hx = ux + g.vx[k], hy = uy + g.vy[k], hz = uz + g.vz[k];
    const float inv_h = 1.0f / std::sqrt(hx * hx + hy * hy + hz * hz);
    hx *= inv_h, hy *= inv_h, hz *= inv_h;
    const float ndh_raw = nx * hx + ny * hy + nz * hz;
    const float vdh = std::fabs(g.vx[k] * hx + g.vy[k] * hy + g.vz[k] * hz);
    // (N.H)^2 (a^2 - 1) + 1 as sin^2 + cos^2 a^2, the sine from N x H;
    // N.H clamped at 0 as gltf_direct clamps it (the denominator is then 1).
    const float cx = ny * hz - nz * hy, cy = nz * hx - nx * hz, cz = nx * hy - ny * hx;
    const float sin2 = cx * cx + cy * cy + cz * cz;
    const float d_denom = ndh_raw > 0 ? sin2 + ndh_raw * ndh_raw * a2 : 1.0f;
    const float d = a2 / (kPi * d_denom * d_denom);
    const float vis = 1.0f / ((ndl + std::sqrt(a2 + (1 - a2) * ndl * ndl)) * (ndv + std::sqrt(a2 + (1 - a2) * ndv * ndv)));
    const float spec_pi = d * vis * kPi;
    const float m1 = 1 - std::min(vdh, 1.0f), m2 = m1 * m1, w = m2 * m2 * m1;
    const float f_d = g.f0[k] + (1 - g.f0[k]) * w;
    const float m = g.metallic[k];
    const float scale = r.falloff[k] * g.cover[k] * ndl;
    const float keep = (1 - f_d) * g.diffuse[k] * (1 - m), spec_d = f_d * spec_pi * (1 - m), spec_m = spec_pi * m;
    // dielectric (1 - m) + metal m, the metal's Fresnel c + (1 - c) w per channel.
    tr[k] = scale * (g.br[k] * keep + spec_d + (g.br[k] + (1 - g.br[k]) * w) * spec_m);
    tg[k] = scale * (g.bg[k] * keep + spec_d + (g.bg[k] + (1 - g.bg[k]) * w) * spec_m);
    tb[k] = scale * (g.bb[k] * keep + spec_d + (g.bb[k] + (1 - g.bb[k]) * w) * spec_m);
  }
  const float ir = static_cast<float>(intensity.x), ig = static_cast<float>(intensity.y),
              ib = static_cast<float>(intensity.z);
  for (int k = 0; k < kPacketSize; ++k)
    if (seen[k]) colours[k] += Vec3{ir * tr[k], ig * tg[k], ib * tb[k]};
}

}  // namespace holoray
