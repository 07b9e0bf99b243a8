#include "render/shading.hpp"

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "render/gltf_brdf.hpp"
#include "render/gltf_batch.hpp"
#include "render/light_batch.hpp"
#include "render/shadow_cache.hpp"

namespace holoray {

namespace {
Vec3 reflect(const Vec3& d, const Vec3& n) { return d - n * (2 * dot(d, n)); }
}  // namespace

Vec3 trace(const RenderContext& scene, const Ray& ray, int depth, RayCounts& counts) {
  Hit hit;
  if (!scene.accel().intersect(ray, hit)) return scene.background();
  return shade(scene, ray, scene.surface(ray, hit), depth, counts);
}

namespace {

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

// How much of a light's intensity reaches a point at `dist` along
// `to_light` (unit, toward the light): attenuation 1 / (kc + kl d + kq d^2),
// KHR_lights_punctual's range window and the spot cone (Tachyon's linear
// falloff in the angle, or glTF's smooth one). Exactly 1 for NFF's lights.
[[gnu::noinline]] double light_falloff(const PointLight& light, const Vec3& to_light, double dist) {
  if (light.kind == LightKind::directional) return 1;
  double a = 1;
  if (light.kc != 1 || light.kl != 0 || light.kq != 0) a = 1 / (light.kc + (light.kl + light.kq * dist) * dist);
  if (light.range > 0) {
    const double x2 = (dist / light.range) * (dist / light.range);
    const double w = std::clamp(1 - x2 * x2, 0.0, 1.0);
    a *= w * w;
  }
  if (light.kind == LightKind::spot) {
    const double cos_a = -dot(light.direction, to_light);
    if (light.smooth_cone) {
      const double cos_outer = light.cos_fall_end;
      const double t = std::clamp((cos_a - cos_outer) / std::fmax(1e-3, light.cos_fall_start - cos_outer), 0.0, 1.0);
      a *= t * t;
    } else {
      const double angle = std::acos(std::clamp(cos_a, -1.0, 1.0));
      if (angle > light.fall_end) a = 0;
      else if (angle > light.fall_start) a *= 1 - (angle - light.fall_start) / (light.fall_end - light.fall_start);
    }
  }
  return a;
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

// The BRDF's inputs at a hit. Metallic and roughness come from the
// SurfacePoint (textures applied), not the HitFrame: NFF's hot loops keep
// their frames as small as before glTF.
GltfSurface gltf_surface(const HitFrame& f, const SurfacePoint& sp) {
  return GltfSurface{f.colour, sp.metallic, sp.roughness, dielectric_f0(f.m->ior), f.m->transmission};
}

// light_contribution() of a glTF material: kept out of line, so that NFF's
// hot path stays as small as it was.
[[gnu::noinline]] Vec3 gltf_contribution(const HitFrame& f, const SurfacePoint& sp, const PointLight& light,
                                         const Vec3& to_light, double falloff) {
  return mul(light.intensity * (falloff * (1 - f.m->transmittance)),
             gltf_direct(gltf_surface(f, sp), f.ns, f.view, to_light));
}

// NFF's diffuse and highlight weights toward a light (nff-notes §10.10).
inline Vec3 nff_term(const HitFrame& f, const Vec3& to_light) {
  const Material& m = *f.m;
  const double n_dot_l = dot(f.ns, to_light);
  Vec3 term = f.colour * (m.kd * n_dot_l);
  if (m.ks > 0) {
    const double r_dot_v = dot(reflect(-to_light, f.ns), f.view);
    if (r_dot_v > 0) term += Vec3{1, 1, 1} * (m.ks * std::pow(r_dot_v, m.shine));
  }
  return term;
}

// light_contribution() of a blinn_phong material: NFF's terms plus MTL's
// highlight Ks (N.H)^Ns (illumination model 2), out of line as glTF's.
[[gnu::noinline]] Vec3 blinn_phong_contribution(const HitFrame& f, const SurfacePoint& sp, const PointLight& light,
                                                const Vec3& to_light, double falloff) {
  Vec3 term = nff_term(f, to_light);
  const double n_dot_h = dot(f.ns, normalize(to_light + f.view));
  if (n_dot_h > 0) term += f.m->specular * (sp.highlight * std::pow(n_dot_h, f.m->shine));
  return mul(light.intensity * falloff, term);
}

// The light's contribution along the unblocked shadow ray's unit direction `to_light`. NFF's
// materials: diffuse and highlight, computed only for lights that are
// seen, so a shadowed light costs no pow(). glTF's: the metallic-roughness
// BRDF (gltf_brdf.hpp) times the part of the surface that is there
// (BLEND: alpha). blinn_phong's: NFF's with MTL's highlight.
Vec3 light_contribution(const HitFrame& f, const SurfacePoint& sp, const PointLight& light, const Vec3& to_light,
                        double falloff) {
  if (f.m->model != ShadingModel::nff) [[unlikely]] {
    if (f.m->model == ShadingModel::gltf) return gltf_contribution(f, sp, light, to_light, falloff);
    return blinn_phong_contribution(f, sp, light, to_light, falloff);
  }
  return mul(light.intensity * falloff, nff_term(f, to_light));
}

// NFF's ambient term Ia*Kd*C (nff-notes §4); glTF materials have none.
Vec3 ambient_term(const RenderContext& scene, const HitFrame& f) {
  if (f.m->model == ShadingModel::gltf) return {};
  return mul(scene.ambient(), f.colour) * f.m->kd;
}

// What the shadow cache says of `shadow` (light number `light`, cast from
// `sp`): 1 the light is seen, 0 it is blocked, -1 unknown: trace the ray. The
// cache is asked only where the ray leaves from the light's side of the
// surface, the side its cells' corners leave from. A partial cell's ray is
// traced with the packet's others: testing the occluders its corners met
// first (one primitive each) measured slower than tracing (gears_s4 2048x2048:
// 3.27/3.15/2.79 s against 2.71/2.76/2.40 s).
int cached_visibility(const RenderContext& scene, const HitFrame& f, const SurfacePoint& sp, const CellRef& cell,
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

CellRef cell_of(const RenderContext& scene, const SurfacePoint& sp) {
  const ShadowCache* cache = scene.shadow_cache();
  return cache ? cache->locate(sp) : CellRef::none();
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

// secondary_rays() of a glTF material, out of line as gltf_contribution().
[[gnu::noinline]] SecondaryRays gltf_secondary_rays(const RenderContext& scene, const Ray& ray, const SurfacePoint& sp,
                                                    const HitFrame& f) {
  SecondaryRays s;
  const Material& m = *f.m;
  if (sp.roughness < kMirrorRoughness) {
    s.mirror = true;
    s.mirror_ray = mirror_ray_of(ray, f);
    s.mirror_weight = gltf_mirror_weight(gltf_surface(f, sp), dot(f.ns, f.view)) * (1 - m.transmittance);
  }
  // BLEND's uncovered share and KHR_materials_transmission's share of the
  // covered part both go straight through: one ray, their weights summed.
  const Vec3 transmitted = m.transmission > 0 ? gltf_transmit_weight(gltf_surface(f, sp), dot(f.ns, f.view)) : Vec3{};
  if (m.transmittance > 0 || m.transmission > 0) {
    s.transmit = true;
    s.transmit_ray = Ray{sp.position - f.ng * scene.epsilon(), ray.dir, 0, INFINITY};
    s.transmit_weight = Vec3{1, 1, 1} * m.transmittance + transmitted * (1 - m.transmittance);
  }
  return s;
}

// Whether secondary_rays() can give a ray for material `m` at all (a glTF
// material's depends on its texel's roughness: assumed yes).
inline bool may_cast_secondary(const Material& m) {
  return m.model == ShadingModel::gltf || m.ks > 0 || m.transmittance > 0;
}

// What gltf_secondary_rays() gives at `sp`, asked without building its
// record: a mirror ray below kMirrorRoughness, a transmitted one where any
// light goes through. A rough opaque glTF lane (most of a glTF scene) then
// costs the packet's secondary passes nothing (lit_spheres.gltf: 4 % of its
// cycles went to zeroing and copying empty records).
inline bool gltf_mirrors(const SurfacePoint& sp) { return sp.roughness < kMirrorRoughness; }
inline bool gltf_transmits(const Material& m) { return m.transmittance > 0 || m.transmission > 0; }

// The mirror ray of an NFF or blinn_phong material (Ks > 0), weighted Ks:
// false when it casts none. Written into `out` (no temporary: a packet's
// lanes are filled in place).
[[gnu::always_inline]] inline bool nff_mirror(const Ray& ray, const HitFrame& f, Ray& out, Vec3& weight) {
  const Material& m = *f.m;
  if (!(m.ks > 0)) return false;
  out = mirror_ray_of(ray, f);
  weight = Vec3{m.ks, m.ks, m.ks};
  return true;
}

// The transmitted ray of an NFF or blinn_phong material (T > 0), weighted T:
// refracted by Snell's law, or on total internal reflection (`reflects`) a
// second mirror ray; false when it casts none.
[[gnu::always_inline]] inline bool nff_transmit(const RenderContext& scene, const Ray& ray, const SurfacePoint& sp,
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

SecondaryRays secondary_rays(const RenderContext& scene, const Ray& ray, const SurfacePoint& sp, const HitFrame& f) {
  if (f.m->model == ShadingModel::gltf) [[unlikely]]
    return gltf_secondary_rays(scene, ray, sp, f);
  SecondaryRays s;
  s.mirror = nff_mirror(ray, f, s.mirror_ray, s.mirror_weight);
  s.transmit = nff_transmit(scene, ray, sp, f, s.transmit_ray, s.transmit_weight, s.transmit_reflects);
  return s;
}

// Adds mirror and transmitted light to `colour`, traced one ray at a time (incoherent).
void add_secondary(const RenderContext& scene, const Ray& ray, const SurfacePoint& sp, const HitFrame& f, int depth,
                   RayCounts& counts, Vec3& colour) {
  if (depth >= scene.max_depth()) return;
  const SecondaryRays s = secondary_rays(scene, ray, sp, f);
  if (s.mirror) {
    ++counts.reflected;
    colour += mul(trace(scene, s.mirror_ray, depth + 1, counts), s.mirror_weight);
  }
  if (s.transmit) {
    ++(s.transmit_reflects ? counts.reflected : counts.refracted);
    colour += mul(trace(scene, s.transmit_ray, depth + 1, counts), s.transmit_weight);
  }
}

}  // namespace

namespace {

// Tachyon ignores a term below half an 8-bit step (MINCONTRIB).
constexpr double kMinContrib = 0.5 / 255;

// Tachyon's light toward a hit (light.c): the unit direction to the light,
// the distance to it and N.L times attenuation and spot falloff.
struct LightRay {
  Vec3 to_light;
  double distance = INFINITY;
  double intensity = 0;
};

LightRay tachyon_light(const PointLight& light, const Vec3& p, const Vec3& n) {
  LightRay r;
  if (light.kind == LightKind::directional) {
    r.to_light = -light.direction;
    r.intensity = dot(n, r.to_light);
    return r;
  }
  const Vec3 d = light.position - p;
  r.distance = length(d);
  if (!(r.distance > 0)) return r;
  r.to_light = d / r.distance;
  r.intensity = dot(n, r.to_light) / (light.kc + (light.kl + light.kq * r.distance) * r.distance);
  if (light.kind == LightKind::spot) {
    const double angle = std::acos(std::clamp(-dot(light.direction, r.to_light), -1.0, 1.0));
    if (angle > light.fall_end) r.intensity = 0;
    else if (angle > light.fall_start) r.intensity *= 1 - (angle - light.fall_start) / (light.fall_end - light.fall_start);
  }
  return r;
}

// Tachyon 0.99's full_shader (shade.c; docs/tachyon-notes.md §3):
//   C = T * (ambient + diffuse * sum_lights Il N.L) + sum_lights phong * Il' (N.H)^e
//       + specular * I_reflected + (1 - opacity) * I_straight_through
// with T the texture colour, H Blinn's half vector (Tachyon's default
// highlight), Il' the light colour (plastic) or T (metal), both normals
// turned to the viewer; past the depth limit a secondary ray sees the background.
// How much of a light a Tachyon shadow ray lets through: 0 when an opaque
// surface blocks it, else the product of (1 - opacity) over the transparent
// surfaces it crosses (Tachyon's shadow filter; a surface with opacity < 1
// casts no shadow of its own). Lights' spheres are passed through.
double tachyon_shadow(const RenderContext& scene, Ray shadow, RayCounts& counts) {
  ++counts.shadow;
  if (!scene.has_tachyon_transparency()) return scene.accel().occluded(shadow) ? 0 : 1;
  double filter = 1;
  Hit h;
  // Each step starts past the last hit; the cap stops a ray grazing a stack
  // of coincident surfaces (past it, the light counts as blocked).
  for (int step = 0; step < 64; ++step) {
    if (!scene.accel().intersect(shadow, h)) return filter;
    const Material& m = *scene.surface(shadow, h).material;
    if (!m.emitter) {
      if (m.model != ShadingModel::tachyon || !(m.transmittance > 0)) return 0;
      filter *= m.transmittance;
      if (filter < kMinContrib) return 0;
    }
    shadow.tnear = std::fmax(h.t, shadow.tnear) + scene.epsilon();
    if (!(shadow.tnear < shadow.tfar)) return filter;
    ++counts.shadow;
  }
  return 0;
}

// One hit's Tachyon shading in three steps, so that a packet of hits can
// trace its shadow rays together between the first and the last and still
// give each lane the bits of shade_tachyon().
struct TachyonHit {
  HitFrame f;
  Vec3 dir, texel, diffuse, highlight;
  bool lit = false;  // its diffuse or highlight weight needs the lights
};

TachyonHit tachyon_begin(const RenderContext& scene, const Ray& ray, const SurfacePoint& sp) {
  TachyonHit t;
  t.f = frame_of(scene, ray, sp);
  t.dir = normalize(ray.dir);
  t.texel = scene.surface_colour(sp, length(sp.position - ray.org));
  t.lit = !t.f.m->emitter && (t.f.m->kd > kMinContrib || t.f.m->phong > kMinContrib);
  return t;
}

// The light's terms, once its shadow ray let `seen` of it through.
void tachyon_add_light(TachyonHit& t, const PointLight& light, const LightRay& l, double seen) {
  const Material& m = *t.f.m;
  const double inten = l.intensity * seen;
  t.diffuse += light.intensity * inten;
  if (m.phong > kMinContrib) {
    const Vec3 h = l.to_light - t.dir;
    double spec = dot(t.f.ns, h);
    if (spec > kMinContrib) {
      spec = std::pow(spec / length(h), m.shine) * m.phong;
      t.highlight += (m.phong_metal ? t.texel : light.intensity) * spec;
    }
  }
}

Ray tachyon_shadow_ray(const RenderContext& scene, const TachyonHit& t, const LightRay& l) {
  return Ray{t.f.above, l.to_light, 0, l.distance - scene.epsilon()};
}

Vec3 tachyon_finish(const RenderContext& scene, const Ray& ray, const SurfacePoint& sp, const TachyonHit& t, int depth,
                    RayCounts& counts) {
  const Material& m = *t.f.m;
  if (m.emitter) return t.texel;
  Vec3 colour = mul(t.texel, t.diffuse * m.kd + Vec3{m.ambient, m.ambient, m.ambient}) + t.highlight;
  auto secondary = [&](const Ray& r, double weight) {
    if (depth >= scene.max_depth()) return scene.background() * weight;
    return trace(scene, r, depth + 1, counts) * weight;
  };
  if (m.ks > kMinContrib) {
    ++counts.reflected;
    colour += secondary(Ray{t.f.above, normalize(reflect(t.dir, t.f.ns)), 0, INFINITY}, m.ks);
  }
  if (m.transmittance > kMinContrib) {
    ++counts.refracted;
    colour += secondary(Ray{sp.position - t.f.ng * scene.epsilon(), t.dir, 0, INFINITY}, m.transmittance);
  }
  if (const auto& fog = scene.fog()) {
    const double r = length(sp.position - ray.org);
    double k = 1;
    switch (fog->mode) {
      case FogDesc::Mode::linear: k = (fog->end - r) / (fog->end - fog->start); break;
      case FogDesc::Mode::exp: k = std::exp(-fog->density * (r - fog->start)); break;
      case FogDesc::Mode::exp2: {
        const double v = fog->density * (r - fog->start);
        k = std::exp(-v * v);
        break;
      }
    }
    k = std::clamp(k, 0.0, 1.0);
    colour = colour * k + fog->colour * (1 - k);
  }
  return colour;
}

Vec3 shade_tachyon(const RenderContext& scene, const Ray& ray, const SurfacePoint& sp, int depth, RayCounts& counts) {
  TachyonHit t = tachyon_begin(scene, ray, sp);
  if (t.lit) {
    for (const PointLight& light : scene.lights()) {
      const LightRay l = tachyon_light(light, sp.position, t.f.ns);
      if (!(l.intensity > kMinContrib)) continue;
      const double seen = tachyon_shadow(scene, tachyon_shadow_ray(scene, t, l), counts);
      if (seen != 0) tachyon_add_light(t, light, l, seen);
    }
  }
  return tachyon_finish(scene, ray, sp, t, depth, counts);
}

// shade_tachyon() for the lanes of a packet with tachyon[k] set: the shadow
// rays toward each light go as one packet (rtcOccluded16) unless the scene
// has transparent surfaces, whose filtering walks each ray on its own.
void shade_tachyon(const RenderContext& scene, const RayPacket& rays, const bool tachyon[kPacketSize],
                   const SurfacePoint sps[kPacketSize], int depth, RayCounts& counts, Vec3 colours[kPacketSize]) {
  TachyonHit t[kPacketSize];
  for (int k = 0; k < kPacketSize; ++k)
    if (tachyon[k]) t[k] = tachyon_begin(scene, rays.rays[k], sps[k]);
  const bool filtered = scene.has_tachyon_transparency();
  RayPacket shadows;
  LightRay l[kPacketSize];
  bool blocked[kPacketSize];
  for (const PointLight& light : scene.lights()) {
    int cast = 0;
    for (int k = 0; k < kPacketSize; ++k) {
      shadows.active[k] = false;
      if (!tachyon[k] || !t[k].lit) continue;
      l[k] = tachyon_light(light, sps[k].position, t[k].f.ns);
      if (!(l[k].intensity > kMinContrib)) continue;
      if (filtered) {
        const double seen = tachyon_shadow(scene, tachyon_shadow_ray(scene, t[k], l[k]), counts);
        if (seen != 0) tachyon_add_light(t[k], light, l[k], seen);
        continue;
      }
      shadows.rays[k] = tachyon_shadow_ray(scene, t[k], l[k]);
      shadows.active[k] = true;
      ++cast;
    }
    if (cast == 0) continue;
    counts.shadow += static_cast<uint64_t>(cast);
    scene.accel().occluded(shadows, blocked);
    for (int k = 0; k < kPacketSize; ++k)
      if (shadows.active[k] && !blocked[k]) tachyon_add_light(t[k], light, l[k], 1.0);
  }
  for (int k = 0; k < kPacketSize; ++k)
    if (tachyon[k]) colours[k] = tachyon_finish(scene, rays.rays[k], sps[k], t[k], depth, counts);
}

}  // namespace

Vec3 shade(const RenderContext& scene, const Ray& ray, const SurfacePoint& sp, int depth, RayCounts& counts) {
  if (sp.material->model == ShadingModel::tachyon) return shade_tachyon(scene, ray, sp, depth, counts);
  const HitFrame f = frame_of(scene, ray, sp);
  Vec3 colour = ambient_term(scene, f);
  add_emission(scene, ray, sp, colour);
  const bool cached = scene.shadow_cache() != nullptr;
  const CellRef cell = cached ? cell_of(scene, sp) : CellRef::none();
  const auto& lights = scene.lights();
  for (size_t l = 0; l < lights.size(); ++l) {
    Ray shadow;
    double falloff;
    if (!shadow_ray(scene, f, sp, lights[l], shadow, falloff)) continue;
    int seen = cached ? cached_visibility(scene, f, sp, cell, static_cast<int>(l), shadow, counts) : -1;
    if (seen < 0) {
      ++counts.shadow;
      seen = !scene.accel().occluded(shadow);
    }
    if (seen) colour += light_contribution(f, sp, lights[l], shadow.dir, falloff);
  }
  add_secondary(scene, ray, sp, f, depth, counts, colour);
  return colour;
}

namespace {

// The colour seen along each active lane of `rays` at ray-tree `depth`:
// traced as one packet, the hits shaded as a packet. Only nearly parallel
// rays come here, and Embree's coherent (frustum) traversal takes them
// faster (teapot_s6 0.907x, gears_s4 0.951x the whole command); it does not
// agree with the single-ray kernel on every ray (gears: 1 mirror ray in 2 M
// found another surface), which the image budget allows.
void trace_packet(const RenderContext& scene, const RayPacket& rays, int depth, RayCounts& counts,
                  Vec3 colours[kPacketSize]) {
  Hit hits[kPacketSize];
  bool found[kPacketSize] = {};
  scene.accel().intersect(rays, hits, found, RayCoherence::coherent, !scene.only_plain_nff());
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

// trace() for a packet's secondary ray: in a scene of plain NFF materials
// with Embree's float hit (RenderScene::only_plain_nff).
Vec3 trace_secondary(const RenderContext& scene, const Ray& ray, int depth, RayCounts& counts) {
  Hit hit;
  if (!scene.accel().intersect(ray, hit, RayCoherence::incoherent, !scene.only_plain_nff())) return scene.background();
  return shade(scene, ray, scene.surface(ray, hit), depth, counts);
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
void add_secondary(const RenderContext& scene, const RayPacket& rays, const bool hit[kPacketSize],
                   const SurfacePoint sps[kPacketSize], const HitFrame f[kPacketSize], int depth, RayCounts& counts,
                   Vec3 colours[kPacketSize]) {
  if (depth >= scene.max_depth()) return;
  // Most NFF surfaces are matte: their packets skip building 16 empty ray
  // pairs (tree_s11, all matte: 4 % of its cycles went there).
  bool any = false;
  for (int k = 0; k < kPacketSize; ++k)
    any |= hit[k] && (f[k].m->model == ShadingModel::gltf ? gltf_mirrors(sps[k]) || gltf_transmits(*f[k].m)
                                                          : may_cast_secondary(*f[k].m));
  if (!any) return;
  RayPacket next;
  Vec3 weight[kPacketSize];
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
        if (next.active[k]) colours[k] += mul(trace_secondary(scene, next.rays[k], depth + 1, counts), weight[k]);
      return;
    }
    Vec3 seen[kPacketSize];
    trace_packet(scene, next, depth + 1, counts, seen);
    for (int k = 0; k < kPacketSize; ++k)
      if (next.active[k]) colours[k] += mul(seen[k], weight[k]);
  };
  // Each lane's rays are written straight into the packet, the mirror rays
  // first (copying whole SecondaryRays records stalled on store forwarding:
  // teapot_s6 spent 4 % of its cycles there). A glTF lane's come from
  // gltf_secondary_rays, asked once per pass.
  for (int k = 0; k < kPacketSize; ++k) {
    next.active[k] = false;
    if (!hit[k]) continue;
    if (f[k].m->model == ShadingModel::gltf) [[unlikely]] {
      if (!gltf_mirrors(sps[k])) continue;
      const SecondaryRays g = gltf_secondary_rays(scene, rays.rays[k], sps[k], f[k]);
      if ((next.active[k] = g.mirror)) next.rays[k] = g.mirror_ray, weight[k] = g.mirror_weight;
    } else {
      next.active[k] = nff_mirror(rays.rays[k], f[k], next.rays[k], weight[k]);
    }
    counts.reflected += next.active[k];
  }
  flush();
  for (int k = 0; k < kPacketSize; ++k) {
    next.active[k] = false;
    if (!hit[k]) continue;
    bool reflects = false;
    if (f[k].m->model == ShadingModel::gltf) [[unlikely]] {
      if (!gltf_transmits(*f[k].m)) continue;
      const SecondaryRays g = gltf_secondary_rays(scene, rays.rays[k], sps[k], f[k]);
      if ((next.active[k] = g.transmit)) next.rays[k] = g.transmit_ray, weight[k] = g.transmit_weight;
      reflects = g.transmit_reflects;
    } else {
      next.active[k] = nff_transmit(scene, rays.rays[k], sps[k], f[k], next.rays[k], weight[k], reflects);
    }
    if (next.active[k]) ++(reflects ? counts.reflected : counts.refracted);
  }
  flush();
}

}  // namespace

Vec3 shade_local(const RenderContext& scene, const Ray& ray, const SurfacePoint& sp, uint32_t lit, uint32_t trace,
                 RayCounts& counts) {
  const HitFrame f = frame_of(scene, ray, sp);
  Vec3 colour = ambient_term(scene, f);
  add_emission(scene, ray, sp, colour);
  const auto& lights = scene.lights();
  for (size_t l = 0; l < lights.size() && l < kMaxPartLights; ++l) {
    const bool traced = trace >> l & 1u;
    if (!traced && !(lit >> l & 1u)) continue;
    Ray shadow;
    double falloff;
    if (!shadow_ray(scene, f, sp, lights[l], shadow, falloff)) continue;
    if (traced) {
      ++counts.shadow;
      if (scene.accel().occluded(shadow)) continue;
    }
    colour += light_contribution(f, sp, lights[l], shadow.dir, falloff);
  }
  return colour;
}

Vec3 shade_secondary(const RenderContext& scene, const Ray& ray, const SurfacePoint& sp, int depth, RayCounts& counts) {
  Vec3 colour;
  add_secondary(scene, ray, sp, frame_of(scene, ray, sp), depth, counts, colour);
  return colour;
}

void shade_secondary(const RenderContext& scene, const RayPacket& rays, const bool hit[kPacketSize],
                     const SurfacePoint sps[kPacketSize], int depth, RayCounts& counts, Vec3 colours[kPacketSize]) {
  HitFrame f[kPacketSize];
  for (int k = 0; k < kPacketSize; ++k)
    if (hit[k]) f[k] = frame_of(scene, rays.rays[k], sps[k]);
  add_secondary(scene, rays, hit, sps, f, depth, counts, colours);
}

namespace {

// What every light's shadow rays need of a packet's lanes, one array per
// coordinate, gathered once per packet: the hit points, the shading normals
// and the shadow rays' origins (already rounded to Embree's floats).
struct LaneGeometry {
  alignas(64) double px[kPacketSize], py[kPacketSize], pz[kPacketSize];
  alignas(64) double nx[kPacketSize], ny[kPacketSize], nz[kPacketSize];
  float origin[kPacketSize][3];

  void gather(const bool hit[kPacketSize], const SurfacePoint sps[kPacketSize], const HitFrame f[kPacketSize]) {
    for (int k = 0; k < kPacketSize; ++k) {
      // Missed lanes get harmless values: every lane is computed, the hit ones kept.
      const Vec3 p = hit[k] ? sps[k].position : Vec3{}, n = hit[k] ? f[k].ns : Vec3{}, o = hit[k] ? f[k].above : Vec3{};
      px[k] = p.x, py[k] = p.y, pz[k] = p.z, nx[k] = n.x, ny[k] = n.y, nz[k] = n.z;
      origin[k][0] = static_cast<float>(o.x), origin[k][1] = static_cast<float>(o.y), origin[k][2] = static_cast<float>(o.z);
    }
  }
};

// One point light of unit falloff (NFF's) for a packet's lanes without the
// shadow cache: shadow_ray<true>()'s arithmetic, each operation the same as
// there and in the same order (the same bits as the RayPacket path), on
// every lane without a branch, the rays written straight into Embree's
// 16-wide layout instead of a RayPacket of doubles that occluded() then
// converts, each origin rounded once per packet, not once per light. GCC
// leaves the loop scalar: the gain is the branches and conversions saved.
template <class MarkLit>
void shade_point_light(const RenderContext& scene, const bool hit[kPacketSize], const LaneGeometry& g,
                       const SurfacePoint sps[kPacketSize],
                       const HitFrame f[kPacketSize], size_t l, RayCounts& counts, Vec3 colours[kPacketSize],
                       MarkLit&& mark_lit) {
  const PointLight& light = scene.lights()[l];
  const double eps = scene.epsilon();
  const double lx = light.position.x, ly = light.position.y, lz = light.position.z;
  ShadowPacket shadows;
  alignas(64) double ux[kPacketSize], uy[kPacketSize], uz[kPacketSize];
  for (int k = 0; k < kPacketSize; ++k) {
    const double dx = lx - g.px[k], dy = ly - g.py[k], dz = lz - g.pz[k];
    const double dist = std::sqrt(dx * dx + dy * dy + dz * dz);
    const double inv = 1.0 / dist;
    ux[k] = dx * inv, uy[k] = dy * inv, uz[k] = dz * inv;
    const double n_dot_l = g.nx[k] * ux[k] + g.ny[k] * uy[k] + g.nz[k] * uz[k];
    shadows.set(k, g.origin[k], Vec3{ux[k], uy[k], uz[k]}, dist - eps, hit[k] & (dist > eps) & !(n_dot_l <= 0));
  }
  int cast = 0;
  for (int k = 0; k < kPacketSize; ++k) cast += shadows.valid[k] != 0;
  if (cast == 0) return;
  counts.shadow += static_cast<uint64_t>(cast);
  bool blocked[kPacketSize];
  scene.accel().occluded(shadows, blocked);
  for (int k = 0; k < kPacketSize; ++k)
    if (shadows.valid[k] && !blocked[k])
      colours[k] += light_contribution(f[k], sps[k], light, Vec3{ux[k], uy[k], uz[k]}, 1.0), mark_lit(k, l);
}

// The lanes of a packet for its point lights of unit falloff: as an
// NffLanes batch when every hit lane's material is NFF's (true), else as
// LaneGeometry for shade_point_light (false).
bool gather_lanes(const bool hit[kPacketSize], const SurfacePoint sps[kPacketSize],
                  const HitFrame f[kPacketSize], NffLanes& batch, LaneGeometry& lanes) {
  for (int k = 0; k < kPacketSize; ++k)
    if (hit[k] && f[k].m->model != ShadingModel::nff) {
      lanes.gather(hit, sps, f);
      return false;
    }
  for (int k = 0; k < kPacketSize; ++k) {
    if (!hit[k]) {
      batch.clear(k);
      continue;
    }
    const Material& m = *f[k].m;
    batch.set(k, sps[k].position, f[k].ns, f[k].above, f[k].view, f[k].colour * m.kd, m.ks, m.shine);
  }
  return true;
}

// One light for a packet's lanes gathered as a float batch, without the
// shadow cache: NFF's point lights of unit falloff (NffLanes,
// light_batch.hpp) or glTF's lights that can_batch() (GltfLanes,
// gltf_batch.hpp). The shadow rays go as one packet; the lanes it reaches
// get the light's term and, with `parts`, its bit.
template <class Lanes>
void shade_batched_light(const RenderContext& scene, const Lanes& batch, size_t l, RayCounts& counts,
                         Vec3 colours[kPacketSize], ShadeParts parts[]) {
  constexpr bool nff = std::is_same_v<Lanes, NffLanes>;
  const PointLight& light = scene.lights()[l];
  ShadowPacket shadows;
  std::conditional_t<nff, NffLightRays, GltfLightRays> rays;
  int cast;
  if constexpr (nff) cast = nff_shadow_rays(batch, light.position, scene.epsilon(), shadows, rays);
  else cast = gltf_shadow_rays(batch, light, scene.epsilon(), shadows, rays);
  if (cast == 0) return;
  counts.shadow += static_cast<uint64_t>(cast);
  bool blocked[kPacketSize];
  scene.accel().occluded(shadows, blocked);
  bool seen[kPacketSize];
  for (int k = 0; k < kPacketSize; ++k) seen[k] = (shadows.valid[k] != 0) & !blocked[k];
  if constexpr (nff) add_nff_light(batch, rays, seen, light.intensity, colours);
  else add_gltf_light(batch, rays, seen, light.intensity, colours);
  if (parts && l < kMaxPartLights)
    for (int k = 0; k < kPacketSize; ++k) parts[k].lit |= static_cast<uint32_t>(seen[k]) << l;
}

}  // namespace

void shade(const RenderContext& scene, const RayPacket& rays, const bool hit_in[kPacketSize],
           const SurfacePoint sps[kPacketSize], int depth, RayCounts& counts, Vec3 colours[kPacketSize],
           ShadeParts parts[kPacketSize]) {
  // Tachyon materials take their own packet path; the NFF lanes go on below.
  bool hit[kPacketSize], tachyon[kPacketSize];
  bool any_tachyon = false;
  for (int k = 0; k < kPacketSize; ++k) {
    tachyon[k] = hit_in[k] && sps[k].material->model == ShadingModel::tachyon;
    hit[k] = hit_in[k] && !tachyon[k];
    any_tachyon |= tachyon[k];
  }
  if (any_tachyon) shade_tachyon(scene, rays, tachyon, sps, depth, counts, colours);
  if (parts)
    for (int k = 0; k < kPacketSize; ++k) parts[k] = ShadeParts{};
  auto mark_lit = [&](int k, size_t l) {
    if (parts && l < kMaxPartLights) parts[k].lit |= 1u << l;
  };
  HitFrame f[kPacketSize];
  CellRef cells[kPacketSize];  // set and read only when there is a cache
  const bool cached = scene.shadow_cache() != nullptr;
  for (int k = 0; k < kPacketSize; ++k) {
    if (!hit[k]) continue;
    f[k] = frame_of(scene, rays.rays[k], sps[k]);
    colours[k] = ambient_term(scene, f[k]);
    add_emission(scene, rays.rays[k], sps[k], colours[k]);
    if (cached) cells[k] = cell_of(scene, sps[k]);
  }
  // The shadow rays of one packet toward one light share their end point:
  // traced together as a packet.
  RayPacket shadows;
  bool blocked[kPacketSize];
  double falloff[kPacketSize];
  const auto& lights = scene.lights();
  LaneGeometry lanes;  // gathered for the first point light of unit falloff
  NffLanes batch;      // the same, when every lane's material is NFF's
  enum { not_yet, double_lanes, float_batch } gathered = not_yet;
  // One light's lanes; `Unit` as shadow_ray's.
  auto shade_light = [&]<bool Unit>(size_t l, std::bool_constant<Unit>) {
    if constexpr (Unit) {
      if (!cached) {
        if (gathered == not_yet) gathered = gather_lanes(hit, sps, f, batch, lanes) ? float_batch : double_lanes;
        if (gathered == float_batch) shade_batched_light(scene, batch, l, counts, colours, parts);
        else shade_point_light(scene, hit, lanes, sps, f, l, counts, colours, mark_lit);
        return;
      }
    }
    int cast = 0;
    for (int k = 0; k < kPacketSize; ++k) {
      shadows.active[k] = hit[k] && shadow_ray<Unit>(scene, f[k], sps[k], lights[l], shadows.rays[k], falloff[k]);
      if (!shadows.active[k]) continue;
      if (!cached) {
        ++cast;
        continue;
      }
      const int seen = cached_visibility(scene, f[k], sps[k], cells[k], static_cast<int>(l), shadows.rays[k], counts);
      if (seen >= 0) {
        if (seen) colours[k] += light_contribution(f[k], sps[k], lights[l], shadows.rays[k].dir, falloff[k]), mark_lit(k, l);
        shadows.active[k] = false;
        continue;
      }
      ++cast;
    }
    if (cast == 0) return;
    counts.shadow += static_cast<uint64_t>(cast);
    scene.accel().occluded(shadows, blocked);
    for (int k = 0; k < kPacketSize; ++k)
      if (shadows.active[k] && !blocked[k])
        colours[k] += light_contribution(f[k], sps[k], lights[l], shadows.rays[k].dir, falloff[k]), mark_lit(k, l);
  };
  // Every hit lane glTF's (no shadow cache): the lights go as float batches.
  bool gltf_packet = !cached, any_hit = false;
  for (int k = 0; k < kPacketSize; ++k)
    if (hit[k]) gltf_packet &= f[k].m->model == ShadingModel::gltf, any_hit = true;
  gltf_packet &= any_hit;
  GltfLanes gltf_lanes;
  if (gltf_packet)
    for (int k = 0; k < kPacketSize; ++k) {
      if (hit[k]) gltf_lanes.set(k, sps[k].position, f[k].ns, f[k].above, f[k].view, gltf_surface(f[k], sps[k]),
                                 f[k].m->transmittance);
      else gltf_lanes.clear(k);
    }
  for (size_t l = 0; l < lights.size(); ++l) {
    if (gltf_packet && can_batch(lights[l])) shade_batched_light(scene, gltf_lanes, l, counts, colours, parts);
    else if (lights[l].unit_falloff) shade_light(l, std::true_type{});
    else shade_light(l, std::false_type{});
  }
  if (!parts) {
    add_secondary(scene, rays, hit, sps, f, depth, counts, colours);
    return;
  }
  // The secondary light as the difference, so that the colour is added up
  // in the same order as without parts (bit for bit the same image).
  Vec3 local[kPacketSize];
  std::copy(colours, colours + kPacketSize, local);
  add_secondary(scene, rays, hit, sps, f, depth, counts, colours);
  for (int k = 0; k < kPacketSize; ++k) {
    if (!hit[k]) continue;
    const Vec3 s = colours[k] - local[k];
    parts[k].secondary[0] = static_cast<float>(s.x), parts[k].secondary[1] = static_cast<float>(s.y),
    parts[k].secondary[2] = static_cast<float>(s.z);
  }
}

}  // namespace holoray
