// holoray/temporal: reverse reprojection of point images (Nehab, Sander,
// Lawrence, Tatarchuk and Isidoro, "Accelerating Real-Time Shading with
// Reverse Reprojection Caching", Graphics Hardware 2007), for the integral
// camera. The alternative to the paper's forward splat (reproject.hpp):
//
// 1. Every pixel of the frame traces its own eye ray, in 16-ray packets per
//    elemental image as full tracing does, so visibility, silhouettes, the
//    slab near the array and the background are exact and nothing is missed
//    or filled. Colour reuse looks up Embree's unrefined hit (RawHit) and
//    refines only the hits it shades. Two exceptions copy instead, where
//    nothing can have changed: a frame with a keyframe's camera in which
//    nothing moved (a hold) is that keyframe; with a keyframe's camera and
//    colour reuse, an elemental image whose lines cannot reach a moved
//    object is the keyframe's (ReverseOptions::copy_unchanged).
// 2. Only the shading is reused. The hit is moved to each keyframe's time by
//    its object's transforms (object space, as the point image records it)
//    and projected through the keyframe's integral camera into the lens that
//    looks along the pixel's own line direction (contract, property 2;
//    LensArray::project_along): the keyframe pixel that saw this surface
//    point from the nearest direction.
// 3. That keyframe pixel is used when it saw the same object at the same
//    depth along its line (within ReverseOptions::same_surface pixel
//    footprints); else the other keyframe is tried; else the hit is shaded
//    exactly, as full tracing would. Those hits are gathered from successive
//    packets and shaded 16 at a time: a packet's shadow and mirror rays cost
//    about as much with a few lanes active as with all 16.
//
// What is reused (ReverseReuse):
// - `color`: the keyframe's colour (the paper's colour reuse), filtered
//   bilinearly over the 2 x 2 keyframe pixels around the landing point that
//   saw the same surface. Shading is as seen from the keyframe's lens at its
//   sample points: an EIA pixel covers s*|t|/g of the scene, so on detailed
//   surfaces this is the error.
// - `visibility`: only what the keyframe's rays found: which lights its point
//   saw, and the light its mirror and refraction rays brought. Ambient,
//   diffuse and highlight terms are computed at the pixel's own hit
//   (shade_local), so only shadow edges and reflections carry the
//   keyframe's sampling. Used only while no object moved since the keyframe
//   (a moved occluder would leave a stale shadow) and for scenes of at most
//   kMaxPartLights lights; otherwise the hit is shaded.
#pragma once

#include "camera/lens_array.hpp"
#include "render/render_context.hpp"
#include "temporal/point_image.hpp"
#include "temporal/reproject.hpp"

namespace holoray {

enum class ReverseReuse { color, visibility };

struct ReverseOptions {
  ReverseReuse reuse = ReverseReuse::color;
  int threads = 0;  ///< 0: all cores
  /// Same surface: the keyframe pixel's depth within this many pixel
  /// footprints (s * |t| / g) of the projected point's.
  double same_surface = 2.0;
  /// A frame with a keyframe's camera copies from that keyframe what cannot
  /// have changed, without a ray: the whole image when every object is
  /// where that keyframe saw it (a hold: exact); with colour reuse on a
  /// square grid, each elemental image none of whose lines can reach an
  /// object that moved (a locked-off shot: what the lookups would give).
  /// False sends every pixel through the lookups (their tests).
  bool copy_unchanged = true;
};

/// Traces the keyframe `frame` seen by `camera` (the scene at its time) into
/// a point image, with the ShadeParts that `reuse` needs. `stats` gets its
/// rays and seconds. The colour equals render_frame()'s bit for bit.
PointImage trace_point_image(const RenderContext& scene, const LensArray& camera, int frame, ReverseReuse reuse,
                             int threads, RenderStats& stats);

/// Builds frame `frame`, seen by `camera`, from keyframes `prev` and `next`
/// (either may be null, not both; the nearer in time is tried first) by
/// reverse reprojection; `scene` must already be at that frame. A frame
/// identical to a keyframe (same camera, nothing moved) is that keyframe
/// (ReverseOptions::copy_unchanged). Status per pixel: `reprojected`
/// (reused) or `traced` (shaded, or background); never missed. Throws std::invalid_argument for a keyframe of another size, with
/// no transforms, or without the parts `options.reuse` needs.
ReprojectedFrame reverse_reproject(const RenderContext& scene, const LensArray& camera, int frame,
                                   const PointImage* prev, const PointImage* next, const ReverseOptions& options);

}  // namespace holoray
