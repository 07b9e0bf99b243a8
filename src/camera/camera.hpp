// holoray/camera: what every camera offers (issue 13): the line a pixel
// records and, the other way, the pixels that record a point; the
// PixelCamera concept says it and each camera's file checks it.
#pragma once

#include <concepts>
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

/// What every camera offers (issue 13): its size in pixels, the line a
/// pixel records and, the other way, every pixel that records a point
/// (appended to `out`, cleared first; line(h.i, h.j, h.u, h.v) passes
/// through the point at parameter h.t: one hit per lens that sees it for an
/// integral camera, at most one for a pinhole). A concept, not a base
/// class: the renderers take the concrete cameras, and their lines come
/// from camera/pixel_lines.h, the text the GPU compiles too.
template <class C>
concept PixelCamera = requires(const C& c, int i, double u, const Vec3& p, std::vector<PanelHit>& out) {
  { c.width() } -> std::convertible_to<int>;
  { c.height() } -> std::convertible_to<int>;
  { c.line(i, i, u, u) } -> std::same_as<PixelLine>;
  c.project(p, out);
};

}  // namespace holoray
