// holoray/camera: the line each pixel records, one text for both devices
// (issue 70, "one source"): compiled as C++ in double (the CPU cameras,
// through line_compat.hpp, in namespace holoray::camera_lines) and as GLSL 4.50 in
// float (the GPU kernel's eye rays, gpu/shaders/trace.comp). Written in the
// subset shading/common.h describes, with two more names: hr_real (double on
// the CPU, float on the GPU) and hr_vec3 (Vec3, vec3). Literals carry no
// suffix, so that each language reads them at its own precision. The camera
// model is docs/design/camera-model.md; every line here is in the array's
// (panel's) local frame unless its comment says world.
#ifndef HOLORAY_CAMERA_PIXEL_LINES_H
#define HOLORAY_CAMERA_PIXEL_LINES_H

#ifdef __cplusplus
#include "camera/line_compat.hpp"
#define HR_LINES_BEGIN namespace holoray::camera_lines {
#define HR_LINES_END }
#else
#include "shading/common.h"
#define hr_real float
#define hr_vec3 vec3
#define HR_LINES_BEGIN
#define HR_LINES_END
#endif

#define HR_LINE_GRID_SQUARE 0
#define HR_LINE_GRID_HEX 1
#define HR_LINE_GRID_LENTICULAR 2

HR_LINES_BEGIN

#ifndef __cplusplus
/// An orthonormal frame placed in the world (math/vec.hpp's Frame).
struct HrFrame {
  vec3 origin, x, y, z;
};
/// lround for the values the grids round: ties away from zero above zero;
/// below zero the callers clamp to 0, where either rounding lands.
int hr_round(float x) { return int(floor(x + 0.5)); }
#define HR_LINE_INF uintBitsToFloat(0x7f800000u)
#endif

/// A local point or direction of `f` in the world, summed in Frame's order.
HR_FN hr_vec3 hr_to_world_point(HrFrame f, hr_vec3 p) { return f.origin + f.x * p.x + f.y * p.y + f.z * p.z; }
HR_FN hr_vec3 hr_to_world_dir(HrFrame f, hr_vec3 d) { return f.x * d.x + f.y * d.y + f.z * d.z; }

// Each camera's constants, as its line functions below take them.
#include "camera/line_constants.h"

// ---- the integral camera's lens array (camera/lens_array.hpp) ----

/// The hex lens of pixel (i, j): the nearest centre, in pixel units from the
/// top-left corner (x offsets are multiples of 1/2, so ties within a row
/// are exact); ties keep the lower row, then the lower column.
HR_FN ivec2 hr_hex_lens_of_pixel(HrLensGrid g, int i, int j) {
  int P = g.pixels_per_lens;
  hr_real px = hr_real(i) + 0.5;
  hr_real py = hr_real(j) + 0.5;
  hr_real row_step = hr_real(P) * 1.7320508075688772 / 2.0;
  int ly0 = clamp(hr_round((py - hr_real(P) / 2.0) / row_step), 0, g.lenses_y - 1);
  ivec2 best = ivec2(0, 0);
  hr_real best_d2 = HR_LINE_INF;
  for (int ly = max(0, ly0 - 1); ly <= min(g.lenses_y - 1, ly0 + 1); ++ly) {
    hr_real shift = (ly & 1) != 0 ? 0.5 : 0.0;
    hr_real cy = hr_real(P) / 2.0 + hr_real(ly) * row_step;
    int lx0 = clamp(hr_round(px / hr_real(P) - 0.5 - shift), 0, g.lenses_x - 1);
    for (int lx = max(0, lx0 - 1); lx <= min(g.lenses_x - 1, lx0 + 1); ++lx) {
      hr_real dx = px - (hr_real(lx) + 0.5 + shift) * hr_real(P);
      hr_real dy = py - cy;
      hr_real d2 = dx * dx + dy * dy;
      if (d2 < best_d2) {  // strict: the first of equals stays
        best_d2 = d2;
        best = ivec2(lx, ly);
      }
    }
  }
  return best;
}

/// The lens pixel (i, j) belongs to: (column, row); a lenticule's row is 0.
HR_FN ivec2 hr_lens_of_pixel(HrLensGrid g, int i, int j) {
  int P = g.pixels_per_lens;
  if (g.grid == HR_LINE_GRID_SQUARE) return ivec2(i / P, j / P);
  if (g.grid == HR_LINE_GRID_LENTICULAR) return ivec2(i / P, 0);
  return hr_hex_lens_of_pixel(g, i, j);
}

/// Lens (lx, ly)'s centre on the lens plane (z = 0); a lenticule's is on
/// the middle row, (c_x, 0, 0).
HR_FN hr_vec3 hr_lens_centre(HrLensGrid g, int lx, int ly) {
  hr_real half_array_w = hr_real(g.lenses_x) * g.pitch / 2.0;
  if (g.grid == HR_LINE_GRID_SQUARE)
    return hr_vec3((hr_real(lx) + 0.5) * g.pitch - half_array_w,
                   hr_real(g.lenses_y) * g.pitch / 2.0 - (hr_real(ly) + 0.5) * g.pitch, 0.0);
  if (g.grid == HR_LINE_GRID_HEX)
    return hr_vec3((hr_real(lx) + 0.5 + ((ly & 1) != 0 ? 0.5 : 0.0)) * g.pitch - half_array_w,
                   g.half_h - g.pitch / 2.0 - hr_real(ly) * g.row_step, 0.0);
  return hr_vec3((hr_real(lx) + 0.5) * g.pitch - half_array_w, 0.0, 0.0);
}

/// The panel point of pixel (i, j) at (u, v) inside it (0.5: its centre),
/// on the panel plane z = -gap.
HR_FN hr_vec3 hr_panel_point(HrLensGrid g, int i, int j, hr_real u, hr_real v) {
  return hr_vec3((hr_real(i) + u) * g.s - g.half_w, g.half_h - (hr_real(j) + v) * g.s, -g.gap);
}

/// The line pixel (i, j) records, at (u, v) inside it (camera-model.md,
/// "Pixel lines"): from the panel point through its lens centre, origin the
/// centre, dir unit toward +z. A lenticule has power across only: the line
/// crosses the lens plane on its axis at the point's height and, along the
/// axis, aims at the viewer's height (contract, "Lenticular sheet").
HR_FN void hr_lens_array_line(HrLensGrid g, int i, int j, hr_real u, hr_real v, HR_OUT(hr_vec3) origin,
                              HR_OUT(hr_vec3) dir) {
  hr_vec3 p = hr_panel_point(g, i, j, u, v);
  ivec2 l = hr_lens_of_pixel(g, i, j);
  hr_vec3 c = hr_lens_centre(g, l.x, l.y);
  if (g.grid == HR_LINE_GRID_LENTICULAR) {
    hr_real dy = g.converging != 0 ? -p.y / g.view_distance : 0.0;
    origin = hr_vec3(c.x, p.y, 0.0);
    dir = normalize(hr_vec3((c.x - p.x) / g.gap, dy, 1.0));
    return;
  }
  origin = c;
  dir = normalize(c - p);
}

// ---- a display's panel, lenses of any pitch (camera/display_camera.hpp) ----

/// Sample c of row j at (u, v) inside it, on the panel plane z = -gap.
HR_FN hr_vec3 hr_panel_sample_point(HrPanelGrid g, int c, int j, hr_real u, hr_real v) {
  return hr_vec3((hr_real(c) + u) * g.sample_width - g.half_w, g.half_h - (hr_real(j) + v) * g.pixel_pitch, -g.gap);
}

/// Across and along a lenticule's axis, of a lens-plane or panel point.
HR_FN hr_real hr_panel_across(HrPanelGrid g, hr_vec3 p) { return p.x * g.cos_slant - p.y * g.sin_slant; }
HR_FN hr_real hr_panel_along(HrPanelGrid g, hr_vec3 p) { return p.x * g.sin_slant + p.y * g.cos_slant; }

/// Lens (lx, ly)'s centre (square, hex) on the lens plane.
HR_FN hr_vec3 hr_panel_lens_centre(HrPanelGrid g, int lx, int ly) {
  if (g.grid == HR_LINE_GRID_HEX)
    return hr_vec3(g.left + (hr_real(lx) + 0.5 + ((ly & 1) != 0 ? 0.5 : 0.0)) * g.pitch,
                   g.half_h - g.pitch / 2.0 - hr_real(ly) * g.row_step, 0.0);
  return hr_vec3(g.left + (hr_real(lx) + 0.5) * g.pitch, g.half_h - (hr_real(ly) + 0.5) * g.pitch, 0.0);
}

/// The lens over panel point p: a lenticule by the strip across its axis;
/// a square lens by its cell; a hex lens the nearest centre of the two rows
/// around p, ties to the lower row, then the lower column (contract,
/// "Hexagonal grid").
HR_FN ivec2 hr_panel_lens_at(HrPanelGrid g, hr_vec3 p) {
  hr_real P = g.pitch;
  if (g.grid == HR_LINE_GRID_LENTICULAR) return ivec2(int(floor((hr_panel_across(g, p) - g.left) / P)), 0);
  if (g.grid == HR_LINE_GRID_SQUARE) return ivec2(int(floor((p.x - g.left) / P)), int(floor((g.half_h - p.y) / P)));
  int row0 = int(floor((g.half_h - P / 2.0 - p.y) / g.row_step));
  ivec2 best = ivec2(0, 0);
  hr_real best_d2 = HR_LINE_INF;
  for (int ly = row0; ly <= row0 + 1; ++ly) {
    hr_real shift = (ly & 1) != 0 ? 0.5 : 0.0;
    // The cell [lx + shift, lx + 1 + shift) pitches from the left edge; at
    // an exact boundary ceil - 1 picks the lower column.
    int lx = int(ceil((p.x - g.left) / P - shift)) - 1;
    hr_vec3 c = hr_panel_lens_centre(g, lx, ly);
    hr_real d2 = (p.x - c.x) * (p.x - c.x) + (p.y - c.y) * (p.y - c.y);
    if (d2 < best_d2) {
      best_d2 = d2;
      best = ivec2(lx, ly);
    }
  }
  return best;
}

/// Where lenticule l's axis crosses the lens plane at the height (along
/// the axis) of point p.
HR_FN hr_vec3 hr_panel_axis_point(HrPanelGrid g, int l, hr_vec3 p) {
  hr_real a = g.left + (hr_real(l) + 0.5) * g.pitch;
  hr_real b = hr_panel_along(g, p);
  return hr_vec3(a * g.cos_slant + b * g.sin_slant, -a * g.sin_slant + b * g.cos_slant, 0.0);
}

/// The line sample c of row j records, at (u, v) inside it: through its lens
/// centre (square, hex) toward +z; or, under a lenticule, the pinhole's
/// line through its axis across it and, along it (no power), aimed at the
/// viewer's height (contract, "Lenticular sheet", turned by the slant).
HR_FN void hr_panel_line(HrPanelGrid g, int c, int j, hr_real u, hr_real v, HR_OUT(hr_vec3) origin,
                         HR_OUT(hr_vec3) dir) {
  hr_vec3 p = hr_panel_sample_point(g, c, j, u, v);
  ivec2 l = hr_panel_lens_at(g, p);
  if (g.grid != HR_LINE_GRID_LENTICULAR) {
    origin = hr_panel_lens_centre(g, l.x, l.y);
    dir = normalize(origin - p);
    return;
  }
  hr_vec3 q = hr_panel_axis_point(g, l.x, p);
  hr_real k = (hr_panel_across(g, q) - hr_panel_across(g, p)) / g.gap;
  hr_real dy = g.converging != 0 ? -q.y / g.view_distance : 0.0;
  origin = q;
  dir = normalize(hr_vec3(k * g.cos_slant, -k * g.sin_slant + dy, 1.0));
}

// ---- a pinhole view (camera/pinhole.hpp) ----

/// Where pixel (i, j)'s sample at (u, v) lies on the image plane (the
/// view's frame; distance 1, orthographic: the eye's plane), its window
/// shifted by (shift_x, shift_y).
HR_FN void hr_image_plane_point(HrPinhole c, int i, int j, hr_real u, hr_real v, hr_real shift_x, hr_real shift_y,
                                HR_OUT(hr_real) x, HR_OUT(hr_real) y) {
  x = (hr_real(i) + u + (c.sample_u - 0.5) - 0.5 * hr_real(c.width)) * c.pixel + shift_x;
  y = (0.5 * hr_real(c.height) - (hr_real(j) + v + (c.sample_v - 0.5))) * c.pixel + shift_y;
}

/// Pixel (i, j)'s line at (u, v) inside it, in the world: from the eye
/// (f.origin; f.z points back toward it) through the image plane at
/// distance 1; orthographic, from the eye's plane along -f.z.
HR_FN void hr_pinhole_line(HrPinhole c, HrFrame f, int i, int j, hr_real u, hr_real v, HR_OUT(hr_vec3) origin,
                           HR_OUT(hr_vec3) dir) {
  hr_real x;
  hr_real y;
  hr_image_plane_point(c, i, j, u, v, c.shift_x, c.shift_y, x, y);
  if (c.ortho != 0) {
    origin = hr_to_world_point(f, hr_vec3(x, y, 0.0));
    dir = -f.z;
    return;
  }
  origin = f.origin;
  dir = normalize(hr_to_world_dir(f, hr_vec3(x, y, -1.0)));
}

// ---- a Looking Glass's native panel (display/looking_glass.hpp) ----

/// The subpixel cell of pixel (i, j) (the calibration's cell pattern
/// 0 to 4, as the official shader's GetCellForPixel: the row counted from
/// the bottom), of `cells` cells; 0 where the calibration has none.
HR_FN int hr_looking_glass_cell(int pattern, int cells, int height, int i, int j) {
  if (cells == 0) return 0;
  int x = i;
  int y = height - 1 - j;
  int cell = 0;
  if (pattern == 1) cell = (y % 2 == 0) == (x % 2 == 0) ? 0 : 1;  // checkerboard AB / BA
  if (pattern == 2) cell = x % 2;
  if (pattern == 3) cell = (y + (x % 2) * 2) % 4;
  if (pattern == 4) cell = y % 2;
  return cell % cells;
}

/// The line of a subpixel of pixel (i, j), at (u, v) inside the pixel,
/// whose view value from the calibration's phase is x in (0, 1)
/// (looking_glass_view): the view of continuous quilt index x views, the
/// centre view sheared by t = tan(its angle) (world).
HR_FN void hr_looking_glass_line(HrLookingGlass g, HrFrame f, int i, int j, hr_real u, hr_real v, hr_real x,
                                 HR_OUT(hr_vec3) origin, HR_OUT(hr_vec3) dir) {
  hr_real index = x * hr_real(g.views);
  hr_real along = g.views == 1 ? 0.5 : index / hr_real(g.views - 1);
  hr_real t = tan((along - 0.5) * g.view_cone_deg * 3.141592653589793 / 180.0);
  hr_real px;
  hr_real py;
  hr_image_plane_point(g.centre, i, j, u, v, g.centre.shift_x - t, 0.0, px, py);
  origin = f.origin + f.x * (g.distance * t);
  dir = normalize(hr_to_world_dir(f, hr_vec3(px, py, -1.0)));
}

HR_LINES_END

#endif
