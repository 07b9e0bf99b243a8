// holoray/display: Looking Glass displays from their calibration file (the
// device's visual.json), mapped exactly as the device's own software maps
// them: the fragment shader of Looking Glass's WebXR package
// (npm @lookingglass/webxr 0.6.0, dist/bundle/webxr.js, function Shader and
// the pitch, tilt and subp getters of its config). With the panel W x H,
// pixel (i, j) (j from the top), subpixel s = 0, 1, 2 (R, G, B):
//
//   u = (i + 1/2) / W,  v = (H - j - 1/2) / H          pixel centre, v up (GL)
//   P    = pitch * W / DPI * cos(atan(1 / slope))      lenticules across the width
//   tilt = H / (W * slope),  subp = 1 / (3 W)          both negated by flipImageX
//   a = (u + s * subp + v * tilt) * P - center         no subpixelCells
//   a = ((u + dx_s / W) + (v + dy_s / H) * tilt) * P - center
//                                                      subpixelCells: the offsets (dx, dy) of
//                                                      subpixel s in the pixel's cell
//   x = clamp(1 - fract(a), 0.00001, 0.999999)         the subpixel's view value
//
// A quilt of N views shows view k where x N = k: the default view filter
// blends view floor(x N) toward view floor(x N) + 1 by fract(x N), and the
// last view toward view 0 (the quilt texture repeats). invView, flipImageY
// and flipSubp are read but, as in that shader, not used.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "camera/camera.hpp"
#include "camera/pinhole.hpp"
#include "camera/pixel_lines.h"
#include "camera/quilt_camera.hpp"
#include "image/image.hpp"

namespace holoray {

/// One subpixel cell of a calibration (its "subpixelCells" entry): where the
/// R, G and B subpixels sit relative to the pixel, panel pixels, x right, y up.
struct SubpixelCell {
  double dx[3] = {0, 0, 0}, dy[3] = {0, 0, 0};
};

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
  /// Newer devices' per-subpixel offsets; empty: the even RGB stripe (subp).
  std::vector<SubpixelCell> cells;
  /// Which cell a pixel uses (the shader's cellPatternType, 0 to 4): the
  /// file's CellPatternMode, else 1 (the package's default subpixelMode).
  int cell_pattern = 1;
};

/// At most this many subpixel cells: the shader holds 60 floats of them.
inline constexpr int kMaxSubpixelCells = 10;

/// Parses a calibration. Throws std::runtime_error naming the file and the
/// field: not JSON, a field missing or not a number, impossible values
/// (non-positive pitch, DPI or size, zero slope, a cone outside (0, 180),
/// more than kMaxSubpixelCells cells, a cell pattern outside 0 to 4).
LookingGlassCalibration parse_looking_glass(std::string_view json, const std::string& source);
LookingGlassCalibration read_looking_glass(const std::string& path);

/// The cell (index into c.cells) of pixel (i, j), j from the top: the
/// shader's GetCellForPixel. 0 when there are no cells.
int looking_glass_cell(const LookingGlassCalibration& c, int i, int j);

/// The view value x of subpixel s (0 R, 1 G, 2 B) of pixel (i, j), j from
/// the top: in [0.00001, 0.999999] (the mapping above).
double looking_glass_view(const LookingGlassCalibration& c, int i, int j, int s);

/// The views of a quilt that the device software's default view filter
/// (OldViewFiltering) blends for view value x: colour = (1 - w) view[first]
/// + w view[second], second = first + 1 but 0 after the last view.
struct ViewBlend {
  int first = 0, second = 0;
  double w = 0;
};
ViewBlend looking_glass_blend(double x, int views);

/// The quilt views a native panel image is the continuous version of
/// (render and animate --looking-glass; --views): the device software's
/// default quilt for the portrait class, 8 x 6.
inline constexpr int kDefaultLookingGlassViews = 48;

/// The native panel traced directly: sample (3i + s, j) is subpixel s of
/// pixel (i, j), traced through the pixel's centre along the sheared view
/// (quilt_camera.hpp) of an N-view quilt at the continuous view index x N:
/// angle (x N / (N - 1) - 1/2) viewCone. Where x N is a whole number k that
/// is quilt view k's own pixel, so tracing natively and interlacing an N-view
/// quilt agree there. `centre` is the scene's own view (its size is
/// replaced by the panel's). Throws std::invalid_argument for views < 1.
class LookingGlassCamera {
 public:
  LookingGlassCamera(const LookingGlassCalibration& c, const PinholeDesc& centre, int views = kDefaultLookingGlassViews);
  int width() const { return 3 * c_.width; }
  int height() const { return c_.height; }
  PixelLine line(int c, int j, double u = 0.5, double v = 0.5) const;
  /// Forward projection is not offered (one view per subpixel): throws std::logic_error.
  void project(const Vec3& p_world, std::vector<PanelHit>& out) const;
  const LookingGlassCalibration& calibration() const { return c_; }
  /// The centre view (the panel's size), its frame (x right, y up, z toward
  /// the eye; world), |at - from| (scene units), one pixel's size on the
  /// image plane at distance 1, and the quilt's views: what line() reads,
  /// for a renderer that generates the lines elsewhere (the GPU path).
  const PinholeDesc& centre() const { return centre_; }
  const Frame& frame() const { return frame_; }
  double distance() const { return distance_; }
  double pixel_size() const { return pixel_; }
  int views() const { return views_; }

  /// The constants its lines are computed from (camera/line_constants.h),
  /// which the GPU's kernel reads too (gpu/shaders/layout.h, GpuFrame).
  const camera_lines::HrLookingGlass& line_constants() const { return lines_; }

 private:
  LookingGlassCalibration c_;
  PinholeDesc centre_;
  Frame frame_;            // the centre view's: x right, y up, z toward the eye
  double distance_ = 0;    // |at - from|
  double pixel_ = 0;       // one pixel on the image plane at distance 1
  int views_ = kDefaultLookingGlassViews;
  camera_lines::HrLookingGlass lines_{};  // as the shared line function takes it (camera/pixel_lines.h)
};
static_assert(PixelCamera<LookingGlassCamera>);

/// The native panel made from a quilt as the device software makes it: each
/// subpixel's channel is looking_glass_blend of two views, each read as the
/// shader reads its quilt texture (bilinear, repeating at the quilt's
/// edges, at the pixel's centre within the view, with the shader's column
/// count nudged by 0.00001). Throws std::invalid_argument when the quilt
/// image is not C*w x R*h of `q`.
ImageBuffer interlace_quilt(const ImageBuffer& quilt, const QuiltDesc& q, const LookingGlassCalibration& c);

}  // namespace holoray
