#include "render/shading.hpp"

#include <cmath>

namespace holoray {

namespace {
Vec3 reflect(const Vec3& d, const Vec3& n) { return d - n * (2 * dot(d, n)); }
}  // namespace

Vec3 trace(const RenderScene& scene, const Ray& ray, int depth, RayCounts& counts) {
  Hit hit;
  if (!scene.accel().intersect(ray, hit)) return scene.background();
  return shade(scene, ray, scene.surface(ray, hit), depth, counts);
}

Vec3 shade(const RenderScene& scene, const Ray& ray, const SurfacePoint& sp, int depth, RayCounts& counts) {
  const Material& m = *sp.material;
  const Vec3 view = -ray.dir;
  // Both normals turned to the side the ray came from (two-sided surfaces, nff-notes §10.2).
  const bool front = dot(sp.ng, view) >= 0;
  const Vec3 ng = front ? sp.ng : -sp.ng;
  const Vec3 ns = front ? sp.ns : -sp.ns;
  const double eps = scene.epsilon();
  const Vec3 above = sp.position + ng * eps;  // origin for rays leaving on the viewer's side

  Vec3 colour = mul(scene.ambient(), m.colour) * m.kd;
  for (const PointLight& light : scene.lights()) {
    Vec3 to_light = light.position - sp.position;
    const double dist = length(to_light);
    if (!(dist > eps)) continue;
    to_light = to_light / dist;
    const double n_dot_l = dot(ns, to_light);
    if (n_dot_l <= 0) continue;  // faces away: no shadow ray (nff-notes §10.10)
    ++counts.shadow;
    if (scene.accel().occluded(Ray{above, to_light, 0, dist - eps})) continue;
    Vec3 term = m.colour * (m.kd * n_dot_l);
    if (m.ks > 0) {
      const double r_dot_v = dot(reflect(-to_light, ns), view);
      if (r_dot_v > 0) term += Vec3{1, 1, 1} * (m.ks * std::pow(r_dot_v, m.shine));
    }
    colour += mul(light.intensity, term);
  }
  if (depth >= kMaxRayDepth) return colour;

  auto mirror_dir = [&] {
    Vec3 r = reflect(ray.dir, ns);
    // An interpolated normal can send the mirror ray into the surface; fall back to the true one.
    if (dot(r, ng) <= 0) r = reflect(ray.dir, ng);
    return normalize(r);
  };
  if (m.ks > 0) {
    ++counts.reflected;
    colour += trace(scene, Ray{above, mirror_dir(), 0, INFINITY}, depth + 1, counts) * m.ks;
  }
  if (m.transmittance > 0) {
    // Entering when the ray meets the outward (winding) side.
    const double eta = front ? 1.0 / m.ior : m.ior;
    const double cos_i = dot(view, ns);
    const double k = 1 - eta * eta * (1 - cos_i * cos_i);
    if (k < 0) {  // total internal reflection: the transmitted weight goes to a reflection ray
      ++counts.reflected;
      colour += trace(scene, Ray{above, mirror_dir(), 0, INFINITY}, depth + 1, counts) * m.transmittance;
    } else {
      Vec3 dir = normalize(ray.dir * eta + ns * (eta * cos_i - std::sqrt(k)));
      if (dot(dir, ng) >= 0) dir = ray.dir;  // shading normal bent it back out: go straight through
      ++counts.refracted;
      const Vec3 below = sp.position - ng * eps;
      colour += trace(scene, Ray{below, dir, 0, INFINITY}, depth + 1, counts) * m.transmittance;
    }
  }
  return colour;
}

}  // namespace holoray
