// holoray/shading: how much of a light reaches a point, for both devices.
// Units (docs/lights.md): a light's colour is the radiance a white
// Lambertian surface facing it shows at unit falloff, so a point or
// directional light of colour I gives a surface the irradiance
// pi I falloff cos(theta), and its reflected radiance is f pi I falloff cos.
#ifndef HOLORAY_SHADING_LIGHTS_H
#define HOLORAY_SHADING_LIGHTS_H

#include "shading/common.h"

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

HR_END

#endif
