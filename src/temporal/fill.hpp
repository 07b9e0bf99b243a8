// holoray/temporal: filling the missed pixels of a reprojected frame (paper
// §5): every status below zero (missed, leak, rejected) is filled.
#pragma once

#include "camera/lens_array.hpp"
#include "render/render_context.hpp"
#include "temporal/reproject.hpp"

namespace holoray {

enum class Fill {
  trace,       ///< ray trace exactly those pixels (one sample at the centre)
  interpolate  ///< the paper: mean of the valid 8-neighbours in the same elemental
               ///< image on the surface most of them show, grown ring by ring;
               ///< holes whose line misses the scene's bounds are background
               ///< (exact, no ray); pixels with no neighbour on a surface are traced
};

/// Fills `frame` in place; the scene must be at the frame's time.
void fill_missed(const RenderContext& scene, const LensArray& camera, Fill fill, int threads, ReprojectedFrame& frame);

}  // namespace holoray
