// holoray/camera: a Looking Glass quilt (issue 14): C x R off-axis pinhole
// views tiled in one image, the way Looking Glass tools lay them out
// (lfdocs.lookingglassfactory.com, "Quilts"): view 0, the leftmost, is the
// bottom-left tile; views run left to right, then bottom to top; the top-
// right tile is the rightmost view. Files are named `NAME_qs{C}x{R}a{A}`,
// A the aspect (width / height) of one view.
//
// The views (sheared frusta sharing one focal plane): with the scene's
// viewpoint (from, at, up, vertical field of view), D = |at - from| and r the
// image's right vector, view k of N = C*R looks from
//     from_k = from + r * D tan(phi_k),  phi_k = -cone/2 + cone * k / (N - 1)
// along the same direction d as the viewpoint, its image window moved by
// -tan(phi_k) (PinholeDesc::shift_x) so that the window's centre stays on
// `at`: every view frames the focal plane through `at` identically, and a
// point on it appears at the same pixel in every view. One view (N = 1) is
// the viewpoint's own.
#pragma once

#include <string>
#include <vector>

#include "camera/camera.hpp"
#include "camera/pinhole.hpp"

namespace holoray {

struct QuiltDesc {
  int columns = 8, rows = 6;   ///< C x R views
  int view_width = 420, view_height = 560;  ///< pixels of one view (Looking Glass Portrait's 8x6 quilt: 420x560)
  double view_cone_deg = 40;   ///< angle from the leftmost to the rightmost view, degrees, in [0, 180)
};

/// The sheared view at angle `phi_rad` from `centre` (documented above with
/// phi = phi_k), width x height pixels.
PinholeDesc sheared_view(const PinholeDesc& centre, double phi_rad, int width, int height);

/// View k's pinhole description, as documented above. Throws
/// std::invalid_argument for k outside [0, C*R) or a cone outside [0, 180).
PinholeDesc quilt_view(const QuiltDesc& q, const PinholeDesc& centre, int k);

/// `path` with the quilt suffix before its extension: "out.png" ->
/// "out_qs8x6a0.75.png" (the aspect with up to 4 significant digits). A
/// name already holding "_qs" is kept as it is.
std::string quilt_file_name(const std::string& path, const QuiltDesc& q);

/// The whole quilt as one camera: pixel (i, j) of the C*w x R*h image is
/// pixel (i mod w, j mod h) of the view whose tile holds it.
class QuiltCamera {
 public:
  /// Throws std::invalid_argument for fewer than one view or more than 4096,
  /// views of fewer than one pixel, a quilt over 2^30 pixels a side, or bad
  /// view cameras.
  QuiltCamera(const QuiltDesc& q, const PinholeDesc& centre);

  const QuiltDesc& desc() const { return q_; }
  int width() const { return q_.columns * q_.view_width; }
  int height() const { return q_.rows * q_.view_height; }
  const PinholeCamera& view(int k) const { return views_[static_cast<size_t>(k)]; }
  /// The view whose tile holds quilt pixel (i, j).
  int view_at(int i, int j) const { return (q_.rows - 1 - j / q_.view_height) * q_.columns + i / q_.view_width; }

  PixelLine line(int i, int j, double u = 0.5, double v = 0.5) const {
    return views_[static_cast<size_t>(view_at(i, j))].line(i % q_.view_width, j % q_.view_height, u, v);
  }
  /// The quilt pixel of view k's pixel (i, j): its tile's corner added
  /// (view 0's tile bottom left, as documented above).
  int quilt_x(int k, int i) const { return i + k % q_.columns * q_.view_width; }
  int quilt_y(int k, int j) const { return j + (q_.rows - 1 - k / q_.columns) * q_.view_height; }
  /// One hit per view that sees the point, in quilt pixels.
  void project(const Vec3& p_world, std::vector<PanelHit>& out) const;

 private:
  QuiltDesc q_;
  std::vector<PinholeCamera> views_;
};
static_assert(PixelCamera<QuiltCamera>);

}  // namespace holoray
