// holoray/camera: the one interface every camera offers (issue 13): the
// line a pixel records and, the other way, the pixels that record a point.
// The integral camera (lens_array.hpp) and the pinhole camera (pinhole.hpp)
// implement it; renderers take the concrete (final) classes, so their hot
// loops pay no virtual call.
#pragma once

#include <vector>

#include "math/vec.hpp"

namespace holoray {

/// The line a pixel records along: L(t) = origin + t*dir (world frame; dir
/// unit). Integral camera: origin is the lens centre c (square, hex) or the
/// crossing point q on the lens plane (lenticular), dir toward +z of the
/// array. Pinhole: origin is the eye, t the distance from it.
struct PixelLine {
  Vec3 origin;
  Vec3 dir;
};

/// Where a scene point lands on the image: pixel (i, j), the position inside
/// it (u, v in [0,1), 0.5 = centre; the same meaning as the offsets of
/// Camera::line) and the point's line parameter t.
struct PanelHit {
  int i = 0, j = 0;
  double u = 0.5, v = 0.5;
  double t = 0;
};

class Camera {
 public:
  virtual ~Camera() = default;
  virtual int width() const = 0;   ///< pixels
  virtual int height() const = 0;  ///< pixels
  /// The line of pixel (i, j) at offset (u, v) inside it (world frame).
  virtual PixelLine line(int i, int j, double u = 0.5, double v = 0.5) const = 0;
  /// Every pixel whose line passes through the world point, appended to
  /// `out` (cleared first): line(h.i, h.j, h.u, h.v) passes through it at
  /// parameter h.t. An integral camera gives one per lens that sees it, a
  /// pinhole at most one.
  virtual void project(const Vec3& p_world, std::vector<PanelHit>& out) const = 0;
};

}  // namespace holoray
