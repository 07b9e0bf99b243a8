// holoray/python: looking at finished images (holoray/preview.hpp):
// sub-aperture views, what an eye sees on a display, a Looking Glass's panel
// from a quilt; numpy in and out.
#include <pybind11/stl.h>

#include <string>

#include "arrays.hpp"
#include "bindings.hpp"
#include "holoray/pick.hpp"
#include "holoray/preview.hpp"

namespace holoray::python {

void bind_preview(py::module_& m) {
  m.def(
      "subaperture_view",
      [](const py::handle& eia, int pixels_per_lens, const std::string& grid, int u, int v) {
        const api::EiaLayout layout{
            pick<api::Grid>("grid", grid, {{"square", api::Grid::square}, {"hex", api::Grid::hex}, {"lenticular", api::Grid::lenticular}}),
            pixels_per_lens};
        const api::Image image = numpy_to_image(eia, "eia");
        py::gil_scoped_release nogil;
        api::Image view = api::subaperture_view(image, layout, u, v);
        py::gil_scoped_acquire gil;
        return image_to_numpy(view);
      },
      py::arg("eia"), py::arg("pixels_per_lens"), py::arg("grid") = "square", py::arg("u") = -1, py::arg("v") = -1,
      "Pixel (u, v) of every elemental image (-1: P/2), as `holoray subaperture`: (Ny, Nx, C), lenticular (H, Nx, C).");
  m.def(
      "simulate_view",
      [](const py::handle& panel, const std::string& display, const py::handle& eye, int width, int samples) {
        api::SimulateOptions so;
        so.eye_mm = vec3_of(eye, "eye");
        so.width = width;
        so.samples = samples;
        const api::Image image = numpy_to_image(panel, "panel");
        py::gil_scoped_release nogil;
        api::Image seen = api::simulate_view(image, display, so);
        py::gil_scoped_acquire gil;
        return image_to_numpy(seen);
      },
      py::arg("panel"), py::arg("display"), py::arg("eye") = py::make_tuple(0.0, 0.0, 600.0), py::arg("width") = 800,
      py::arg("samples") = 3,
      "What an eye at `eye` (mm, the display's frame) sees of a panel image through the display file's lens sheet, "
      "as `holoray simulate`.");
  m.def(
      "interlace_quilt",
      [](const py::handle& quilt, int columns, int rows, const std::string& calibration) {
        const api::Image image = numpy_to_image(quilt, "quilt");
        py::gil_scoped_release nogil;
        api::Image panel = api::interlace_quilt(image, columns, rows, calibration);
        py::gil_scoped_acquire gil;
        return image_to_numpy(panel);
      },
      py::arg("quilt"), py::arg("columns"), py::arg("rows"), py::arg("calibration"),
      "A Looking Glass's native panel from a quilt of columns x rows views and its calibration (visual.json), as "
      "`holoray interlace`.");
}

}  // namespace holoray::python
