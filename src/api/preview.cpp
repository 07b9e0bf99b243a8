// The public preview tools (holoray/preview.hpp) over camera/subaperture,
// preview/ and display/looking_glass.
#include "holoray/preview.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "api/internal.hpp"
#include "camera/quilt_camera.hpp"
#include "camera/subaperture.hpp"
#include "preview/simulate.hpp"
#include "preview/views.hpp"

namespace holoray::api {

namespace {

using detail::ImageAccess;

// The lens array of an EIA of this size (camera/subaperture.hpp's eia_layout).
holoray::LensArray lens_array_of(const Image& eia, const EiaLayout& layout) {
  if (eia.empty()) throw std::invalid_argument("the EIA is empty");
  const holoray::Grid grid = layout.grid == Grid::hex          ? holoray::Grid::hex
                             : layout.grid == Grid::lenticular ? holoray::Grid::lenticular
                                                               : holoray::Grid::square;
  return holoray::LensArray(eia_layout(eia.width(), eia.height(), grid, layout.pixels_per_lens));
}

}  // namespace

Image subaperture_view(const Image& eia, const EiaLayout& layout, int u, int v) {
  const holoray::LensArray lenses = lens_array_of(eia, layout);
  const int half = layout.pixels_per_lens / 2;
  return ImageAccess::wrap(extract_subaperture(ImageAccess::buffer(eia), lenses, u < 0 ? half : u, v < 0 ? half : v));
}

Image view_grid(const Image& eia, const EiaLayout& layout) {
  const holoray::LensArray lenses = lens_array_of(eia, layout);
  return ImageAccess::wrap(holoray::view_grid(holoray::as_rgb(ImageAccess::buffer(eia)), lenses));
}

std::vector<Image> view_sweep(const Image& eia, const EiaLayout& layout) {
  const holoray::LensArray lenses = lens_array_of(eia, layout);
  std::vector<Image> frames;
  for (ImageBuffer& f : holoray::view_sweep(holoray::as_rgb(ImageAccess::buffer(eia)), lenses))
    frames.push_back(ImageAccess::wrap(std::move(f)));
  return frames;
}

Image simulate_view(const Image& panel, const std::string& display_path, const SimulateOptions& options) {
  if (panel.empty()) throw std::invalid_argument("simulate_view: the panel image is empty");
  holoray::SimulateOptions so;
  so.eye_mm = {options.eye_mm[0], options.eye_mm[1], options.eye_mm[2]};
  so.width = options.width;
  so.samples = options.samples;
  const DisplayDesc display = read_display(display_path);
  return ImageAccess::wrap(holoray::simulate_view(holoray::as_rgb(ImageAccess::buffer(panel)), display, so));
}

std::string quilt_file_name(const std::string& path, const QuiltLayout& layout) {
  return holoray::quilt_file_name(
      path, QuiltDesc{layout.columns, layout.rows, layout.view_width, layout.view_height, layout.view_cone_deg});
}

Image interlace_quilt(const Image& quilt, int columns, int rows, const std::string& calibration_path) {
  if (columns < 1 || rows < 1 || int64_t{columns} * rows > 4096)
    throw std::invalid_argument(fmt::format("quilt: expected 1 to 4096 views, got {}x{}", columns, rows));
  const LookingGlassCalibration cal = read_calibration(calibration_path);
  if (quilt.empty() || quilt.width() % columns || quilt.height() % rows)
    throw std::invalid_argument(fmt::format("a {}x{} image is not {}x{} views of whole pixels", quilt.width(),
                                            quilt.height(), columns, rows));
  const QuiltDesc q{columns, rows, quilt.width() / columns, quilt.height() / rows, cal.view_cone_deg};
  return ImageAccess::wrap(holoray::interlace_quilt(ImageAccess::buffer(quilt), q, cal));
}

}  // namespace holoray::api
