// holoray/render, internal to the shading: what every shading model's terms
// read about one hit (HitFrame), the shadow ray toward a light and its
// falloff, the secondary rays' record, and the shadow cache's answers. The
// models are a type each (render/models/), dispatched on Material::model in
// one place (shading_models.hpp).
#pragma once

#include <cmath>

#include "render/light_falloff.hpp"
#include "render/ray_counts.hpp"
#include "render/render_context.hpp"
#include "render/shadow_cache.hpp"

namespace holoray::shading {

inline Vec3 reflect(const Vec3& d, const Vec3& n) { return d - n * (2 * dot(d, n)); }

// What every term of the shading formula needs about one hit.
struct HitFrame {
  const Material* m;
  Vec3 colour;  // the surface colour C: the material's, times its texture (SurfacePoint::colour)
  Vec3 view;   // toward the viewer
  Vec3 ng;     // geometric normal turned to the viewer's side
  Vec3 ns;     // shading normal turned likewise
  Vec3 above;  // origin for rays leaving on the viewer's side
  bool front;  // the ray met the outward (winding) side
};

[[gnu::always_inline]] inline HitFrame frame_of(const RenderContext& scene, const Ray& ray, const SurfacePoint& sp) {
  HitFrame f;
  f.m = sp.material;
  f.colour = sp.colour;
  f.view = -ray.dir;
  // Both normals turned to the side the ray came from (two-sided surfaces, nff-notes §10.2).
  f.front = dot(sp.ng, f.view) >= 0;
  f.ng = f.front ? sp.ng : -sp.ng;
  f.ns = f.front ? sp.ns : -sp.ns;
  f.above = sp.position + f.ng * scene.epsilon();
  return f;
}

// A mesh material's own light (Material::emission), added right after the
// ambient term; most materials give off none and add nothing (NFF's and
// Tachyon's scenes keep their bits).
inline void add_emission(const RenderContext& scene, const Ray& ray, const SurfacePoint& sp, Vec3& colour) {
  const Vec3& e = sp.material->emission;
  if (e.x > 0 || e.y > 0 || e.z > 0) colour += scene.emission(sp, length(sp.position - ray.org));
}


// The shadow ray toward `light` and the light's falloff there; false when
// no shadow ray is cast (light on the surface, the normal faces away from
// it: nff-notes §10.10, or the falloff leaves nothing). A directional
// light's ray is unbounded. `Unit`: the caller knows the light is a point
// of unit falloff (PointLight::unit_falloff: NFF's), and the code for the
// other kinds is left out of its loop.
template <bool Unit = false>
[[gnu::always_inline]] inline bool shadow_ray(const RenderContext& scene, const HitFrame& f, const SurfacePoint& sp,
                                              const PointLight& light, Ray& shadow, double& falloff) {
  const double eps = scene.epsilon();
  if (!Unit && light.kind == LightKind::directional) {
    const Vec3 to_light = -light.direction;
    if (dot(f.ns, to_light) <= 0) return false;
    shadow = Ray{f.above, to_light, 0, INFINITY};
    falloff = 1;
    return true;
  }
  Vec3 to_light = light.position - sp.position;
  const double dist = length(to_light);
  if (!(dist > eps)) return false;
  to_light = to_light / dist;
  if (dot(f.ns, to_light) <= 0) return false;
  falloff = 1;
  if (!Unit && !light.unit_falloff) {
    falloff = light_falloff(light, to_light, dist);
    if (!(falloff > 0)) return false;
  }
  shadow = Ray{f.above, to_light, 0, dist - eps};
  return true;
}


// The secondary rays that leave a hit (nff-notes §10): the mirror ray when
// Ks > 0, weighted Ks; the transmitted ray when T > 0, weighted T: refracted
// by Snell's law, or on total internal reflection a second mirror ray.
// glTF materials: the mirror ray below kMirrorRoughness, weighted by the
// Fresnel mix (gltf_mirror_weight) times alpha; BLEND's 1 - alpha goes
// straight through, unbent.
struct SecondaryRays {
  bool mirror = false, transmit = false;
  bool transmit_reflects = false;  // total internal reflection: counted as a reflected ray
  Ray mirror_ray, transmit_ray;
  Vec3 mirror_weight, transmit_weight;
};


// The mirror ray off the hit (the true normal where the interpolated one
// would send it into the surface).
[[gnu::always_inline]] inline Ray mirror_ray_of(const Ray& ray, const HitFrame& f) {
  Vec3 r = reflect(ray.dir, f.ns);
  if (dot(r, f.ng) <= 0) r = reflect(ray.dir, f.ng);
  return Ray{f.above, normalize(r), 0, INFINITY};
}


// What the shadow cache says of `shadow` (light number `light`, cast from
// `sp`): 1 the light is seen, 0 it is blocked, -1 unknown: trace the ray. The
// cache is asked only where the ray leaves from the light's side of the
// surface, the side its cells' corners leave from. A partial cell's ray is
// traced with the packet's others: testing the occluders its corners met
// first (one primitive each) measured slower than tracing (gears_s4 2048x2048:
// 3.27/3.15/2.79 s against 2.71/2.76/2.40 s).
inline int cached_visibility(const RenderContext& scene, const HitFrame& f, const SurfacePoint& sp, const CellRef& cell,
                      int light, const Ray& shadow, RayCounts& counts) {
  const ShadowCache* cache = scene.shadow_cache();
  if (cache == nullptr || cell.slot == CellRef::kNone || dot(f.ng, shadow.dir) <= 0) return -1;
  // The cache's corners aim at a light's position: a directional light has none.
  if (scene.lights()[static_cast<size_t>(light)].kind == LightKind::directional) return -1;
  switch (cache->visibility(sp, cell, light, counts)) {
    case LightVisibility::lit: ++counts.shadow_cached; return 1;
    case LightVisibility::shadowed: ++counts.shadow_cached; return 0;
    case LightVisibility::partial:
    case LightVisibility::unknown: return -1;
  }
  return -1;
}

inline CellRef cell_of(const RenderContext& scene, const SurfacePoint& sp) {
  const ShadowCache* cache = scene.shadow_cache();
  return cache ? cache->locate(sp) : CellRef::none();
}


}  // namespace holoray::shading
