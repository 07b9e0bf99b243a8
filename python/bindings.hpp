// holoray/python: the module's parts, one file each.
#pragma once

#include <pybind11/pybind11.h>

#include "holoray/camera.hpp"

namespace holoray::python {

namespace py = pybind11;

void bind_scene(py::module_& m);    ///< Scene, load_scene (scene_bindings.cpp)
void bind_cameras(py::module_& m);  ///< LensArray, Pinhole, Quilt, Display, LookingGlass (render_bindings.cpp)
void bind_render(py::module_& m);   ///< Result, render (render_bindings.cpp)
void bind_animate(py::module_& m);  ///< the animation iterator (animate_bindings.cpp)
void bind_preview(py::module_& m);  ///< subaperture_view, simulate_view, interlace_quilt (preview_bindings.cpp)
void bind_web(py::module_& m);      ///< write_web (web_bindings.cpp)

/// A camera object of this module as the API's camera; TypeError otherwise.
api::Camera camera_of(const py::handle& camera, const char* name);

}  // namespace holoray::python
