// holoray/render: a quilt's views sharing their path samples (issue 70).
//
// A quilt's neighbouring views see mostly the same points from directions a
// fraction of a degree apart. The paper reuses a point image's colour in
// the next frame (§4); here a path sample's first vertex x, with the light
// gathered there (FirstVertexRecord), is taken by every neighbouring view
// that sees x, its BSDF evaluated again for that view's eye: an unbiased
// estimate of x's radiance toward it (path_tracer.hpp). Each pixel thus
// averages its own samples and those of up to 2 S neighbours.
//
// A view takes x at a pixel when x projects into it and lies on the surface
// the pixel's centre ray meets: within one pixel's footprint of that
// surface's tangent plane, its normal within 37 degrees (a z-buffer test,
// the paper's, against a first pass of one centre ray per pixel). The
// pixel's own samples are split by the same test: the n_s of its spp that
// land on that surface are pooled with the m it took, and the others (the
// background, another object past a silhouette, a mirror) stand alone:
//
//   colour = (n_s / spp) (own on the surface + taken) / (n_s + m) + (own others) / spp
//
// so a pixel over an edge keeps its coverage, and the surface's share is
// the mean of 1 + 2S views' samples where they see it. Pooling every
// shareable sample instead biased silhouettes and edges (a floor of 33 dB
// where the unshared image reached 38: tests/test_view_sharing.cpp).
// A point is seen on the same row of every view, so one task traces one
// row of all the views and keeps every sample it shares: each pixel's sums
// are added in one order, and the image is the same bit for bit for any
// thread count, without atomics (which, with the cache misses of writing
// across the quilt, took 8 % more time: the room at 2 samples, 8 views a
// side).
#pragma once

#include "camera/quilt_camera.hpp"
#include "render/render_context.hpp"
#include "render/renderer.hpp"

namespace holoray {

/// The most neighbours on each side a view takes samples from (the
/// public kMaxShareViews).
inline constexpr int kMaxSharedViews = 16;

/// Bytes render_quilt_shared holds besides the frame for a quilt of
/// `pixels`: the first pass's points and each pixel's own and taken sums.
/// Computed without allocating, for the memory bound.
uint64_t shared_views_bytes(int64_t pixels);

/// Renders `camera`'s quilt under the path integrator, each view taking the
/// samples of `opt.share_views` (1 to kMaxSharedViews) views on each side,
/// in view order. Throws std::invalid_argument under Whitted's integrator,
/// for a band of rows (RenderOptions::rows) or a share outside that range.
FrameBuffers render_quilt_shared(const RenderContext& scene, const QuiltCamera& camera, const RenderOptions& opt,
                                 RenderStats& stats);

}  // namespace holoray
