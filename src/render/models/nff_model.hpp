// holoray/render: the NFF shading model, the SPD's (nff-notes §4, §10):
//   I = Ia Kd C + sum over seen lights Il (Kd C N.L + Ks (R.V)^Shine)
//       + Ks I_reflected + T I_transmitted
// Ks is both the mirror weight and the highlight weight; refraction follows
// Snell's law with total internal reflection. The hot path: all inline.
#pragma once

#include "render/shading_terms.hpp"

namespace holoray::shading {

struct NffModel {
  /// Ia Kd C (nff-notes §4).
  static Vec3 ambient(const RenderContext& scene, const HitFrame& f) { return mul(scene.ambient(), f.colour) * f.m->kd; }

  // NFF's diffuse and highlight weights toward a light (nff-notes §10.10).
  static Vec3 term(const HitFrame& f, const Vec3& to_light) {
    const Material& m = *f.m;
    const double n_dot_l = dot(f.ns, to_light);
    Vec3 term = f.colour * (m.kd * n_dot_l);
    if (m.ks > 0) {
      const double r_dot_v = dot(reflect(-to_light, f.ns), f.view);
      if (r_dot_v > 0) term += Vec3{1, 1, 1} * (m.ks * std::pow(r_dot_v, m.shine));
    }
    return term;
  }


  /// A seen light's term: Il times falloff times term(), computed only for
  /// lights that are seen, so a shadowed light costs no pow().
  static Vec3 light(const HitFrame& f, const PointLight& light, const Vec3& to_light, double falloff) {
    return mul(light.intensity * falloff, term(f, to_light));
  }

  // The mirror ray of an NFF or blinn_phong material (Ks > 0), weighted Ks:
  // false when it casts none. Written into `out` (no temporary: a packet's
  // lanes are filled in place).
  [[gnu::always_inline]] static bool mirror(const Ray& ray, const HitFrame& f, Ray& out, Vec3& weight) {
    const Material& m = *f.m;
    if (!(m.ks > 0)) return false;
    out = mirror_ray_of(ray, f);
    weight = Vec3{m.ks, m.ks, m.ks};
    return true;
  }


  // The transmitted ray of an NFF or blinn_phong material (T > 0), weighted T:
  // refracted by Snell's law, or on total internal reflection (`reflects`) a
  // second mirror ray; false when it casts none.
  [[gnu::always_inline]] static bool transmit(const RenderContext& scene, const Ray& ray, const SurfacePoint& sp,
                                                  const HitFrame& f, Ray& out, Vec3& weight, bool& reflects) {
    const Material& m = *f.m;
    if (!(m.transmittance > 0)) return false;
    weight = Vec3{m.transmittance, m.transmittance, m.transmittance};
    // Entering when the ray meets the outward (winding) side.
    const double eta = f.front ? 1.0 / m.ior : m.ior;
    const double cos_i = dot(f.view, f.ns);
    const double k = 1 - eta * eta * (1 - cos_i * cos_i);
    reflects = k < 0;
    if (reflects) {
      out = mirror_ray_of(ray, f);
      return true;
    }
    Vec3 dir = normalize(ray.dir * eta + f.ns * (eta * cos_i - std::sqrt(k)));
    if (dot(dir, f.ng) >= 0) dir = ray.dir;  // shading normal bent it back out: go straight through
    out = Ray{sp.position - f.ng * scene.epsilon(), dir, 0, INFINITY};
    return true;
  }

};

}  // namespace holoray::shading
