// holoray/shading: uniform numbers in [0, 1)^2 warped to directions, and
// the weights that combine sampling strategies. Shared by both devices.
#ifndef HOLORAY_SHADING_WARP_H
#define HOLORAY_SHADING_WARP_H

#include "shading/common.h"

HR_BEGIN

/// The unit disk, area-preserving and low-distortion (Shirley and Chiu 1997,
/// the concentric map).
HR_FN vec2 hr_concentric_disk(vec2 u) {
  float a = 2.0f * u.x - 1.0f, b = 2.0f * u.y - 1.0f;
  if (a == 0.0f && b == 0.0f) return vec2(0.0f, 0.0f);
  float r, phi;
  if (abs(a) > abs(b)) {
    r = a;
    phi = 0.25f * HR_PI * (b / a);
  } else {
    r = b;
    phi = 0.5f * HR_PI - 0.25f * HR_PI * (a / b);
  }
  return vec2(r * cos(phi), r * sin(phi));
}

/// A direction about +z with density cos(theta) / pi (Malley's method), in
/// the local frame; its pdf is hr_cosine_pdf.
HR_FN vec3 hr_cosine_hemisphere(vec2 u) {
  vec2 d = hr_concentric_disk(u);
  return vec3(d.x, d.y, sqrt(max(0.0f, 1.0f - d.x * d.x - d.y * d.y)));
}
HR_FN float hr_cosine_pdf(float cos_theta) { return max(cos_theta, 0.0f) * HR_INV_PI; }

/// A direction uniform in the cone of half-angle acos(cos_max) about +z
/// (local frame); its density, 1 / (2 pi (1 - cos_max)), is hr_cone_pdf.
HR_FN vec3 hr_uniform_cone(vec2 u, float cos_max) {
  float c = mix(1.0f, cos_max, u.x);
  float s = sqrt(max(0.0f, 1.0f - c * c));
  float phi = 2.0f * HR_PI * u.y;
  return vec3(cos(phi) * s, sin(phi) * s, c);
}
HR_FN float hr_cone_pdf(float cos_max) { return 1.0f / (2.0f * HR_PI * (1.0f - cos_max)); }

/// Barycentrics (b1, b2) of a point uniform over a triangle (the square-root
/// parametrisation, pbrt-v4's SampleUniformTriangle): the point is
/// p0 (1 - b1 - b2) + p1 b1 + p2 b2.
HR_FN vec2 hr_uniform_triangle(vec2 u) {
  float s = sqrt(u.x);
  return vec2(s * (1.0f - u.y), s * u.y);
}

/// A density over area (1 / m^2) as one over solid angle seen from a point
/// `dist2` (squared) away, the surface's cosine to the line `cos_surface`.
HR_FN float hr_area_to_solid_angle(float pdf_area, float dist2, float cos_surface) {
  return cos_surface > 0.0f ? pdf_area * dist2 / cos_surface : 0.0f;
}

/// Veach's power heuristic (beta 2) weight of a strategy of density `pa`
/// against one of density `pb`, one sample each (Veach 1997, §9.2.4).
HR_FN float hr_power_heuristic(float pa, float pb) {
  float a = pa * pa, b = pb * pb;
  return a + b > 0.0f ? a / (a + b) : 0.0f;
}

HR_END

#endif
