#include <pybind11/stl.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <string>

#include "holoray/pick.hpp"
#include "arrays.hpp"
#include "bindings.hpp"
#include "result.hpp"
#include "holoray/render.hpp"
#include "holoray/world.hpp"
#include "worker.hpp"

namespace holoray::python {

namespace {

std::array<int, 2> pair_of(const py::handle& h, const char* name) {
  if (py::isinstance<py::int_>(h)) {
    const int n = h.cast<int>();
    return {n, n};
  }
  try {
    const auto t = h.cast<std::array<int, 2>>();
    return t;
  } catch (const py::cast_error&) {
    throw py::type_error(std::string(name) + ": expected two integers (x, y)");
  }
}

// A path (str or os.PathLike) to a file that exists; FileNotFoundError otherwise.
std::string existing_file(const py::object& path, const char* name) {
  const std::string p = py::str(py::module_::import("os").attr("fspath")(path));
  if (!py::module_::import("os.path").attr("isfile")(p).cast<bool>()) {
    PyErr_SetObject(PyExc_FileNotFoundError, py::make_tuple(2, std::string(name) + ": no such file", p).ptr());
    throw py::error_already_set();
  }
  return p;
}

// The cameras' focus_distance= (a focal plane's distance from the eye, > 0).
std::optional<double> checked_focus(std::optional<double> d) {
  if (d && !(*d > 0 && std::isfinite(*d))) throw py::value_error("focus_distance: expected a positive distance");
  return d;
}

std::optional<api::Placement> placement_of(const py::handle& origin, const py::handle& normal, const py::handle& up) {
  if (origin.is_none() && normal.is_none() && up.is_none()) return std::nullopt;
  if (origin.is_none() || normal.is_none() || up.is_none())
    throw py::value_error("origin, normal, up: give all three (an explicit placement), or none");
  return api::Placement{vec3_of(origin, "origin"), vec3_of(normal, "normal"), vec3_of(up, "up")};
}


py::dict stats_dict(const api::RenderStats& s) {
  py::dict rays, seconds, out;
  rays["eye"] = s.rays.eye;
  rays["shadow"] = s.rays.shadow;
  rays["reflected"] = s.rays.reflected;
  rays["refracted"] = s.rays.refracted;
  rays["shadow_cached"] = s.rays.shadow_cached;
  rays["cache_samples"] = s.rays.cache_samples;
  rays["total"] = s.rays.total();
  seconds["build"] = s.build_seconds;
  seconds["gpu_setup"] = s.gpu_setup_seconds;
  seconds["trace"] = s.trace_seconds;
  out["rays"] = rays;
  out["seconds"] = seconds;
  return out;
}

// The id AOV as int32 (it is held as float: exact up to 2^24 objects).
py::array id_array(const api::Image& id) {
  py::array_t<int32_t> out({static_cast<py::ssize_t>(id.height()), static_cast<py::ssize_t>(id.width())});
  int32_t* dst = out.mutable_data();
  for (size_t k = 0; k < id.size(); ++k) dst[k] = static_cast<int32_t>(id.data()[k]);
  return out;
}

struct Rendered {
  api::Result result;
  std::string description;
  std::string device;  // the GPU's name; "cpu"
};

}  // namespace

api::Camera camera_of(const py::handle& c, const char* name) {
  if (py::isinstance<api::LensArray>(c)) return c.cast<api::LensArray>();
  if (py::isinstance<api::Pinhole>(c)) return c.cast<api::Pinhole>();
  if (py::isinstance<api::Quilt>(c)) return c.cast<api::Quilt>();
  if (py::isinstance<api::Display>(c)) return c.cast<api::Display>();
  if (py::isinstance<api::LookingGlass>(c)) return c.cast<api::LookingGlass>();
  throw py::type_error(std::string(name) + ": expected holoray.LensArray, Pinhole, Quilt, Display or LookingGlass, got " +
                       std::string(py::str(py::type::of(c))));
}

void bind_cameras(py::module_& m) {
  py::class_<api::LensArray>(m, "LensArray",
                             "The integral camera, placed by the scene's viewpoint as `holoray render` places it. "
                             "EIA size: lenses x pixels_per_lens (square grid).")
      .def(py::init([](const py::handle& lenses, int pixels_per_lens, const std::string& grid, std::optional<double> fov_lens,
                       const std::string& mode, std::optional<double> pitch, std::optional<double> gap, std::optional<int> rows,
                       std::optional<double> view_distance, const py::handle& origin, const py::handle& normal,
                       const py::handle& up, std::optional<double> focus_distance) {
             api::LensArray a;
             const auto [nx, ny] = pair_of(lenses, "lenses");
             if (nx < 1 || ny < 1)
               throw py::value_error("lenses: expected at least 1x1, got " + std::to_string(nx) + "x" + std::to_string(ny));
             if (pixels_per_lens < 1) throw py::value_error("pixels_per_lens: expected at least 1, got " + std::to_string(pixels_per_lens));
             a.lenses_x = nx, a.lenses_y = ny;
             a.pixels_per_lens = pixels_per_lens;
             a.grid = pick<api::Grid>("grid", grid, {{"square", api::Grid::square}, {"hex", api::Grid::hex}, {"lenticular", api::Grid::lenticular}});
             a.mode = pick<api::Mode>("mode", mode, {{"orthoscopic", api::Mode::orthoscopic}, {"pseudoscopic", api::Mode::pseudoscopic}});
             if (fov_lens && gap) throw py::value_error("fov_lens: goes without gap (each sets the other)");
             if (fov_lens && !(*fov_lens > 0 && *fov_lens < 180))
               throw py::value_error("fov_lens: expected degrees in (0, 180), got " + std::to_string(*fov_lens));
             if (pitch && !(*pitch > 0 && std::isfinite(*pitch))) throw py::value_error("pitch: expected a finite number > 0");
             if (gap && !(*gap > 0 && std::isfinite(*gap))) throw py::value_error("gap: expected a finite number > 0");
             if (rows && *rows < 1) throw py::value_error("rows: expected at least 1");
             a.fov_lens_deg = fov_lens;
             a.pitch = pitch;
             a.gap = gap;
             a.rows = rows.value_or(0);
             if (view_distance && !(*view_distance > 0)) throw py::value_error("view_distance: expected a number > 0");
             a.view_distance = view_distance.value_or(INFINITY);
             a.placement = placement_of(origin, normal, up);
             if (a.placement && !pitch) throw py::value_error("pitch: an explicit placement (origin, normal, up) needs the lens pitch");
             a.focus_distance = checked_focus(focus_distance);
             if (focus_distance && a.placement) throw py::value_error("focus_distance: goes without origin, normal and up");
             return a;
           }),
           py::arg("lenses") = py::make_tuple(64, 64), py::arg("pixels_per_lens") = 8, py::arg("grid") = "square",
           py::arg("fov_lens") = py::none(), py::arg("mode") = "orthoscopic", py::kw_only(), py::arg("pitch") = py::none(),
           py::arg("gap") = py::none(), py::arg("rows") = py::none(), py::arg("view_distance") = py::none(),
           py::arg("origin") = py::none(), py::arg("normal") = py::none(), py::arg("up") = py::none(),
           py::arg("focus_distance") = py::none())
      .def_property_readonly("lenses", [](const api::LensArray& a) { return py::make_tuple(a.lenses_x, a.lenses_y); })
      .def_readonly("pixels_per_lens", &api::LensArray::pixels_per_lens)
      .def("__repr__", [](const api::LensArray& a) {
        return "holoray.LensArray(lenses=(" + std::to_string(a.lenses_x) + ", " + std::to_string(a.lenses_y) +
               "), pixels_per_lens=" + std::to_string(a.pixels_per_lens) + ")";
      });
  py::class_<api::Pinhole>(m, "Pinhole", "The viewpoint's perspective view; resolution None: the scene's, else 512x512.")
      .def(py::init([](const py::handle& resolution, const std::array<double, 2>& shift) {
             api::Pinhole p;
             if (!resolution.is_none()) {
               const auto [w, h] = pair_of(resolution, "resolution");
               if (w < 1 || h < 1 || w > 65536 || h > 65536) throw py::value_error("resolution: expected 1 to 65536 pixels each way");
               p.width = w, p.height = h;
             }
             if (!std::isfinite(shift[0]) || !std::isfinite(shift[1])) throw py::value_error("shift: expected two finite numbers");
             p.shift_x = shift[0], p.shift_y = shift[1];
             return p;
           }),
           py::arg("resolution") = py::none(), py::kw_only(), py::arg("shift") = std::array<double, 2>{0, 0});
  py::class_<api::Quilt>(m, "Quilt", "A Looking Glass quilt of columns x rows sheared views (view 0 bottom left).")
      .def(py::init([](int columns, int rows, const py::handle& view_resolution, double view_cone,
                       std::optional<double> focus_distance) {
             api::Quilt q;
             if (columns < 1 || rows < 1 || int64_t{columns} * rows > 4096)
               throw py::value_error("columns, rows: expected 1 to 4096 views in all");
             const auto [w, h] = pair_of(view_resolution, "view_resolution");
             if (w < 1 || h < 1 || w > 65536 || h > 65536) throw py::value_error("view_resolution: expected 1 to 65536 pixels each way");
             if (!(view_cone >= 0 && view_cone <= 180)) throw py::value_error("view_cone: expected degrees in [0, 180]");
             q.columns = columns, q.rows = rows, q.view_width = w, q.view_height = h, q.view_cone_deg = view_cone;
             q.focus_distance = checked_focus(focus_distance);
             return q;
           }),
           py::arg("columns"), py::arg("rows"), py::arg("view_resolution") = py::make_tuple(420, 560), py::arg("view_cone") = 40.0,
           py::kw_only(), py::arg("focus_distance") = py::none());
  py::class_<api::Display>(m, "Display", "A physical panel and its lens sheet, from a display file (TOML).")
      .def(py::init([](const py::object& path, std::optional<double> focus_distance) {
             return api::Display{existing_file(path, "path"), std::nullopt, checked_focus(focus_distance)};
           }),
           py::arg("path"), py::kw_only(), py::arg("focus_distance") = py::none());
  py::class_<api::LookingGlass>(m, "LookingGlass", "A Looking Glass's native panel image, from its calibration (visual.json).")
      .def(py::init([](const py::object& path, int views, std::optional<double> focus_distance) {
             if (views < 1 || views > 4096) throw py::value_error("views: expected 1 to 4096");
             return api::LookingGlass{existing_file(path, "path"), views, checked_focus(focus_distance)};
           }),
           py::arg("path"), py::arg("views") = 48, py::kw_only(), py::arg("focus_distance") = py::none());
}

uint32_t checked_seed(int64_t seed) {
  if (seed < 0 || seed > 4294967295LL) throw py::value_error("seed: expected 0 to 4294967295, got " + std::to_string(seed));
  return static_cast<uint32_t>(seed);
}

api::RenderOptions light_options(const std::string& integrator, const py::object& environment, double environment_strength,
                                 double environment_rotation, bool blender_principled, std::optional<int> max_depth) {
  api::RenderOptions o;
  if (integrator == "path") o.integrator = api::Integrator::path;
  else if (integrator != "whitted") throw py::value_error("integrator: expected 'whitted' or 'path', got '" + integrator + "'");
  // A file name, or a colour (r, g, b).
  if (py::isinstance<py::str>(environment)) {
    o.environment.file = environment.cast<std::string>();
  } else if (!environment.is_none()) {
    const auto c = environment.cast<std::vector<double>>();
    if (c.size() != 3) throw py::value_error("environment: expected a file name or a colour (r, g, b)");
    o.environment.colour = std::array<double, 3>{c[0], c[1], c[2]};
  }
  o.environment.strength = environment_strength;
  o.environment.rotation_deg = environment_rotation;
  o.blender_principled = blender_principled;
  if (max_depth && *max_depth < 1) throw py::value_error("max_depth: expected at least 1");
  o.max_depth = max_depth.value_or(0);
  return o;
}

void bind_render(py::module_& m) {
  py::class_<api::World>(m, "World",
                         "A scene built once for many cameras and either device (OSPRay's World): render(world, camera) "
                         "takes it in place of a scene. Its light options are fixed here; render()'s, left at their "
                         "defaults, take them.")
      .def(py::init([](const api::Scene& scene, std::optional<int> max_depth, const std::string& integrator,
                       const py::object& environment, double environment_strength, double environment_rotation,
                       bool blender_principled) {
             const api::RenderOptions o = light_options(integrator, environment, environment_strength, environment_rotation,
                                                        blender_principled, max_depth);
             const api::Scene snapshot = scene;
             py::gil_scoped_release nogil;
             return api::World(snapshot, o);
           }),
           py::arg("scene"), py::kw_only(), py::arg("max_depth") = py::none(), py::arg("integrator") = "whitted",
           py::arg("environment") = py::none(), py::arg("environment_strength") = 1.0, py::arg("environment_rotation") = 0.0,
           py::arg("blender_principled") = false)
      .def_property_readonly("build_seconds", &api::World::build_seconds)
      .def_property_readonly("skipped_polygons", &api::World::skipped_polygons);
  py::class_<PyResult>(m, "Result", "One rendered image: colour, AOVs, statistics.")
      .def_readonly("colour", &PyResult::colour, "float32 (H, W, 3), linear RGB")
      .def_readonly("aovs", &PyResult::aovs, "'albedo' (H, W, 3), 'depth' (H, W), 'normal' (H, W, 3), 'id' int32 (H, W)")
      .def_readonly("stats", &PyResult::stats, "{'rays': {...}, 'seconds': {'build', 'trace'}}")
      .def_readonly("description", &PyResult::description, "what was rendered, as `holoray render` prints it")
      .def_readonly("camera", &PyResult::camera, "the camera it was rendered through")
      .def("__repr__", [](const PyResult& r) {
        return "<holoray.Result " + std::string(py::str(r.colour.attr("shape"))) + ": " + r.description.substr(0, r.description.find('\n')) + ">";
      });
  m.def(
      "render",
      [](const py::object& scene_or_world, const py::handle& camera, std::optional<int> threads, int spp,
         std::optional<int> max_depth, const std::vector<std::string>& aovs, const py::object& progress,
         const std::string& device, const std::string& integrator, const py::object& environment,
         double environment_strength, double environment_rotation, bool blender_principled, int share_views,
         int64_t seed) {
        api::RenderOptions o =
            light_options(integrator, environment, environment_strength, environment_rotation, blender_principled, max_depth);
        o.device = device;
        o.share_views = share_views;
        o.seed = checked_seed(seed);
        const api::Camera cam = camera_of(camera, "camera");
        if (threads && *threads < 1) throw py::value_error("threads: expected at least 1 (None: all cores)");
        if (spp < 1) throw py::value_error("spp: expected at least 1 sample per pixel");
        o.threads = threads.value_or(0);
        o.spp = spp;
        // A World, or a Scene built for this render alone.
        std::optional<api::World> world;
        std::optional<api::Scene> scene;
        if (py::isinstance<api::World>(scene_or_world)) world = scene_or_world.cast<api::World>();
        else if (py::isinstance<api::Scene>(scene_or_world)) scene = scene_or_world.cast<api::Scene>();
        else throw py::type_error("scene: expected a holoray.Scene or a holoray.World");
        for (const std::string& a : aovs) {
          if (a == "albedo") o.aovs.albedo = true;
          else if (a == "depth") o.aovs.depth = true;
          else if (a == "normal") o.aovs.normal = true;
          else if (a == "id") o.aovs.id = true;
          else throw py::value_error("aovs: expected albedo, depth, normal or id, got '" + a + "'");
        }
        if (!progress.is_none() && !PyCallable_Check(progress.ptr())) throw py::type_error("progress: expected a callable");
        // Progress crosses from the workers as a number: the callback runs
        // on this thread, at the waits' slices.
        Waker waker;
        std::atomic<double> fraction{0};
        if (!progress.is_none())
          o.progress = [&](double f) {
            double seen = fraction.load();
            while (f > seen && !fraction.compare_exchange_weak(seen, f)) {
            }
            waker.wake();
          };
        // Its own handle on the scene (the cast above copied it): another
        // Python thread changing it meanwhile changes the original.
        double shown = 0;
        auto tick = [&] {
          const double f = fraction.load();
          if (f > shown) progress(shown = f);
        };
        Rendered out = run_off_interpreter<Rendered>(
            [&](std::stop_token stop) {
              api::RenderOptions ro = o;
              ro.stop = stop;
              const api::Renderer r = world ? api::Renderer(*world, cam, ro) : api::Renderer(*scene, cam, ro);
              const std::string name = r.device_name();
              return Rendered{r.render(), r.describe(), name.empty() ? "cpu" : name};
            },
            waker, progress.is_none() ? std::function<void()>{} : std::function<void()>(tick));
        PyResult res;
        const api::Result& rr = out.result;
        res.colour = image_to_numpy(rr.colour);
        if (!rr.albedo.empty()) res.aovs["albedo"] = image_to_numpy(rr.albedo);
        if (!rr.depth.empty()) res.aovs["depth"] = image_to_numpy(rr.depth, true);
        if (!rr.normal.empty()) res.aovs["normal"] = image_to_numpy(rr.normal);
        if (!rr.id.empty()) res.aovs["id"] = id_array(rr.id);
        res.stats = stats_dict(rr.stats);
        res.stats["device"] = out.device;
        res.description = out.description;
        res.camera = py::reinterpret_borrow<py::object>(camera);
        res.encoding = api::default_encoding(scene ? scene->source() : world->source());
        return res;
      },
      py::arg("scene"), py::arg("camera"), py::kw_only(), py::arg("threads") = py::none(), py::arg("spp") = 1,
      py::arg("max_depth") = py::none(), py::arg("aovs") = std::vector<std::string>{}, py::arg("progress") = py::none(),
      py::arg("device") = "cpu", py::arg("integrator") = "whitted", py::arg("environment") = py::none(),
      py::arg("environment_strength") = 1.0, py::arg("environment_rotation") = 0.0, py::arg("blender_principled") = false,
      py::arg("share_views") = 0, py::arg("seed") = 0,
      "Renders scene (a Scene, or a World built once for many renders) through camera: Result. With a World, the light "
      "options left at their defaults take the world's. Releases the GIL; Ctrl-C raises KeyboardInterrupt within half a second; "
      "progress(fraction) is called on the calling thread. device: 'cpu', 'gpu' (the first Vulkan GPU, else lavapipe) "
      "or 'gpu:N'; stats['device'] names it. integrator: 'whitted' or 'path' (docs/lights.md); with 'path', "
      "environment: an equirectangular .hdr/.exr file or a colour (r, g, b), times environment_strength, turned by "
      "environment_rotation degrees about the up axis; blender_principled: glTF materials as Blender's Principled BSDF; "
      "share_views: a Quilt's views, path traced on the CPU, each take the samples of this many views on each side "
      "(docs/guide/light.md); seed: the path integrator's, renders with different seeds having independent noise.");
  m.def(
      "gpu_devices",
      [] {
        py::gil_scoped_release nogil;
        return api::gpu_devices();
      },
      "The machine's Vulkan devices ('0: llvmpipe (...), CPU, Vulkan 1.3, 2.0 GiB'), in the order 'gpu:N' counts them. "
      "RuntimeError saying what to install when there is no loader or device.");
  m.def(
      "release_gpu_devices",
      [] {
        py::gil_scoped_release nogil;
        return api::release_gpu_devices();
      },
      "Frees the GPU devices this process keeps idle between renders (and their compiled kernels), handing their "
      "memory back to the driver; the next GPU render makes its own again. Returns how many were freed.");
}

}  // namespace holoray::python
