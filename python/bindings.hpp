// holoray/python: the module's parts, one file each.
#pragma once

#include <pybind11/pybind11.h>

#include <optional>
#include <string>

#include "holoray/camera.hpp"
#include "holoray/render.hpp"

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

/// render()'s, World()'s and animate()'s light keywords as a RenderOptions
/// with them set: integrator 'whitted' or 'path', environment a file name,
/// a colour (r, g, b) or None. ValueError naming the keyword otherwise.
api::RenderOptions light_options(const std::string& integrator, const py::object& environment, double environment_strength,
                                 double environment_rotation, bool blender_principled, std::optional<int> max_depth);

/// The path integrator's seed (api::RenderOptions::seed); ValueError outside 0 to 2^32 - 1.
uint32_t checked_seed(int64_t seed);

}  // namespace holoray::python
