// holoray/python: the `_holoray` extension module, the compiled half of the
// `holoray` package (python/holoray/__init__.py is the other). Exceptions
// are mapped here: SceneError (a ValueError with file, line, column),
// std::system_error to OSError by its errno (FileNotFoundError,
// PermissionError, ...), std::invalid_argument to ValueError with the API's
// `names` said as this module's keywords, std::length_error to ValueError
// (pybind11's own).
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>

#include "arrays.hpp"
#include "bindings.hpp"
#include "holoray/holoray.hpp"

namespace py = pybind11;
using namespace holoray;

namespace {

// This module's keywords are the C++ API's names but for fov_lens_deg and
// the animation's reference (fov_lens, report).
std::string in_keyword_words(std::string_view message) {
  return api::say_names(message, [](std::string_view name) {
    if (name == "fov_lens_deg") return std::string("fov_lens");
    if (name == "reference") return std::string("report");
    return std::string(name);
  });
}

}  // namespace

PYBIND11_MODULE(_holoray, m) {
  m.doc() = "holoray's compiled module: use the `holoray` package.";
  m.attr("__version__") = api::version();

  static py::exception<api::SceneError> scene_error(m, "SceneError", PyExc_ValueError);
  scene_error.doc() = "A malformed scene, shot, display or calibration file: str(e) is 'file:line:col: error: ...', "
                      "the offending line and a caret; e.file, e.line, e.column.";
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const api::SceneError& e) {
      py::object instance = py::reinterpret_borrow<py::object>(scene_error.ptr())(e.what());
      instance.attr("file") = e.file();
      instance.attr("line") = e.line();
      instance.attr("column") = e.column();
      PyErr_SetObject(scene_error.ptr(), instance.ptr());
    } catch (const api::Cancelled& e) {
      PyErr_SetString(PyExc_KeyboardInterrupt, e.what());
    } catch (const std::invalid_argument& e) {
      PyErr_SetString(PyExc_ValueError, in_keyword_words(e.what()).c_str());
    } catch (const std::system_error& e) {
      // OSError(errno, text) is the subclass for the errno: FileNotFoundError,
      // PermissionError, IsADirectoryError, ...
      if (e.code().category() != std::generic_category() && e.code().category() != std::system_category()) throw;
      PyErr_SetObject(PyExc_OSError, py::make_tuple(e.code().value(), e.what()).ptr());
    }
  });

  m.def("read_image", [](const std::string& path) { return python::image_to_numpy(api::read_image(path)); },
        py::arg("path"), "PNG, EXR, JPEG, ... as float32 (H, W, C): values as stored (8-bit codes / 255).");
  m.def("write_image",
        [](const std::string& path, const py::handle& array, const std::string& encoding) {
          if (encoding != "linear" && encoding != "srgb")
            throw py::value_error("encoding: expected 'linear' or 'srgb', got '" + encoding + "'");
          const api::Image img = python::numpy_to_image(array, "array");
          py::gil_scoped_release nogil;
          api::write_image(path, img, encoding == "srgb" ? api::Encoding::srgb : api::Encoding::linear);
        },
        py::arg("path"), py::arg("array"), py::arg("encoding") = "linear",
        ".png (8-bit, encoding 'linear' or 'srgb') or .exr (float32), written to a temporary name and renamed.");
  m.def("psnr",
        [](const py::handle& a, const py::handle& b) {
          return api::psnr(python::numpy_to_image(a, "a"), python::numpy_to_image(b, "b"));
        },
        py::arg("a"), py::arg("b"), "PSNR in dB on the 8-bit scale of two images of values in 0..1; inf when equal.");

  python::bind_scene(m);
  python::bind_cameras(m);
  python::bind_render(m);
  python::bind_animate(m);
  python::bind_preview(m);
  python::bind_web(m);
}
