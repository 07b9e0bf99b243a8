// holoray/render: renders an ordinary pinhole view (camera/pinhole.hpp) of a
// scene with the same shading, packets, samples and AOVs as the integral
// renderer (renderer.hpp), for previews and for comparing holoray with other
// ray tracers pixel for pixel (issue 13).
#pragma once

#include "camera/pinhole.hpp"
#include "camera/quilt_camera.hpp"
#include "render/renderer.hpp"

namespace holoray {

/// Renders `camera`'s view of `scene`: per pixel the colour averaged over
/// options.spp samples (sample 0 at the centre; sample_offset), 4 x 4 pixel
/// packets of 16 rays, tiles of 32 x 32 pixels on options.threads workers.
/// The result does not depend on the thread count. AOVs as render_frame's,
/// with depth = the distance from the eye and normals facing it. Rays start
/// at the eye (NFF's hither is not applied, as for the integral camera).
/// options.style, tile_order and primary_hits are ignored. Throws
/// std::invalid_argument when spp < 1 or threads < 0.
FrameBuffers render_view(const RenderContext& scene, const PinholeCamera& camera, const RenderOptions& options,
                         RenderStats& stats);

/// Renders a Looking Glass quilt (camera/quilt_camera.hpp): every view in one
/// pass over the whole quilt image, as render_view renders one view, so the
/// scene is built once and the threads never wait for a view to finish.
/// With one sample per pixel, tile k of the result is render_view of quilt
/// view k (more samples jitter by quilt pixel, not view pixel). With
/// options.share_views, the views share their path samples
/// (render/view_sharing.hpp).
FrameBuffers render_quilt(const RenderContext& scene, const QuiltCamera& camera, const RenderOptions& options,
                          RenderStats& stats);

}  // namespace holoray
