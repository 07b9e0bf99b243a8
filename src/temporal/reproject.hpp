// holoray/temporal: builds a frame between two keyframes from their point
// images (paper §4, §5), exactly where it can be checked and by tracing where
// it cannot.
//
// 1. Splat: every keyframe point is moved to the frame's time by its object's
//    transform and forward-projected through the frame's integral camera
//    (contract, property 2). `Reach::all` projects into every lens that sees
//    it, as the paper does; `Reach::near` (default) only into the lens where
//    the line through the moved point, in the direction the keyframe pixel
//    saw it, crosses the array (and the neighbour it lands in from there):
//    an image warp per elemental image, about one projection per point
//    instead of one per lens that sees it, which is what makes it pay.
// 2. Z-buffer per keyframe: the point nearest the viewer wins (largest t
//    orthoscopic, smallest t > 0 pseudoscopic), less a penalty of two pixel
//    footprints per pixel of distance from the pixel centre, so that on one
//    surface the best-centred point wins. One 64-bit atomic max per landing:
//    the result does not depend on the thread count.
// 3. Merge: when both keyframes give the same surface (same object, depth
//    within 4 footprints) colours blend by time distance; else the nearer wins.
// 4. Leaks: a point seen through a gap between a nearer surface's points
//    has neighbours on two opposite sides of it (up to two pixels out, same
//    elemental image) nearer by more than 4 footprints (a depth
//    discontinuity): marked missed. A pixel with a nearer neighbour on one
//    side only (behind a silhouette) gets an occlusion ray from the viewer's
//    side to its hit in step 5, and is missed if something is in front.
// 5. Local visibility: the pixel's own centre ray is intersected, exactly and
//    without a BVH traversal, with the primitives that landed on and around
//    it (its winner, the other keyframe's candidate, its 8 neighbours'
//    winners); the nearest hit wins, which settles silhouettes and surfaces
//    that cross. No hit marks it missed. `Reuse::geometry` shades that exact
//    hit in the frame's scene: shadows, highlights and reflections follow
//    lights, objects and camera, and the pixel equals full ray tracing
//    whenever the visible surface is among those primitives. `Reuse::color`
//    keeps the keyframe colour (the paper).
//    Near the array (|t| < g) a point is seen by at most one lens and the
//    lens cones leave gaps between them, so a surface there can leave no
//    point in either keyframe and the surface behind it would show instead:
//    one short occlusion ray across that slab, in front of the hit, catches
//    it (ReprojectOptions::check_near_slab).
// 6. Fill (fill.hpp) the missed pixels.
#pragma once

#include <cstdint>
#include <vector>

#include "camera/lens_array.hpp"
#include "image/image.hpp"
#include "render/render_context.hpp"
#include "temporal/point_image.hpp"

namespace holoray {

enum class Reuse { color, geometry };
/// Which lenses a keyframe point is forward-projected into (step 1).
enum class Reach {
  near,    ///< the lens along the direction the keyframe pixel saw it (and its landing neighbour)
  all,     ///< every lens that sees it (the paper)
};

/// Per-pixel outcome of a reprojected frame.
enum class PixelStatus : int8_t {
  reprojected = 1,   ///< a keyframe point, checked
  missed = -1,       ///< no point landed here
  leak = -2,         ///< a point seen through a gap of a nearer surface
  rejected = -3,     ///< the pixel's ray misses the winning primitive
  traced = 2,        ///< filled by ray tracing
  interpolated = 3,  ///< filled from neighbours in its elemental image
};

struct ReprojectOptions {
  Reuse reuse = Reuse::color;
  Reach reach = Reach::near;
  bool detect_leaks = true;
  /// Also try the neighbours' primitives on each pixel's ray (step 5).
  bool local_visibility = true;
  /// Trace one short occlusion ray across the slab |t| < gap in front of
  /// each reprojected hit (see step 5).
  bool check_near_slab = true;
  int threads = 0;  ///< 0: all cores
};

/// A reprojected frame before or after filling.
struct ReprojectedFrame {
  ImageBuffer colour;                 ///< W x H x 3; background colour where not reprojected
  std::vector<PixelStatus> status;    ///< W*H
  std::vector<uint8_t> received;      ///< W*H: 1 where at least one point landed
  std::vector<int32_t> object;        ///< W*H: object id shown (reprojected or traced); -1 background or unknown
  RayCounts rays;                     ///< rays spent shading (geometry reuse) and filling
  /// The keyframe this frame is a copy of (the same camera, nothing moved:
  /// every pixel taken from it, none traced); -1 otherwise.
  int copied_from = -1;
  /// Wall-clock seconds per stage: splat, merge, leaks, check (+ shade), fill.
  struct Seconds {
    double splat = 0, merge = 0, leaks = 0, check = 0, fill = 0;
  } seconds;

  size_t count(PixelStatus s) const;
};

/// Reprojects keyframes `prev` and `next` (either may be null, not both)
/// into the frame `frame` seen by `camera`; `scene` must already be at that
/// frame (RenderScene::set_transforms). Point images record hits in object
/// space, so the scene's current transforms move them. Colours of one
/// surface blend with weight (frame - prev.frame) / (next.frame - prev.frame)
/// on `next`. Throws std::invalid_argument for a keyframe of another size.
ReprojectedFrame reproject(const RenderContext& scene, const LensArray& camera, int frame, const PointImage* prev,
                           const PointImage* next, const ReprojectOptions& options);

}  // namespace holoray
