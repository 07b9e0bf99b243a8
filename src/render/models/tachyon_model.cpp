#include "render/models/tachyon_model.hpp"

#include <algorithm>

#include "render/shading.hpp"

namespace holoray::shading {

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
// give each lane the bits of TachyonModel::shade().
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

}  // namespace

Vec3 TachyonModel::shade(const RenderContext& scene, const Ray& ray, const SurfacePoint& sp, int depth, RayCounts& counts) {
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

void TachyonModel::shade(const RenderContext& scene, const RayPacket& rays, const bool tachyon[kPacketSize],
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


}  // namespace holoray::shading
