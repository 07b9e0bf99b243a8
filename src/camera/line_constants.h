// holoray/camera: each camera's constants, as camera/pixel_lines.h's line
// functions take them: one declaration read three ways. The CPU cameras
// hold them in double (pixel_lines.h includes this in
// holoray::camera_lines, hr_real = double); the GPU reads the same records
// in float, from GpuFrame (gpu/shaders/layout.h includes this in
// holoray::gpu, hr_real = float, for the host to fill from the CPU
// camera's own record; GLSL through pixel_lines.h). No include guard, by
// design: C++ includes it once in each of those namespaces, and pixel_lines.h's
// guard keeps GLSL to one. Scalars only, so that std430 packs them at 4
// bytes as C++ does (layout.h puts them after its 16-byte vectors).

/// A lens array over its panel, whole pixels per lens: `grid` one of
/// HR_LINE_GRID_*; lenses_y is 1 for a lenticular sheet. Lengths in scene
/// units: s the pixel pitch (pitch / pixels_per_lens), half_w and half_h
/// half the panel, row_step a hex grid's row spacing (pitch sqrt(3)/2).
/// A lenticular sheet's lines converge on a viewer at view_distance when
/// `converging` is 1, else stay level (an infinite distance).
struct HrLensGrid {
  int grid, pixels_per_lens, lenses_x, lenses_y, converging;
  hr_real pitch, gap, s, half_w, half_h, row_step, view_distance;
};

/// A display's lens grid over its panel, sample by sample (one or three a
/// pixel): sample_width across, pixel_pitch down; `left` where the grid
/// starts on the middle row (across the axis for a lenticular sheet, whose
/// axes lean by the slant: sin_slant, cos_slant); row_step a hex grid's row
/// spacing. Lengths in scene units. Lenticular lines converge on a viewer
/// at view_distance when `converging` is 1.
struct HrPanelGrid {
  int grid, converging;
  hr_real pitch, gap, sample_width, pixel_pitch, half_w, half_h, left, row_step, sin_slant, cos_slant, view_distance;
};

/// A pinhole (or orthographic, `ortho` 1) view of width x height pixels;
/// `pixel` one pixel's size on the image plane at distance 1 (orthographic:
/// on the eye's plane); (sample_u, sample_v) where in its pixel the sample
/// at (0.5, 0.5) lands; the window shifted by (shift_x, shift_y).
struct HrPinhole {
  int width, height, ortho;
  hr_real pixel, sample_u, sample_v, shift_x, shift_y;
};

/// A Looking Glass's panel as the continuous version of its quilt: `views`
/// views over a cone of view_cone_deg degrees, each the `centre` view
/// (perspective, no vertical shift) sheared about the zero-parallax plane
/// at `distance`.
struct HrLookingGlass {
  HrPinhole centre;
  int views;
  hr_real view_cone_deg, distance;
};
