#include "render/shading.hpp"

#include <algorithm>
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

namespace {

// What every term of the shading formula needs about one hit.
struct HitFrame {
  const Material* m;
  Vec3 view;   // toward the viewer
  Vec3 ng;     // geometric normal turned to the viewer's side
  Vec3 ns;     // shading normal turned likewise
  Vec3 above;  // origin for rays leaving on the viewer's side
  bool front;  // the ray met the outward (winding) side
};

HitFrame frame_of(const RenderScene& scene, const Ray& ray, const SurfacePoint& sp) {
  HitFrame f;
  f.m = sp.material;
  f.view = -ray.dir;
  // Both normals turned to the side the ray came from (two-sided surfaces, nff-notes §10.2).
  f.front = dot(sp.ng, f.view) >= 0;
  f.ng = f.front ? sp.ng : -sp.ng;
  f.ns = f.front ? sp.ns : -sp.ns;
  f.above = sp.position + f.ng * scene.epsilon();
  return f;
}

// The shadow ray toward `light` and the light's contribution if it is not
// blocked; false when no shadow ray is cast (light on the surface, or the
// normal faces away from it: nff-notes §10.10).
bool light_sample(const RenderScene& scene, const HitFrame& f, const SurfacePoint& sp, const PointLight& light,
                  Ray& shadow, Vec3& contribution) {
  const double eps = scene.epsilon();
  Vec3 to_light = light.position - sp.position;
  const double dist = length(to_light);
  if (!(dist > eps)) return false;
  to_light = to_light / dist;
  const double n_dot_l = dot(f.ns, to_light);
  if (n_dot_l <= 0) return false;
  shadow = Ray{f.above, to_light, 0, dist - eps};
  const Material& m = *f.m;
  Vec3 term = m.colour * (m.kd * n_dot_l);
  if (m.ks > 0) {
    const double r_dot_v = dot(reflect(-to_light, f.ns), f.view);
    if (r_dot_v > 0) term += Vec3{1, 1, 1} * (m.ks * std::pow(r_dot_v, m.shine));
  }
  contribution = mul(light.intensity, term);
  return true;
}

// Adds mirror and transmitted light to `colour`, traced one ray at a time (incoherent).
void add_secondary(const RenderScene& scene, const Ray& ray, const SurfacePoint& sp, const HitFrame& f, int depth,
                   RayCounts& counts, Vec3& colour) {
  if (depth >= scene.max_depth()) return;
  const Material& m = *f.m;
  auto mirror_dir = [&] {
    Vec3 r = reflect(ray.dir, f.ns);
    // An interpolated normal can send the mirror ray into the surface; fall back to the true one.
    if (dot(r, f.ng) <= 0) r = reflect(ray.dir, f.ng);
    return normalize(r);
  };
  if (m.ks > 0) {
    ++counts.reflected;
    colour += trace(scene, Ray{f.above, mirror_dir(), 0, INFINITY}, depth + 1, counts) * m.ks;
  }
  if (m.transmittance > 0) {
    // Entering when the ray meets the outward (winding) side.
    const double eta = f.front ? 1.0 / m.ior : m.ior;
    const double cos_i = dot(f.view, f.ns);
    const double k = 1 - eta * eta * (1 - cos_i * cos_i);
    if (k < 0) {  // total internal reflection: the transmitted weight goes to a reflection ray
      ++counts.reflected;
      colour += trace(scene, Ray{f.above, mirror_dir(), 0, INFINITY}, depth + 1, counts) * m.transmittance;
    } else {
      Vec3 dir = normalize(ray.dir * eta + f.ns * (eta * cos_i - std::sqrt(k)));
      if (dot(dir, f.ng) >= 0) dir = ray.dir;  // shading normal bent it back out: go straight through
      ++counts.refracted;
      const Vec3 below = sp.position - f.ng * scene.epsilon();
      colour += trace(scene, Ray{below, dir, 0, INFINITY}, depth + 1, counts) * m.transmittance;
    }
  }
}

}  // namespace

Vec3 shade(const RenderScene& scene, const Ray& ray, const SurfacePoint& sp, int depth, RayCounts& counts) {
  const HitFrame f = frame_of(scene, ray, sp);
  Vec3 colour = mul(scene.ambient(), f.m->colour) * f.m->kd;
  for (const PointLight& light : scene.lights()) {
    Ray shadow;
    Vec3 contribution;
    if (!light_sample(scene, f, sp, light, shadow, contribution)) continue;
    ++counts.shadow;
    if (!scene.accel().occluded(shadow)) colour += contribution;
  }
  add_secondary(scene, ray, sp, f, depth, counts, colour);
  return colour;
}

namespace {

// The colour seen along each active lane of `rays` at ray-tree `depth`:
// traced as one packet (incoherent), the hits shaded as a packet.
void trace_packet(const RenderScene& scene, const RayPacket& rays, int depth, RayCounts& counts,
                  Vec3 colours[kPacketSize]) {
  Hit hits[kPacketSize];
  bool found[kPacketSize] = {};
  scene.accel().intersect(rays, hits, found, RayCoherence::incoherent);
  SurfacePoint sps[kPacketSize];
  bool any = false;
  for (int k = 0; k < kPacketSize; ++k) {
    if (!rays.active[k]) continue;
    colours[k] = scene.background();
    if (found[k]) sps[k] = scene.surface(rays.rays[k], hits[k]);
    any |= found[k];
  }
  if (any) shade(scene, rays, found, sps, depth, counts, colours);
}

// A packet of secondary rays is traced as a packet only when its rays are
// nearly parallel (every one within ~25 degrees of their mean) and at least
// this many: off a large smooth mirror (the teapot) that is 6 % faster per
// frame; off small spheres (balls) the rays scatter, and packets of them, and
// of their hits' shadow rays, were 27 % slower than single rays.
constexpr double kMinCoherentCos = 0.9;
constexpr int kMinCoherentLanes = 4;

// add_secondary() for the lanes of a packet: the mirror rays of all lanes,
// then the transmitted (or totally reflected) rays, each set traced a level
// deeper as one packet when coherent, else one by one. Same rays, weights and
// order of addition per lane as add_secondary().
void add_secondary(const RenderScene& scene, const RayPacket& rays, const bool hit[kPacketSize],
                   const SurfacePoint sps[kPacketSize], const HitFrame f[kPacketSize], int depth, RayCounts& counts,
                   Vec3 colours[kPacketSize]) {
  if (depth >= scene.max_depth()) return;
  RayPacket next;
  double weight[kPacketSize];
  auto mirror_dir = [&](int k) {
    Vec3 r = reflect(rays.rays[k].dir, f[k].ns);
    if (dot(r, f[k].ng) <= 0) r = reflect(rays.rays[k].dir, f[k].ng);
    return normalize(r);
  };
  auto flush = [&] {
    Vec3 mean;
    int n = 0;
    for (int k = 0; k < kPacketSize; ++k)
      if (next.active[k]) mean += next.rays[k].dir, ++n;
    if (n == 0) return;
    mean = normalize(mean);
    double spread = 1;
    for (int k = 0; k < kPacketSize; ++k)
      if (next.active[k]) spread = std::fmin(spread, dot(next.rays[k].dir, mean));
    if (n < kMinCoherentLanes || spread < kMinCoherentCos) {
      for (int k = 0; k < kPacketSize; ++k)
        if (next.active[k]) colours[k] += trace(scene, next.rays[k], depth + 1, counts) * weight[k];
      return;
    }
    Vec3 seen[kPacketSize];
    trace_packet(scene, next, depth + 1, counts, seen);
    for (int k = 0; k < kPacketSize; ++k)
      if (next.active[k]) colours[k] += seen[k] * weight[k];
  };
  for (int k = 0; k < kPacketSize; ++k) {
    next.active[k] = hit[k] && f[k].m->ks > 0;
    if (!next.active[k]) continue;
    ++counts.reflected;
    next.rays[k] = Ray{f[k].above, mirror_dir(k), 0, INFINITY};
    weight[k] = f[k].m->ks;
  }
  flush();
  for (int k = 0; k < kPacketSize; ++k) {
    next.active[k] = hit[k] && f[k].m->transmittance > 0;
    if (!next.active[k]) continue;
    const Material& m = *f[k].m;
    weight[k] = m.transmittance;
    const Ray& ray = rays.rays[k];
    const double eta = f[k].front ? 1.0 / m.ior : m.ior;
    const double cos_i = dot(f[k].view, f[k].ns);
    const double q = 1 - eta * eta * (1 - cos_i * cos_i);
    if (q < 0) {  // total internal reflection
      ++counts.reflected;
      next.rays[k] = Ray{f[k].above, mirror_dir(k), 0, INFINITY};
    } else {
      Vec3 dir = normalize(ray.dir * eta + f[k].ns * (eta * cos_i - std::sqrt(q)));
      if (dot(dir, f[k].ng) >= 0) dir = ray.dir;
      ++counts.refracted;
      next.rays[k] = Ray{sps[k].position - f[k].ng * scene.epsilon(), dir, 0, INFINITY};
    }
  }
  flush();
}

}  // namespace

void shade(const RenderScene& scene, const RayPacket& rays, const bool hit[kPacketSize],
           const SurfacePoint sps[kPacketSize], int depth, RayCounts& counts, Vec3 colours[kPacketSize]) {
  HitFrame f[kPacketSize];
  for (int k = 0; k < kPacketSize; ++k) {
    if (!hit[k]) continue;
    f[k] = frame_of(scene, rays.rays[k], sps[k]);
    colours[k] = mul(scene.ambient(), f[k].m->colour) * f[k].m->kd;
  }
  // The shadow rays of one packet toward one light share their end point:
  // traced together as a packet.
  RayPacket shadows;
  Vec3 contribution[kPacketSize];
  bool blocked[kPacketSize];
  for (const PointLight& light : scene.lights()) {
    int cast = 0;
    for (int k = 0; k < kPacketSize; ++k) {
      shadows.active[k] = hit[k] && light_sample(scene, f[k], sps[k], light, shadows.rays[k], contribution[k]);
      cast += shadows.active[k];
    }
    if (cast == 0) continue;
    counts.shadow += static_cast<uint64_t>(cast);
    scene.accel().occluded(shadows, blocked);
    for (int k = 0; k < kPacketSize; ++k)
      if (shadows.active[k] && !blocked[k]) colours[k] += contribution[k];
  }
  add_secondary(scene, rays, hit, sps, f, depth, counts, colours);
}

}  // namespace holoray
