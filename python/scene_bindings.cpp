#include <pybind11/stl.h>

#include "arrays.hpp"
#include "bindings.hpp"
#include "holoray/scene.hpp"

namespace holoray::python {

void bind_scene(py::module_& m) {
  py::class_<api::Scene>(m, "Scene", "A scene: loaded from a file (load_scene) or built in code. World units and frame.")
      .def(py::init<>())
      .def(
          "add_mesh",
          [](api::Scene& s, const py::handle& vertices, const py::handle& faces, const py::handle& normals,
             const py::handle& uv, const py::handle& colour, const py::handle& texture) {
            api::Mesh mesh;
            mesh.vertices = rows_of<3>(vertices, "vertices");
            mesh.faces = faces_of(faces, "faces");
            if (!normals.is_none()) mesh.normals = rows_of<3>(normals, "normals");
            if (!uv.is_none()) mesh.uv = rows_of<2>(uv, "uv");
            mesh.colour = vec3_of(colour, "colour");
            if (!texture.is_none()) mesh.texture = texture_of(texture, "texture");
            return s.add_mesh(mesh);
          },
          py::arg("vertices"), py::arg("faces"), py::kw_only(), py::arg("normals") = py::none(), py::arg("uv") = py::none(),
          py::arg("colour") = py::make_tuple(0.8, 0.8, 0.8), py::arg("texture") = py::none(),
          "Adds a triangle mesh; returns its object id. vertices (N, 3) float, world units; faces (M, 3) integer, "
          "counter-clockwise seen from the front; normals (N, 3); uv (N, 2), v up; colour linear RGB; texture "
          "(H, W, 3|4) float (linear) or uint8 (sRGB codes).")
      .def(
          "add_sphere",
          [](api::Scene& s, const py::handle& centre, double radius, const py::handle& colour) {
            return s.add_sphere(vec3_of(centre, "centre"), radius, vec3_of(colour, "colour"));
          },
          py::arg("centre"), py::arg("radius"), py::kw_only(), py::arg("colour") = py::make_tuple(0.8, 0.8, 0.8),
          "Adds an exact sphere (world units); returns its object id.")
      .def(
          "add_light",
          [](api::Scene& s, const py::handle& position, const py::handle& colour) {
            s.add_light(vec3_of(position, "position"), vec3_of(colour, "colour"));
          },
          py::arg("position"), py::arg("colour") = py::make_tuple(1.0, 1.0, 1.0),
          "Adds a point light without falloff; colour is its radiance on a white surface facing it.")
      .def("add_lights", &api::Scene::add_lights, py::arg("path"),
           "Adds the lights of a lights file (docs/lights.md): point, spot, sun and area lights in Blender's units.")
      .def(
          "set_viewpoint",
          [](api::Scene& s, const py::handle& eye, const py::handle& at, const py::handle& up, double fov_deg) {
            s.set_viewpoint(vec3_of(eye, "eye"), vec3_of(at, "at"), vec3_of(up, "up"), fov_deg);
          },
          py::arg("eye"), py::arg("at"), py::arg("up"), py::arg("fov_deg"),
          "The viewpoint that places every camera (NFF's 'v'); fov_deg vertical, in (0, 180).")
      .def_property_readonly("object_count", &api::Scene::object_count)
      .def_property_readonly("light_count", &api::Scene::light_count)
      .def_property_readonly("warnings", &api::Scene::warnings)
      .def("__repr__", [](const api::Scene& s) {
        return "<holoray.Scene " + (s.source().empty() ? std::string("built in code") : "'" + s.source() + "'") + ": " +
               std::to_string(s.object_count()) + " objects, " + std::to_string(s.light_count()) + " lights>";
      });
  m.def(
      "load_scene",
      [](const std::string& path, const std::string& camera_name, const std::vector<std::string>& texture_path) {
        py::gil_scoped_release nogil;
        return api::Scene::load(path, {camera_name, texture_path});
      },
      py::arg("path"), py::kw_only(), py::arg("camera_name") = "", py::arg("texture_path") = std::vector<std::string>{},
      "NFF, Tachyon (.dat) or a mesh file through assimp. Raises SceneError (file:line:col).");
}

}  // namespace holoray::python
