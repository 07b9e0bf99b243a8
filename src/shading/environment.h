// holoray/shading: the environment, an equirectangular (latitude-longitude)
// image around the scene, mapped as Blender maps an Environment Texture
// node, and its importance sampling by an alias table. Shared by both
// devices.
//
// The environment frame is Blender's: z up. A direction d there reads the
// image at u = 0.5 - atan2(d.y, d.x) / (2 pi) (across, from the left
// edge), v = 0.5 + asin(d.z) / pi (up, from the bottom row): +x looks at
// the centre column, +y at the first quarter, -x at the seam (measured
// against Blender 3.4's Cycles, tests/python/test_path.py). A Mapping
// node's Z rotation r reads the direction Rz(r) d.
#ifndef HOLORAY_SHADING_ENVIRONMENT_H
#define HOLORAY_SHADING_ENVIRONMENT_H

#include "shading/common.h"

HR_BEGIN

/// Image coordinates (u right, v up, in [0, 1]) of direction `d` (environment frame, unit).
HR_FN vec2 hr_equirect_uv(vec3 d) {
  float u = 0.5f - atan(d.y, d.x) * (0.5f * HR_INV_PI);
  float v = 0.5f + asin(clamp(d.z, -1.0f, 1.0f)) * HR_INV_PI;
  return vec2(u - floor(u), v);
}

/// The direction (environment frame, unit) at image coordinates (u, v):
/// hr_equirect_uv's inverse.
HR_FN vec3 hr_equirect_direction(vec2 uv) {
  float phi = (0.5f - uv.x) * 2.0f * HR_PI;
  float lat = (uv.y - 0.5f) * HR_PI;
  float c = cos(lat);
  return vec3(c * cos(phi), c * sin(phi), sin(lat));
}

/// The solid-angle density of a direction drawn with image-area density
/// `pdf_uv` (over [0, 1]^2) at latitude cosine `cos_lat`: the map stretches
/// a texel's 2 pi^2 cos(lat) du dv of solid angle.
HR_FN float hr_equirect_pdf(float pdf_uv, float cos_lat) {
  return cos_lat > 0.0f ? pdf_uv / (2.0f * HR_PI * HR_PI * cos_lat) : 0.0f;
}

/// An alias table's first step (Walker 1977; Vose 1991): the cell of `n`
/// that `u` falls in, and `u` rescaled to [0, 1) within it, to compare
/// with the cell's probability (keep the cell below it, else take its alias).
HR_FN uint hr_alias_cell(float u, uint n, HR_OUT(float) u_rest) {
  float x = u * float(n);
  uint cell = min(uint(x), n - 1u);
  u_rest = min(x - float(cell), 0.99999994f);
  return cell;
}

HR_END

#endif
