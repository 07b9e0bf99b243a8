// holoray/python: the Result a render returns (render_bindings.cpp), and
// what the functions that take one read of it (web_bindings.cpp).
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <string>

#include "holoray/image.hpp"

namespace holoray::python {

namespace py = pybind11;

struct PyResult {
  py::array colour;
  py::dict aovs, stats;
  std::string description;
  py::object camera;  ///< the camera object it was rendered through
  /// How `holoray render` would write its 8-bit image unless told: the
  /// scene's default (api::default_encoding).
  api::Encoding encoding = api::Encoding::linear;
};

}  // namespace holoray::python
