// holoray/render: a light's falloff as the shared function computes it
// (shading/lights.h, hr_light_falloff): Whitted's shading, the path
// integrator and the GPU kernel (gpu/shaders/trace.comp) all call that one
// text, in float.
#pragma once

#include "render/render_scene.hpp"
#include "render/shading_vec.hpp"
#include "shading/lights.h"

namespace holoray {

/// `light`'s attenuation, range and spot cone as hr_light_falloff takes them.
inline shading::HrLightFalloff falloff_params(const PointLight& light) {
  shading::HrLightFalloff f;
  f.kind = static_cast<int>(light.kind);
  f.direction = to_f(light.direction);
  f.kc = static_cast<float>(light.kc), f.kl = static_cast<float>(light.kl), f.kq = static_cast<float>(light.kq);
  f.range = static_cast<float>(light.range);
  f.fall_start = static_cast<float>(light.fall_start), f.fall_end = static_cast<float>(light.fall_end);
  f.cos_fall_start = static_cast<float>(light.cos_fall_start), f.cos_fall_end = static_cast<float>(light.cos_fall_end);
  f.smooth_cone = light.smooth_cone;
  f.unit = light.unit_falloff;
  return f;
}

/// The falloff of `light` toward a point `dist` away along `to_light`
/// (unit, from the point toward the light; world).
inline double light_falloff(const PointLight& light, const Vec3& to_light, double dist) {
  return shading::hr_light_falloff(falloff_params(light), to_f(to_light), static_cast<float>(dist));
}

}  // namespace holoray
