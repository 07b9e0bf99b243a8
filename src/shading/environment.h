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

/// World direction `w` (unit) in the environment frame: glTF's +y up
/// turned to Blender's +z up where `up_y` (the exporter's axes), then the
/// Mapping node's turn about z, given by its cosine and sine.
HR_FN vec3 hr_env_from_world(vec3 w, float cos_rot, float sin_rot, bool up_y) {
  vec3 b = up_y ? vec3(w.x, -w.z, w.y) : w;
  return vec3(cos_rot * b.x - sin_rot * b.y, sin_rot * b.x + cos_rot * b.y, b.z);
}

/// hr_env_from_world's inverse.
HR_FN vec3 hr_env_to_world(vec3 e, float cos_rot, float sin_rot, bool up_y) {
  vec3 b = vec3(cos_rot * e.x + sin_rot * e.y, -sin_rot * e.x + cos_rot * e.y, e.z);
  return up_y ? vec3(b.x, b.z, -b.y) : b;
}

/// The sine of the latitude of the top edge of row y of h (rows from the
/// top; y = h gives the bottom edge of the last).
HR_FN float hr_env_row_sin(int y, int h) { return sin((0.5f - float(y) / float(h)) * HR_PI); }

/// The solid angle of a texel of row y of a w x h image.
HR_FN float hr_env_texel_solid_angle(int y, int w, int h) {
  return (2.0f * HR_PI / float(w)) * (hr_env_row_sin(y, h) - hr_env_row_sin(y + 1, h));
}

/// The texel (x, rows from the top) that image coordinates `uv` fall in.
HR_FN ivec2 hr_env_texel_of(vec2 uv, int w, int h) {
  return ivec2(min(w - 1, int(uv.x * float(w))), clamp(int((1.0f - uv.y) * float(h)), 0, h - 1));
}

/// Blender's Linear interpolation of an Environment Texture at `uv`: the
/// four texels around it (x0, y0, x1, y1; wrapped across the seam, clamped
/// at the poles) and the weights of x1 and y1.
HR_FN void hr_env_bilinear(vec2 uv, int w, int h, HR_OUT(ivec4) texels, HR_OUT(vec2) t) {
  float fx = uv.x * float(w) - 0.5f, fy = (1.0f - uv.y) * float(h) - 0.5f;
  int x0 = int(floor(fx)), y0 = int(floor(fy));
  t = vec2(fx - float(x0), fy - float(y0));
  // x0 lies in [-1, w - 1] (GLSL leaves % of a negative undefined).
  texels = ivec4(x0 < 0 ? x0 + w : x0, clamp(y0, 0, h - 1), x0 + 1 >= w ? x0 + 1 - w : x0 + 1, clamp(y0 + 1, 0, h - 1));
}

/// A direction (environment frame, unit) drawn in texel (x, y) of a w x h
/// image: uniform in its u and in the sine of its latitude, so uniform
/// over its solid angle.
HR_FN vec3 hr_env_texel_direction(int x, int y, int w, int h, vec2 u) {
  float bottom = hr_env_row_sin(y + 1, h), top = hr_env_row_sin(y, h);
  float lat = asin(clamp(bottom + u.y * (top - bottom), -1.0f, 1.0f));
  return hr_equirect_direction(vec2((float(x) + u.x) / float(w), 0.5f + lat * HR_INV_PI));
}

/// A direction drawn uniformly over the sphere (a constant environment's sampling; density 1 / (4 pi)).
HR_FN vec3 hr_uniform_sphere(vec2 u) {
  float z = 1.0f - 2.0f * u.x, r = sqrt(max(0.0f, 1.0f - z * z)), phi = 2.0f * HR_PI * u.y;
  return vec3(r * cos(phi), r * sin(phi), z);
}

HR_END

#endif
