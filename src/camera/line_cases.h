// holoray/camera: one test case of every camera's pixel line, the same text
// on both devices (shading/shared_functions.comp's second suite on the GPU,
// tests/test_pixel_lines.cpp on the CPU): 16 uniforms in [0, 1) make a
// camera and a pixel sample, 32 outputs out (laid out at hr_run_line_case).
// The CPU runs it in double, the GPU in float: the test holds them equal to
// float rounding.
#ifndef HOLORAY_CAMERA_LINE_CASES_H
#define HOLORAY_CAMERA_LINE_CASES_H

#include "camera/pixel_lines.h"

/// The camera kinds the cases cycle through (case c is kind c mod 8).
#define HR_LINE_CASE_KINDS 8u
/// The kind whose line goes through a tangent (the Looking Glass's view
/// angle), which GLSL bounds only to 2^-11.
#define HR_LINE_CASE_TANGENT 7u

HR_LINES_BEGIN

/// r[k], r[k + 1], r[k + 2] = v.
HR_FN void hr_put_line3(HR_ARRAY_INOUT(r, 32), uint k, hr_vec3 v) {
  r[k] = float(v.x);
  r[k + 1u] = float(v.y);
  r[k + 2u] = float(v.z);
}

/// Case c: kind c mod 8 of camera (a square, hex and lenticular lens array;
/// a display's square, hex and slanted lenticular panel; a pinhole or
/// orthographic view; a Looking Glass's panel), sized and placed by a[0..7] and a[12..15], and its
/// line at the sample a[8..11] picks. Outputs: r[0..2] the line's origin
/// and r[3..5] its direction (world: an array's turned by a[12] about z and
/// moved by a[13..15]), r[6..7] the lens (arrays and panels; a Looking
/// Glass's subpixel cell), r[8..10] the panel point (arrays and panels).
HR_FN void hr_run_line_case(uint c, HR_ARRAY_IN(a, 16), HR_ARRAY_OUT(r, 32)) {
  for (uint k = 0u; k < 32u; ++k) r[k] = 0.0f;
  uint kind = c % HR_LINE_CASE_KINDS;
  HrFrame f;
  hr_real turn_c = 1.0 - 2.0 * hr_real(a[12]);  // a cosine in [-1, 1] and its sine, without a transcendental
  hr_real turn_s = sqrt(1.0 - turn_c * turn_c);
  f.origin = hr_vec3(hr_real(a[13]), hr_real(a[14]), hr_real(a[15])) * 10.0;
  f.x = hr_vec3(turn_c, turn_s, 0.0);
  f.y = hr_vec3(-turn_s, turn_c, 0.0);
  f.z = hr_vec3(0.0, 0.0, 1.0);
  hr_vec3 o = hr_vec3(0.0, 0.0, 0.0);
  hr_vec3 d = hr_vec3(0.0, 0.0, 0.0);
  if (kind < 3u) {
    HrLensGrid g;
    g.grid = int(kind);
    g.pixels_per_lens = 1 + int(a[0] * 12.0f);
    g.lenses_x = 1 + int(a[1] * 40.0f);
    g.lenses_y = kind == 2u ? 1 : 1 + int(a[2] * 40.0f);
    g.converging = a[7] > 0.5f ? 1 : 0;
    g.pitch = 0.2 + hr_real(a[3]);
    g.gap = 0.5 + hr_real(a[4]);
    g.s = g.pitch / hr_real(g.pixels_per_lens);
    g.row_step = g.pitch * 1.7320508075688772 / 2.0;
    g.view_distance = 5.0 + 50.0 * hr_real(a[6]);
    int width = g.lenses_x * g.pixels_per_lens;
    int height = kind == 0u ? g.lenses_y * g.pixels_per_lens
                 : kind == 1u ? hr_round(hr_real(g.lenses_y * g.pixels_per_lens) * 1.7320508075688772 / 2.0)
                              : 1 + int(a[5] * 100.0f);
    height = max(height, 1);
    g.half_w = hr_real(width) * g.s / 2.0;
    g.half_h = hr_real(height) * g.s / 2.0;
    int i = min(int(a[8] * float(width)), width - 1);
    int j = min(int(a[9] * float(height)), height - 1);
    hr_lens_array_line(g, i, j, hr_real(a[10]), hr_real(a[11]), o, d);
    ivec2 l = hr_lens_of_pixel(g, i, j);
    r[6] = float(l.x);
    r[7] = float(l.y);
    hr_put_line3(r, 8u, hr_panel_point(g, i, j, hr_real(a[10]), hr_real(a[11])));
  } else if (kind < 6u) {
    HrPanelGrid g;
    g.grid = int(kind) - 3;
    g.converging = a[7] > 0.5f ? 1 : 0;
    int samples = a[5] > 0.5f ? 3 : 1;
    g.pixel_pitch = 0.05 + 0.1 * hr_real(a[0]);
    g.sample_width = g.pixel_pitch / hr_real(samples);
    g.pitch = g.pixel_pitch * (1.5 + 10.0 * hr_real(a[1]));
    g.gap = 0.5 + hr_real(a[4]);
    int width = 100 + int(a[2] * 1000.0f);
    int height = 100 + int(a[3] * 1000.0f);
    g.half_w = hr_real(width) * g.pixel_pitch / 2.0;
    g.half_h = hr_real(height) * g.pixel_pitch / 2.0;
    g.sin_slant = g.grid == HR_LINE_GRID_LENTICULAR ? 1.4 * (hr_real(a[6]) - 0.5) : 0.0;
    g.cos_slant = sqrt(1.0 - g.sin_slant * g.sin_slant);
    hr_real offset = (hr_real(a[7]) - 0.5) * g.pitch;
    g.left = g.grid == HR_LINE_GRID_LENTICULAR ? (-g.half_w + offset) * g.cos_slant : -g.half_w + offset;
    g.row_step = g.pitch * 1.7320508075688772 / 2.0;
    g.view_distance = 5.0 + 50.0 * hr_real(a[6]);
    int i = min(int(a[8] * float(width * samples)), width * samples - 1);
    int j = min(int(a[9] * float(height)), height - 1);
    hr_panel_line(g, i, j, hr_real(a[10]), hr_real(a[11]), o, d);
    hr_vec3 p = hr_panel_sample_point(g, i, j, hr_real(a[10]), hr_real(a[11]));
    ivec2 l = hr_panel_lens_at(g, p);
    r[6] = float(l.x);
    r[7] = float(l.y);
    hr_put_line3(r, 8u, p);
  } else if (kind == HR_LINE_CASE_TANGENT) {
    HrLookingGlass g;
    g.centre.width = 100 + int(a[0] * 2000.0f);
    g.centre.height = 100 + int(a[1] * 2000.0f);
    g.centre.ortho = 0;
    g.views = 1 + int(a[2] * 100.0f);
    g.centre.pixel = (0.5 + hr_real(a[3])) * 2.0 / hr_real(g.centre.height);
    g.centre.sample_u = a[4] > 0.5f ? 1.0 : 0.5;
    g.centre.sample_v = g.centre.sample_u;
    g.centre.shift_x = (hr_real(a[5]) - 0.5) * 0.2;
    g.centre.shift_y = 0.0;
    g.view_cone_deg = 20.0 + 40.0 * hr_real(a[6]);
    g.distance = 1.0 + 20.0 * hr_real(a[7]);
    int i = min(int(a[8] * float(g.centre.width)), g.centre.width - 1);
    int j = min(int(a[9] * float(g.centre.height)), g.centre.height - 1);
    hr_real x = 0.00001 + 0.99998 * hr_real(a[10]);  // a view value in (0, 1)
    hr_looking_glass_line(g, f, i, j, hr_real(a[11]), hr_real(a[12]), x, o, d);
    // The subpixel cell of every pattern (0 to 4) with 0 to 4 cells.
    r[6] = float(hr_looking_glass_cell(int((c / 8u) % 5u), int((c / 40u) % 5u), g.centre.height, i, j));
    hr_put_line3(r, 0u, o);
    hr_put_line3(r, 3u, d);
    return;
  } else {
    HrPinhole v;
    v.width = 64 + int(a[0] * 512.0f);
    v.height = 48 + int(a[1] * 512.0f);
    v.ortho = a[6] > 0.7f ? 1 : 0;
    v.pixel = (0.5 + hr_real(a[2])) * 2.0 / hr_real(v.height);
    v.sample_u = a[3] > 0.5f ? 1.0 : 0.5;
    v.sample_v = v.sample_u;
    v.shift_x = (hr_real(a[4]) - 0.5) * 0.2;
    v.shift_y = (hr_real(a[5]) - 0.5) * 0.2;
    int i = min(int(a[8] * float(v.width)), v.width - 1);
    int j = min(int(a[9] * float(v.height)), v.height - 1);
    hr_pinhole_line(v, f, i, j, hr_real(a[10]), hr_real(a[11]), o, d);
    hr_put_line3(r, 0u, o);
    hr_put_line3(r, 3u, d);
    return;
  }
  hr_put_line3(r, 0u, hr_to_world_point(f, o));
  hr_put_line3(r, 3u, hr_to_world_dir(f, d));
}

HR_LINES_END

#endif
