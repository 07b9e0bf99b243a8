// holoray/camera: the camera of a physical display (issue 14): any lens
// pitch, not only whole pixels per lens; a lenticular sheet slanted across
// the panel; each colour subpixel traced along its own line through its own
// lens (van Berkel, "Image preparation for 3D-LCD", SPIE 3639, 1999: a
// subpixel's view is set by where it sits across the lenticule above it).
//
// Frames as lens_array.hpp: "local" is the array frame (origin at the panel
// centre's lens-plane point, z toward the viewer, panel at z = -gap), units
// are scene units. A sample is (column c, row j): c counts subpixels (three
// per pixel) or pixels from the left, j rows from the top. The lines follow
// the contract's pinhole model (camera-model.md) with the pixel centre
// replaced by the sample's centre and the lens found from the sample:
// square and hex grids as "Square grid" / "Hexagonal grid" (nearest centre,
// ties to the lower row then column), the lenticular sheet as "Lenticular
// sheet" rotated by the slant.
#pragma once

#include <cstdint>
#include <vector>

#include "camera/camera.hpp"
#include "camera/lens_array.hpp"
#include "camera/pixel_lines.h"
#include "math/vec.hpp"

namespace holoray {

/// Everything that fixes a display's lines, in scene units (a display file
/// placed in a scene: display/display_placement.hpp). Validated by DisplayCamera.
struct DisplayGeometry {
  int width = 1, height = 1;    ///< panel pixels
  int samples_per_pixel = 1;    ///< 3: colour subpixels in vertical stripes; 1: whole pixels
  double pixel_pitch = 1;       ///< s, pixel centre to centre
  Grid grid = Grid::lenticular;
  double pitch = 1;             ///< lens pitch across the lenses (perpendicular to a lenticule's axis)
  double slant_rad = 0;         ///< lenticular: axes' angle from vertical, positive leaning right at the top
  double gap = 1;               ///< lens plane to panel
  double offset = 0;            ///< lens grid shifted right of the panel's left edge
  double view_distance = INFINITY;  ///< lenticular vertical perspective distance V
  RecordingMode mode = RecordingMode::orthoscopic;
  Frame frame;
};

/// A lens of a display: (x, y) of the square or hex grid, counted from the
/// grid's top-left lens (negative when the offset leaves a partial lens at
/// the left); for a lenticular sheet, x is the lenticule and y is 0.
using DisplayLens = LensIndex;

class DisplayCamera {
 public:
  /// Validates and precomputes. Throws std::invalid_argument naming the bad
  /// value and its unit: non-positive or non-finite pitch, pixel pitch or
  /// gap; a lens narrower than a pixel; a slant outside [-45, 45] degrees or
  /// on a grid that is not lenticular; panels of more than 2^30 samples a side.
  explicit DisplayCamera(const DisplayGeometry& g);

  const DisplayGeometry& geometry() const { return g_; }
  int width() const { return width_; }    ///< samples across: panel width x samples per pixel
  int height() const { return g_.height; }  ///< rows
  double sample_width() const { return sw_; }      ///< s / samples per pixel

  /// Centre of sample (c, j) at offset (u, v) inside it, on the panel (z = -gap).
  Vec3 panel_point_local(int c, int j, double u = 0.5, double v = 0.5) const;
  /// The lens that covers a panel point (z ignored): the nearest lens centre
  /// (square, hex) or the lenticule whose strip holds it.
  DisplayLens lens_at(const Vec3& p_local) const;
  /// Square and hex grids: the lens centre on the lens plane (z = 0). The
  /// lens sheet covers the whole panel, so indices past the grid's first
  /// lens (negative ones at the left or top edge) are lenses too.
  Vec3 lens_centre_local(DisplayLens l) const;
  /// Lenticular: the point of lenticule l's axis on the lens plane with the
  /// same along-axis coordinate as `p_local`; the line of a panel point
  /// under the lenticule passes through it.
  Vec3 axis_point_local(DisplayLens l, const Vec3& p_local) const;

  /// The line of sample (c, j) at offset (u, v) inside it, array frame: it
  /// passes through the sample's lens centre (square, hex) or its
  /// lenticule's axis (lenticular) on the lens plane, toward +z.
  PixelLine line_local(int c, int j, double u = 0.5, double v = 0.5) const;
  PixelLine line(int c, int j, double u = 0.5, double v = 0.5) const;

  /// Forward projection, the exact inverse of line(): every sample whose line
  /// passes through the world point, one per lens whose covered samples hold
  /// its landing point (pseudoscopic: t > 0 only). Points on the lens plane
  /// project nowhere.
  void project(const Vec3& p_world, std::vector<PanelHit>& out) const;

  /// The constants its lines are computed from (camera/line_constants.h),
  /// which the GPU's kernel reads too (gpu/shaders/layout.h, GpuFrame).
  const camera_lines::HrPanelGrid& line_constants() const { return grid_; }

 private:
  // Across- and along-axis coordinates of a lens-plane point (lenticular).
  double across(const Vec3& p) const { return camera_lines::hr_panel_across(grid_, p); }
  double along(const Vec3& p) const { return camera_lines::hr_panel_along(grid_, p); }
  bool sample_at(const Vec3& p_local, PanelHit& h) const;

  DisplayGeometry g_;
  int width_ = 0;
  double sw_ = 0;                // sample width
  double half_w_ = 0, half_h_ = 0;
  double sin_ = 0, cos_ = 1;     // of the slant
  double left_ = 0;              // lens grid's left edge, x (square, hex) or across coordinate (lenticular)
  double row_step_ = 0;          // hex: pitch*sqrt(3)/2
  camera_lines::HrPanelGrid grid_{};    // the grid as the shared line functions take it (camera/pixel_lines.h)
};
static_assert(PixelCamera<DisplayCamera>);

}  // namespace holoray
