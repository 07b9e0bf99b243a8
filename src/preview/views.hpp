// holoray/preview: an EIA's sub-aperture views (contract, property 1) for
// looking at its parallax without a display (issue 14, item 4): all of them
// as one grid, or a sweep across the horizontal ones as an animation.
#pragma once

#include <vector>

#include "camera/lens_array.hpp"
#include "image/image.hpp"

namespace holoray {

/// Every view (u, v) of the EIA, tiled: view (u, v) at tile column u, row v
/// (square and hex: P x P tiles of Nx x Ny; lenticular: P x 1 tiles of
/// Nx x H). The viewer's left is tile column 0. Throws as extract_subaperture.
ImageBuffer view_grid(const ImageBuffer& eia, const LensArray& camera);

/// The horizontal views of the middle row v = P/2, left to right and back
/// (2P - 2 frames; one frame when P = 1): a parallax sweep.
std::vector<ImageBuffer> view_sweep(const ImageBuffer& eia, const LensArray& camera);

}  // namespace holoray
