// holoray/python: the light-field page (holoray/web.hpp) from a render's
// Result or from an image array: `holoray web` from Python.
#include <pybind11/stl.h>

#include <optional>
#include <string>
#include <variant>

#include "arrays.hpp"
#include "bindings.hpp"
#include "holoray/pick.hpp"
#include "holoray/web.hpp"
#include "result.hpp"

namespace holoray::python {

namespace {

api::Encoding encoding_of(const std::string& text) {
  return pick<api::Encoding>("encoding", text, {{"linear", api::Encoding::linear}, {"srgb", api::Encoding::srgb}});
}

}  // namespace

void bind_web(py::module_& m) {
  m.def(
      "write_web",
      [](const py::handle& result, const std::string& dir, const std::string& name, std::optional<std::string> encoding,
         std::optional<int> pixels_per_lens, const std::string& grid, std::optional<std::pair<int, int>> quilt,
         std::optional<std::string> looking_glass) {
        // A Result says its camera and its scene's encoding; an array needs them told.
        api::Image image;
        std::optional<api::Camera> camera;
        api::Encoding chosen = api::Encoding::srgb;
        if (py::isinstance<PyResult>(result)) {
          const PyResult& r = result.cast<const PyResult&>();
          image = numpy_to_image(r.colour, "result.colour");
          camera = camera_of(r.camera, "result.camera");
          chosen = r.encoding;
        } else {
          image = numpy_to_image(result, "result");
          if (quilt) {
            api::Quilt q;
            q.columns = quilt->first, q.rows = quilt->second;
            camera = q;
          } else if (pixels_per_lens) {
            api::LensArray a;
            a.grid = pick<api::Grid>("grid", grid, {{"square", api::Grid::square}, {"hex", api::Grid::hex}, {"lenticular", api::Grid::lenticular}});
            a.pixels_per_lens = *pixels_per_lens;
            camera = a;
          } else {
            throw py::value_error("result: an image array needs pixels_per_lens (an EIA) or quilt=(columns, rows)");
          }
        }
        if (encoding) chosen = encoding_of(*encoding);
        const auto* lenses = std::get_if<api::LensArray>(&*camera);
        const auto* quilt_camera = std::get_if<api::Quilt>(&*camera);
        if (!lenses && !quilt_camera)
          throw py::value_error("result: a page shows an EIA (LensArray) or a quilt (Quilt), not this camera's image");
        if (looking_glass && !quilt_camera)
          throw py::value_error("looking_glass: a Looking Glass shows a quilt, not this camera's image");
        py::gil_scoped_release nogil;
        if (lenses)
          api::write_web_eia(image, api::EiaLayout{lenses->grid, lenses->pixels_per_lens}, dir, name, chosen);
        else
          api::write_web_quilt(image, quilt_camera->columns, quilt_camera->rows, dir, name, chosen, looking_glass.value_or(""));
      },
      py::arg("result"), py::arg("dir"), py::kw_only(), py::arg("name") = "holoray", py::arg("encoding") = py::none(),
      py::arg("pixels_per_lens") = py::none(), py::arg("grid") = "square", py::arg("quilt") = py::none(),
      py::arg("looking_glass") = py::none(),
      "Writes the light-field page of a Result (an EIA or a quilt) or of an image array into dir, as `holoray web`: "
      "open it with `holoray web --serve DIR` (docs/guide/web.md). encoding: 'linear' or 'srgb' (default: a Result's "
      "scene's, as `holoray render` writes it; 'srgb' for an array of linear light). An array needs pixels_per_lens "
      "(and grid) or quilt=(columns, rows). looking_glass: a calibration (visual.json) for a quilt's Looking Glass window.");
}

}  // namespace holoray::python
