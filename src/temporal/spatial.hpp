// holoray/temporal: spatial reuse (issue 4). Neighbouring elemental images
// see nearly the same points, so a still frame can be built like a
// reprojected one, with the frame itself as its own keyframe:
//
// 1. trace every k-th lens across and down (RenderOptions::lens_stride), with
//    their primary hits: a sparse point image;
// 2. forward-project its points into the lenses around their own, where the
//    untraced lenses are (reproject(), Reach::lenses; Reach::all would
//    project each into every lens that sees it, tens to hundreds, and cost
//    more than tracing), with the same z-buffer, leak detection and exact
//    local visibility check as temporal reprojection; the traced lenses keep
//    their pixels;
// 3. fill what no point reached, or what failed the checks (fill_missed).
//
// With Reuse::geometry each reused hit is shaded again through its own pixel,
// so the pixel equals full ray tracing wherever the visible surface was among
// the primitives that landed there; Reuse::color keeps the traced lens's
// colour (view-dependent light then comes from the wrong direction).
#pragma once

#include "camera/lens_array.hpp"
#include "render/render_scene.hpp"
#include "temporal/fill.hpp"
#include "temporal/reproject.hpp"

namespace holoray {

struct SpatialOptions {
  int stride = 2;  ///< trace every stride-th lens across and down (>= 2)
  Reuse reuse = Reuse::geometry;
  Fill fill = Fill::trace;
  int threads = 0;  ///< 0: all cores
};

/// The frame with how each pixel was made (frame.status: reused pixels are
/// `reprojected`; the traced lenses' pixels and the filled ones `traced`,
/// or `interpolated` for Fill::interpolate), and the sparse trace's cost.
struct SpatialFrame {
  ReprojectedFrame frame;      ///< colour, status per pixel, rays spent reusing and filling
  size_t sparse_pixels = 0;    ///< pixels of the traced lenses (status `traced`, as are filled ones)
  RayCounts sparse_rays;       ///< rays of the traced lenses
  double sparse_seconds = 0;   ///< tracing the lens subset
};

/// Renders `camera`'s EIA of `scene` by spatial reuse. Throws
/// std::invalid_argument for a stride below 2.
SpatialFrame render_spatial(const RenderScene& scene, const LensArray& camera, const SpatialOptions& options);

}  // namespace holoray
