// holoray public API: looking at finished images without a display: an
// EIA's sub-aperture views, what an eye sees on a display, a Looking Glass's
// panel from a quilt. Images in and out as api::Image (row 0 at the top).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "holoray/camera.hpp"
#include "holoray/export.hpp"
#include "holoray/image.hpp"

namespace holoray::api {

/// An EIA file's lens layout, known from its grid and pixels per lens alone
/// (pitch and gap do not move its pixels): lens counts from its size.
struct EiaLayout {
  Grid grid = Grid::square;
  int pixels_per_lens = 8;  ///< P
};

/// Pixel (u, v) of every elemental image (contract, property 1; u column, v
/// row in the lens, 0..P-1, -1: P/2): Nx x Ny (square, hex), Nx x H
/// (lenticular). Throws std::invalid_argument, naming `pixels_per_lens`,
/// `u` or `v`, when the EIA's size is not whole lenses or (u, v) is outside.
HOLORAY_API Image subaperture_view(const Image& eia, const EiaLayout& layout, int u = -1, int v = -1);
/// Every sub-aperture view tiled, view (u, v) at tile column u, row v (the
/// viewer's left at column 0; lenticular: one row of P tiles).
HOLORAY_API Image view_grid(const Image& eia, const EiaLayout& layout);
/// The horizontal views of the middle row, left to right and back (2P - 2
/// frames; one when P = 1): a parallax sweep, for write_animation.
HOLORAY_API std::vector<Image> view_sweep(const Image& eia, const EiaLayout& layout);

/// Where the eye is and how finely it looks (docs/guide/displays.md).
struct SimulateOptions {
  std::array<double, 3> eye_mm{0, 0, 600};  ///< display frame, mm, z > 0 in front
  int width = 800;    ///< output pixels across the panel (height keeps its aspect)
  int samples = 3;    ///< samples per output pixel along each axis (the eye's integration)
};
/// What an eye sees of `panel` (the display's native image, RGB or grey)
/// through the lens sheet of the display file `display_path`
/// (display-files.md). Throws SceneError for a malformed display file,
/// std::invalid_argument for a panel of another size or an eye behind it.
HOLORAY_API Image simulate_view(const Image& panel, const std::string& display_path, const SimulateOptions& options = {});

/// A quilt's views as its file name tells Looking Glass tools
/// (NAME_qsCxRaASPECT.ext): C x R views of w x h pixels.
struct QuiltLayout {
  int columns = 8, rows = 6;
  int view_width = 420, view_height = 560;
  double view_cone_deg = 40;
};
/// `path` with the quilt's _qsCxRaASPECT before the extension.
HOLORAY_API std::string quilt_file_name(const std::string& path, const QuiltLayout& layout);
/// The native panel of the Looking Glass whose calibration file (visual.json)
/// is `calibration_path`, made from a quilt of `columns` x `rows` views as
/// the device's software makes it. Throws SceneError for a malformed
/// calibration, std::invalid_argument when the image is not columns x rows
/// views of whole pixels.
HOLORAY_API Image interlace_quilt(const Image& quilt, int columns, int rows, const std::string& calibration_path);

}  // namespace holoray::api
