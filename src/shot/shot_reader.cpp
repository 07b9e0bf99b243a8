#include "shot/shot_reader.hpp"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <cmath>
#include <filesystem>
#include <initializer_list>
#include <set>

#include "scene/file_text.hpp"
#include "scene/parse_error.hpp"
#include "scene/toml_fields.hpp"

namespace holoray {

namespace {

constexpr int64_t kMaxFrames = 1'000'000;
constexpr int64_t kMaxLensCount = 1 << 20;
constexpr int64_t kMaxPixelsPerLens = 4096;

class ShotParser : TomlFields {
 public:
  ShotParser(std::string_view text, std::string source) : TomlFields(text, std::move(source)) {}

  Shot run() {
    const toml::table root = parse();
    Shot shot;
    shot.source = source();
    check_keys(root, "the shot",
               {"frames", "fps", "spp", "background", "array", "camera", "object", "camera_name", "texture_path"});
    shot.read.camera_name = string(root, "camera_name").value_or("");
    if (const toml::node* n = root.get("texture_path")) {
      if (const auto* one = n->as_string()) {
        shot.read.texture_paths.push_back(resolve(one->get()));
      } else if (const toml::array* list = n->as_array(); list && list->is_homogeneous(toml::node_type::string)) {
        for (const toml::node& dir : *list) shot.read.texture_paths.push_back(resolve(dir.as_string()->get()));
      } else {
        fail(n->source(), "texture_path: expected a folder or an array of folders (strings)");
      }
    }
    shot.frames = static_cast<int>(integer(root, "frames", 1, kMaxFrames, true).value_or(1));
    shot.fps = number(root, "fps", 1e-6, 1e6).value_or(24);
    shot.spp = static_cast<int>(integer(root, "spp", 1, 65536).value_or(1));
    shot.background = vec3(root, "background");
    if (const toml::table* a = table(root, "array")) read_array(*a, shot.array);
    if (const toml::table* c = table(root, "camera")) read_camera(*c, shot);
    const toml::node* objects = root.get("object");
    if (!objects) fail(root.source(), "expected at least one [[object]] with a scene file, found none");
    const toml::array* list = objects->as_array();
    if (!list || list->empty() || !list->is_array_of_tables())
      fail(objects->source(), "expected [[object]] tables (one per scene file)");
    for (const toml::node& n : *list) shot.objects.push_back(read_object(*n.as_table()));
    return shot;
  }

 private:
  Interpolation interpolation(const toml::table& t) const {
    return choice(t, "interpolation", {"linear", "smooth"}, "linear") == "smooth" ? Interpolation::smooth
                                                                                 : Interpolation::linear;
  }

  std::string resolve(const std::string& name) const {
    const std::filesystem::path p(name);
    if (p.is_absolute()) return name;
    return (std::filesystem::path(source()).parent_path() / p).lexically_normal().string();
  }

  void read_array(const toml::table& a, ArraySettings& s) const {
    check_keys(a, "[array]", {"grid", "mode", "lenses", "pixels_per_lens", "rows", "pitch", "gap", "fov_lens",
                              "view_distance"});
    const std::string grid = choice(a, "grid", {"square", "hex", "lenticular"}, "square");
    s.grid = grid == "hex" ? Grid::hex : grid == "lenticular" ? Grid::lenticular : Grid::square;
    s.mode = choice(a, "mode", {"orthoscopic", "pseudoscopic"}, "orthoscopic") == "pseudoscopic"
                 ? RecordingMode::pseudoscopic
                 : RecordingMode::orthoscopic;
    if (const toml::node* n = a.get("lenses")) {
      if (n->is_integer()) {
        s.lenses_x = s.lenses_y = static_cast<int>(*integer(a, "lenses", 1, kMaxLensCount));
      } else {
        const toml::array* l = n->as_array();
        if (!l || l->size() != 2 || !(*l)[0].is_integer() || !(*l)[1].is_integer())
          fail(n->source(), "expected 'lenses' to be [Nx, Ny] or one integer");
        for (int k = 0; k < 2; ++k) {
          const int64_t v = *(*l)[static_cast<size_t>(k)].value_exact<int64_t>();
          if (v < 1 || v > kMaxLensCount)
            fail((*l)[static_cast<size_t>(k)].source(), fmt::format("expected lens counts from 1 to {}, found {}", kMaxLensCount, v));
          (k == 0 ? s.lenses_x : s.lenses_y) = static_cast<int>(v);
        }
      }
    }
    s.pixels_per_lens = static_cast<int>(integer(a, "pixels_per_lens", 1, kMaxPixelsPerLens).value_or(8));
    s.rows = static_cast<int>(integer(a, "rows", 0, kMaxLensCount * kMaxPixelsPerLens).value_or(0));
    s.pitch = number(a, "pitch", 1e-300, 1e300);
    s.gap = number(a, "gap", 1e-300, 1e300);
    s.fov_lens_deg = number(a, "fov_lens", 1e-6, 179.999);
    if (s.gap && s.fov_lens_deg) fail(a.get("fov_lens")->source(), "give either 'gap' or 'fov_lens', not both");
    s.view_distance = number(a, "view_distance", 1e-300, INFINITY).value_or(INFINITY);
  }

  void read_camera(const toml::table& c, Shot& shot) const {
    check_keys(c, "[camera]", {"path", "start", "distance", "angle", "interpolation", "key"});
    ShotCamera& cam = shot.camera;
    cam.interpolation = interpolation(c);
    cam.distance = number(c, "distance", 1e-300, 1e300);
    cam.angle_deg = number(c, "angle", 1e-6, 179.999);
    cam.path_start = static_cast<int>(integer(c, "start", 0, 10'000'000).value_or(0));
    if (const auto path = string(c, "path")) {
      if (c.get("key")) fail(c.get("key")->source(), "give either a camera 'path' or [[camera.key]] tables, not both");
      cam.path_file = resolve(*path);
      cam.path = read_camera_path(cam.path_file);
      if (cam.path.size() < static_cast<size_t>(cam.path_start) + static_cast<size_t>(shot.frames))
        fail(c.get("path")->source(),
             fmt::format("the camera path '{}' has {} frames; the shot needs {} from line {}", cam.path_file,
                         cam.path.size(), shot.frames, cam.path_start + 1));
    } else if (c.get("start")) {
      fail(c.get("start")->source(), "'start' is a line of a camera 'path', and there is no path");
    }
    if (const toml::node* keys = c.get("key")) {
      const toml::array* list = keys->as_array();
      if (!list || list->empty() || !list->is_array_of_tables()) fail(keys->source(), "expected [[camera.key]] tables");
      for (const toml::node& n : *list) {
        const toml::table& k = *n.as_table();
        check_keys(k, "[[camera.key]]", {"frame", "from", "at", "up", "angle"});
        ViewKey key;
        key.frame = static_cast<double>(*integer(k, "frame", 0, kMaxFrames, true));
        if (!cam.keys.empty() && !(key.frame > cam.keys.back().frame))
          fail(k.get("frame")->source(), fmt::format("expected camera keys in increasing frame order, found frame {} after {}",
                                                   key.frame, cam.keys.back().frame));
        const auto need = [&](std::string_view name) {
          const auto v = vec3(k, name);
          if (!v) fail(k.source(), fmt::format("expected '{}' = [x, y, z] in [[camera.key]]", name));
          return *v;
        };
        key.from = need("from");
        key.at = need("at");
        key.up = need("up");
        if (length(key.from - key.at) == 0) fail(k.get("at")->source(), "'from' and 'at' are the same point");
        if (!up_orients(key.at - key.from, key.up))
          fail(k.get("up")->source(), "'up' is zero or parallel to the view direction");
        key.angle_deg = number(k, "angle", 1e-6, 179.999);
        cam.keys.push_back(key);
      }
    }
  }

  ShotObject read_object(const toml::table& o) const {
    check_keys(o, "[[object]]", {"scene", "interpolation", "key"});
    ShotObject obj;
    obj.loc = {static_cast<int>(o.source().begin.line), static_cast<int>(o.source().begin.column)};
    const auto scene = string(o, "scene");
    if (!scene) fail(o.source(), "expected 'scene' (a scene file) in [[object]]");
    obj.scene = resolve(*scene);
    obj.motion.interpolation = interpolation(o);
    if (const toml::node* keys = o.get("key")) {
      const toml::array* list = keys->as_array();
      if (!list || list->empty() || !list->is_array_of_tables()) fail(keys->source(), "expected [[object.key]] tables");
      for (const toml::node& n : *list) {
        const toml::table& k = *n.as_table();
        check_keys(k, "[[object.key]]", {"frame", "translate", "rotate", "scale"});
        TransformKey key;
        key.frame = static_cast<double>(*integer(k, "frame", 0, kMaxFrames, true));
        if (!obj.motion.keys.empty() && !(key.frame > obj.motion.keys.back().frame))
          fail(k.get("frame")->source(), fmt::format("expected object keys in increasing frame order, found frame {} after {}",
                                                   key.frame, obj.motion.keys.back().frame));
        key.translate = vec3(k, "translate").value_or(Vec3{});
        key.rotate_deg = vec3(k, "rotate").value_or(Vec3{});
        key.scale = vec3(k, "scale", true).value_or(Vec3{1, 1, 1});
        if (key.scale.x == 0 || key.scale.y == 0 || key.scale.z == 0)
          fail(k.get("scale")->source(), "a scale of zero flattens the object; expected non-zero factors");
        obj.motion.keys.push_back(key);
      }
    }
    return obj;
  }
};

}  // namespace

Shot parse_shot(std::string_view text, const std::string& source) { return ShotParser(text, source).run(); }

Shot read_shot_file(const std::string& path) { return parse_shot(read_text_file(path), path); }

}  // namespace holoray
