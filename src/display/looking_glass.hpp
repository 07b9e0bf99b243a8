// holoray/display: Looking Glass displays from their calibration file
// (issue 14, item 2). A Looking Glass is a slanted lenticular sheet on a
// panel; its calibration (the device's visual.json) gives the lenticules
// per inch, their slope, the phase at the panel's corner and the view cone.
// From those, the slanted-lenticular mapping of van Berkel (SPIE 3639, 1999)
// as Looking Glass's own documentation states its quantities gives each
// subpixel the view it shows:
//
//   u = (i + 1/2) / W,  v = (H - j - 1/2) / H          pixel centre, v up (flips mirror them)
//   P = pitch * (W / DPI) * cos(atan(1 / slope))       lenticules across the panel's width
//   a = (u + s / (3 W) + v * H / (W * slope)) * P - center,  s = 0, 1, 2 the subpixel (R, G, B; flipSubp reverses)
//   f = a - floor(a)                                   where across its lenticule the subpixel sits
//   f = 1 - f when invView
//
// and the subpixel shows the view at angle phi = (f - 1/2) * viewCone, a
// sheared pinhole view as quilt_camera.hpp documents, so that a quilt of N
// views holds the angles f = k / (N - 1). holoray was not checked on a
// device: the signs (which way f runs, invView) follow the formula as
// written, and a unit whose image looks mirrored needs invView toggled.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "camera/camera.hpp"
#include "camera/pinhole.hpp"
#include "camera/quilt_camera.hpp"
#include "image/image.hpp"

namespace holoray {

/// The calibration fields the mapping uses (visual.json: each as {"value": x}).
struct LookingGlassCalibration {
  std::string source;
  double pitch = 0;           ///< lenticules per inch, before the slant correction
  double slope = 0;           ///< rows per pixel of sideways shift of a lenticule (sign: its lean)
  double center = 0;          ///< phase at the panel's corner, lenticules
  double view_cone_deg = 40;  ///< viewCone, degrees
  bool inv_view = false;      ///< invView
  double dpi = 0;             ///< pixels per inch
  int width = 0, height = 0;  ///< screenW, screenH, pixels
  bool flip_x = false, flip_y = false, flip_subp = false;
};

/// Parses a calibration. Throws std::runtime_error naming the file and the
/// field: not JSON, a field missing or not a number, impossible values
/// (non-positive pitch, DPI or size, zero slope, a cone outside (0, 180)).
LookingGlassCalibration parse_looking_glass(std::string_view json, const std::string& source);
LookingGlassCalibration read_looking_glass(const std::string& path);

/// f for subpixel s (0 R, 1 G, 2 B) of pixel (i, j), j from the top: in [0, 1).
double looking_glass_view(const LookingGlassCalibration& c, int i, int j, int s);

/// The native panel traced directly: sample (3i + s, j) is subpixel s of
/// pixel (i, j), traced along the sheared view of its angle through the
/// pixel's centre in a view of the panel's size. `centre` is the scene's
/// own view (its size is replaced by the panel's).
class LookingGlassCamera final : public Camera {
 public:
  LookingGlassCamera(const LookingGlassCalibration& c, const PinholeDesc& centre);
  int width() const override { return 3 * c_.width; }
  int height() const override { return c_.height; }
  PixelLine line(int c, int j, double u = 0.5, double v = 0.5) const override;
  /// Forward projection is not offered (one view per subpixel): throws std::logic_error.
  void project(const Vec3& p_world, std::vector<PanelHit>& out) const override;
  const LookingGlassCalibration& calibration() const { return c_; }

 private:
  LookingGlassCalibration c_;
  PinholeDesc centre_;
  Frame frame_;            // the centre view's: x right, y up, z toward the eye
  double distance_ = 0;    // |at - from|
  double pixel_ = 0;       // one pixel on the image plane at distance 1
};

/// The native panel made from a quilt (the interlacing path): each subpixel
/// takes its channel from the quilt's views around its angle, linearly
/// between views k and k + 1 at x = f (N - 1), bilinearly within a view at
/// the pixel's centre. Throws std::invalid_argument when the quilt image is
/// not C*w x R*h of `q`.
ImageBuffer interlace_quilt(const ImageBuffer& quilt, const QuiltDesc& q, const LookingGlassCalibration& c);

}  // namespace holoray
