// holoray/camera: an ordinary pinhole camera, the scene's own view (NFF `v`,
// nff-notes §2), for previews and for checking holoray pixel for pixel
// against other ray tracers (issue 13). It shares the integral camera's
// vocabulary: line() gives a pixel's ray, project() the inverse, with the
// same PanelHit, as every camera does (camera.hpp's PixelCamera).
//
// Conventions (nff-notes §2): d = normalize(at - from) looks at the image
// centre; image right r = normalize(d x up), image up u = r x d (right-handed,
// `up` need not be perpendicular to d). `fov_deg` is the full vertical field
// of view, top edge to bottom edge of the image (the "full-image" reading of
// NFF's angle); pixels are square, so the horizontal extent follows the
// aspect ratio. Pixel (i, j): column i from the left, row j from the top;
// offset (u, v) inside it in [0, 1), 0.5 = centre.
#pragma once

#include <numbers>
#include <cmath>

#include "camera/camera.hpp"
#include "camera/pixel_lines.h"
#include "math/vec.hpp"
#include "scene/scene_desc.hpp"

namespace holoray {

/// Everything that fixes a pinhole view. World frame, scene units.
struct PinholeDesc {
  Vec3 from, at, up{0, 1, 0};
  double fov_deg = 45;  ///< full vertical field of view, degrees, in (0, 180)
  int width = 512, height = 512;
  /// Tachyon's left-handed screen: image right = up x d instead of d x up
  /// (Viewpoint::mirrored, tachyon-notes §2).
  bool mirrored = false;
  /// Where in its pixel a sample asked for at offset (0.5, 0.5) goes: the
  /// centre by default; (1, 0), the upper-right corner, is where Tachyon
  /// samples (its renderer numbers pixels from 1 and casts pixel (x, y)
  /// through image-plane point (x, y) from the corner at pixel 0), for
  /// comparing with it pixel for pixel (tachyon-notes §2).
  double sample_u = 0.5, sample_v = 0.5;
  /// An off-axis view: the image window moved right by this much on the
  /// image plane at distance 1 (0: centred on d). A view of a Looking Glass
  /// quilt (quilt_camera.hpp) shifts its eye sideways and its window back,
  /// so that every view shares one focal plane (a sheared frustum).
  double shift_x = 0;
  /// The window moved up by this much on the same plane (a camera's vertical
  /// lens shift, as Blender's shift_y).
  double shift_y = 0;
  /// An orthographic view (a file's orthographic camera, Viewpoint::ortho_size):
  /// the image's full height in scene units, rays parallel to d from the
  /// plane through `from`; `fov_deg` is then unused. 0: perspective.
  double ortho_height = 0;
  /// The clipping range along the view axis (Viewpoint::clip_near, clip_far):
  /// only surfaces between the two planes are seen. 0 to infinity: none.
  double clip_near = 0, clip_far = INFINITY;
};

/// The view a scene's viewpoint describes (NFF `v`, or a Tachyon camera,
/// mirrored), at `width` x `height` pixels.
/// The angle (radians) one pixel of a pinhole view subtends at the centre:
/// 2 tan(fov / 2) / height (RenderSettings::footprint).
/// An orthographic view's pixel subtends no angle: its width seen from the
/// focal distance |at - from| stands in.
inline double pixel_angle(const PinholeDesc& d) {
  if (d.ortho_height > 0) return d.ortho_height / d.height / length(d.at - d.from);
  return 2 * std::tan(d.fov_deg * std::numbers::pi / 360) / d.height;
}

/// The angle (or orthographic extent) the viewpoint gives the image's
/// `fov_axis` side becomes the vertical one of a `width` x `height` image.
inline PinholeDesc view_of(const Viewpoint& vp, int width, int height) {
  PinholeDesc d{vp.from, vp.at, vp.up, vp.vertical_angle_deg(width, height), width, height, vp.mirrored};
  d.ortho_height = vp.vertical_ortho_size(width, height);
  d.clip_near = vp.clip_near;
  d.clip_far = vp.clip_far;
  return d;
}

/// A pinhole camera. Immutable after construction; safe to share between threads.
class PinholeCamera {
 public:
  /// Validates and precomputes. Throws std::invalid_argument naming the bad
  /// value: `from` equal to `at`, `up` parallel to the view direction, a
  /// field of view outside (0, 180) degrees, sizes below 1 or over 2^30 pixels.
  explicit PinholeCamera(const PinholeDesc& desc);

  const PinholeDesc& desc() const { return desc_; }
  int width() const { return desc_.width; }
  int height() const { return desc_.height; }
  int64_t pixel_count() const { return static_cast<int64_t>(desc_.width) * desc_.height; }
  /// The view axis d (unit, world): the clipping planes are perpendicular to it.
  Vec3 axis() const { return -frame_.z; }
  /// The eye's frame (world): x image right, y image up, z toward the eye.
  const Frame& frame() const { return frame_; }
  /// One pixel's size on the image plane at distance 1 (orthographic: in
  /// scene units): what line() steps by.
  double pixel_size() const { return pixel_; }

  /// The ray of pixel (i, j) at offset (u, v): origin `from`, unit direction
  /// (world frame). The line parameter t is the distance from the eye.
  PixelLine line(int i, int j, double u = 0.5, double v = 0.5) const;
  /// Where a world point appears: true and `out` (pixel, offset, t = its
  /// distance along the pixel's ray) when it lies in front of the eye and
  /// inside the image. The exact inverse of line().
  bool project(const Vec3& p_world, PanelHit& out) const;
  /// Camera::project: the one pixel of project(p, PanelHit&), if any.
  void project(const Vec3& p_world, std::vector<PanelHit>& out) const;

  /// The constants its lines are computed from (camera/line_constants.h),
  /// which the GPU's kernel reads too (gpu/shaders/layout.h, GpuFrame).
  const camera_lines::HrPinhole& line_constants() const { return lines_; }

 private:
  PinholeDesc desc_;
  Frame frame_;            // x = image right, y = image up, z = -d (toward the eye)
  double pixel_ = 0;       // one pixel's size on the image plane at distance 1
  camera_lines::HrPinhole lines_{};  // the view as the shared line function takes it (camera/pixel_lines.h)
};
static_assert(PixelCamera<PinholeCamera>);

}  // namespace holoray
