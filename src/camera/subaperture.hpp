// holoray/camera: sub-aperture images (contract, property 1): pixel (u, v) of
// every elemental image, gathered into one image with a pixel per lens. For a
// square grid it is an oblique orthographic view of the scene.
#pragma once

#include "camera/lens_array.hpp"
#include "image/image.hpp"

namespace holoray {

/// Gathers pixel (u, v) of each elemental image of `eia` (u column, v row
/// within the lens, 0..P-1; hex: relative to the lens centre as if the cell
/// were square). Output: Nx x Ny (square, hex; hex odd rows as they fall),
/// or Nx x H (lenticular: every row). Throws std::invalid_argument when the
/// EIA's size differs from the camera's or (u, v) is outside 0..P-1.
ImageBuffer extract_subaperture(const ImageBuffer& eia, const LensArray& camera, int u, int v);

/// The lens array of an EIA file with only its grid and pixels per lens
/// known (pitch and gap do not matter to the pixels' layout): lens counts
/// from the image's size. Throws std::invalid_argument when P < 1 or the
/// width (square grid: and height) is not a multiple of P.
LensArrayDesc eia_layout(int width, int height, Grid grid, int pixels_per_lens);

}  // namespace holoray
