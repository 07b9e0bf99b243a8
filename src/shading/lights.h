// holoray/shading: how much of a light reaches a point, for both devices.
// Units (docs/lights.md): a light's colour is the radiance a white
// Lambertian surface facing it shows at unit falloff, so a point or
// directional light of colour I gives a surface the irradiance
// pi I falloff cos(theta), and its reflected radiance is f pi I falloff cos.
#ifndef HOLORAY_SHADING_LIGHTS_H
#define HOLORAY_SHADING_LIGHTS_H

#include "shading/common.h"
#include "shading/warp.h"

// Light kinds, as scene_desc.hpp's LightKind (and gpu/shaders/layout.h's HR_LIGHT_*).
#define HR_LIGHT_KIND_POINT 0
#define HR_LIGHT_KIND_DIRECTIONAL 1
#define HR_LIGHT_KIND_SPOT 2

HR_BEGIN

/// A point, spot or directional light's falloff parameters (scene_desc.hpp,
/// Light; render_scene.hpp, PointLight): attenuation 1 / (kc + kl d + kq d^2),
/// KHR_lights_punctual's range window, and the spot cone: linear in the
/// angle between fall_start and fall_end (Tachyon), or the extension's
/// smooth square in the cosine (`smooth_cone`).
struct HrLightFalloff {
  int kind;
  vec3 direction;  ///< where the light travels (spot axis, directional), unit
  float kc, kl, kq, range;
  float fall_start, fall_end;  ///< radians off the axis
  float cos_fall_start, cos_fall_end;
  bool smooth_cone;
  bool unit;  ///< NFF's lights: no falloff at all
};

/// The falloff toward a point `dist` away along `to_light` (unit, from the
/// point toward the light): 1 for NFF's and directional lights.
HR_FN float hr_light_falloff(HrLightFalloff l, vec3 to_light, float dist) {
  if (l.unit || l.kind == HR_LIGHT_KIND_DIRECTIONAL) return 1.0f;
  float a = 1.0f;
  if (l.kc != 1.0f || l.kl != 0.0f || l.kq != 0.0f) a = 1.0f / (l.kc + (l.kl + l.kq * dist) * dist);
  if (l.range > 0.0f) {
    float x2 = (dist / l.range) * (dist / l.range);
    float w = clamp(1.0f - x2 * x2, 0.0f, 1.0f);
    a *= w * w;
  }
  if (l.kind == HR_LIGHT_KIND_SPOT) {
    float cos_a = -dot(l.direction, to_light);
    if (l.smooth_cone) {
      float t = clamp((cos_a - l.cos_fall_end) / max(1.0e-3f, l.cos_fall_start - l.cos_fall_end), 0.0f, 1.0f);
      a *= t * t;
    } else {
      float angle = acos(clamp(cos_a, -1.0f, 1.0f));
      if (angle > l.fall_end) a = 0.0f;
      else if (angle > l.fall_start) a *= 1.0f - (angle - l.fall_start) / (l.fall_end - l.fall_start);
    }
  }
  return a;
}

/// A point drawn uniformly on an area light (centre c, half-extent axes u
/// and v; an ellipse inscribed in the rectangle when `ellipse`), from a
/// uniform pair.
HR_FN vec3 hr_area_light_point(vec3 c, vec3 u, vec3 v, bool ellipse, vec2 r) {
  vec2 d = ellipse ? hr_concentric_disk(r) : vec2(2.0f * r.x - 1.0f, 2.0f * r.y - 1.0f);
  return c + u * d.x + v * d.y;
}

/// Where the ray o + t d (d unit) meets an area light (as above, its normal
/// n), for t in (0, t_max); -1 when it misses. Both sides are met: the
/// caller asks which one (a light is one-sided).
HR_FN float hr_area_light_hit(vec3 o, vec3 d, float t_max, vec3 c, vec3 u, vec3 v, vec3 n, bool ellipse) {
  float dn = dot(d, n);
  if (abs(dn) < 1.0e-12f) return -1.0f;
  float t = dot(c - o, n) / dn;
  if (!(t > 0.0f && t < t_max)) return -1.0f;
  vec3 q = o + d * t - c;
  float a = dot(q, u) / dot(u, u);
  float b = dot(q, v) / dot(v, v);
  bool inside = ellipse ? a * a + b * b <= 1.0f : abs(a) <= 1.0f && abs(b) <= 1.0f;
  return inside ? t : -1.0f;
}

/// A point drawn uniformly on the disk of radius r centred on a light at
/// `centre`, facing the lit point along `to_point` (unit): a point or spot
/// light with a radius, as Cycles draws one.
HR_FN vec3 hr_disk_light_point(vec3 centre, vec3 to_point, float r, vec2 u) {
  vec3 t;
  vec3 b;
  hr_frame(to_point, t, b);
  vec2 d = hr_concentric_disk(u);
  return centre + (t * d.x + b * d.y) * r;
}

HR_END

#endif
