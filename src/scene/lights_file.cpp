#include "scene/lights_file.hpp"

#include <fmt/format.h>

#include <cmath>

#include "scene/file_text.hpp"
#include "scene/toml_fields.hpp"

namespace holoray {

namespace {

constexpr double kBig = 1e30;  // finite, and far past any scene's

class LightsParser : TomlFields {
 public:
  LightsParser(std::string_view text, std::string source) : TomlFields(text, std::move(source)) {}

  LightsFile run() {
    const toml::table root = parse();
    check_keys(root, "the lights file", {"light"});
    LightsFile out;
    const toml::node* lights = root.get("light");
    if (!lights) return out;
    const toml::array* list = lights->as_array();
    if (!list || !list->is_array_of_tables()) fail(lights->source(), "expected [[light]] tables");
    for (const toml::node& n : *list) read_light(*n.as_table(), out);
    return out;
  }

 private:
  SourceLoc loc_of(const toml::table& t) const {
    return SourceLoc{static_cast<int>(t.source().begin.line), static_cast<int>(t.source().begin.column)};
  }

  Vec3 required_vec3(const toml::table& t, std::string_view key, std::string_view type) const {
    const std::optional<Vec3> v = vec3(t, key);
    if (!v) fail(t.source(), fmt::format("{} {} light needs `{}` = [x, y, z]", type == "area" ? "an" : "a", type, key));
    return *v;
  }

  Vec3 unit(const toml::table& t, std::string_view key, std::string_view type) const {
    const Vec3 v = required_vec3(t, key, type);
    const double len = length(v);
    if (!(len > 0)) fail(t.get(key)->source(), fmt::format("{}: expected a non-zero direction", key));
    return v / len;
  }

  void read_light(const toml::table& t, LightsFile& out) const {
    const std::string type = choice(t, "type", {"point", "spot", "sun", "area"}, "");
    if (type.empty()) fail(t.source(), "a [[light]] needs `type` = \"point\", \"spot\", \"sun\" or \"area\"");
    if (type == "point") check_keys(t, "a point light", {"type", "position", "colour", "power", "radius"});
    if (type == "spot")
      check_keys(t, "a spot light", {"type", "position", "colour", "power", "radius", "direction", "spot_size", "spot_blend"});
    if (type == "sun") check_keys(t, "a sun light", {"type", "colour", "strength", "direction", "angle"});
    if (type == "area")
      check_keys(t, "an area light", {"type", "position", "colour", "power", "direction", "right", "shape", "size"});
    const Vec3 colour = vec3(t, "colour").value_or(Vec3{1, 1, 1});
    if (!(colour.x >= 0 && colour.y >= 0 && colour.z >= 0)) fail(t.get("colour")->source(), "colour: expected values >= 0");

    if (type == "area") {
      AreaLightDesc a;
      a.loc = loc_of(t);
      a.centre = required_vec3(t, "position", type);
      a.normal = unit(t, "direction", type);
      // Blender's local x, made perpendicular to the normal; y completes the
      // frame as Blender's does (x, y, z right-handed, z = -normal).
      Vec3 right = unit(t, "right", type);
      right = right - a.normal * dot(right, a.normal);
      if (!(length(right) > 1e-9)) fail(t.get("right")->source(), "right: expected a direction across `direction`, not along it");
      right = normalize(right);
      const Vec3 up = cross(-a.normal, right);
      const std::string shape = choice(t, "shape", {"square", "rectangle", "disk", "ellipse"}, "square");
      a.ellipse = shape == "disk" || shape == "ellipse";
      double sx = 1, sy = 1;
      if (const toml::node* n = t.get("size")) {
        if (const toml::array* arr = n->as_array(); arr && arr->size() == 2 && (shape == "rectangle" || shape == "ellipse")) {
          sx = as_number(*arr->get(0), "size"), sy = as_number(*arr->get(1), "size");
        } else if (n->is_number() && (shape == "square" || shape == "disk")) {
          sx = sy = as_number(*n, "size");
        } else {
          fail(n->source(), shape == "rectangle" || shape == "ellipse" ? "size: expected [x, y] for a " + shape
                                                                       : "size: expected one number for a " + shape);
        }
        if (!(sx > 0 && sy > 0 && sx < kBig && sy < kBig)) fail(n->source(), "size: expected sizes > 0");
      }
      a.axis_u = right * (sx / 2);
      a.axis_v = up * (sy / 2);
      const double area = a.ellipse ? M_PI * sx * sy / 4 : sx * sy;
      const double power = number(t, "power", 0, kBig).value_or(10);
      // A Lambertian emitter of radiance L over area A emits pi A L: Cycles
      // since 4.0 (a21af93, "Fix wrong conversion from power to radiance of
      // area lights"). Cycles 3.x took P / (4 A); the add-on writes a
      // Blender 3 area light's power as 4.0 would need it for the same light.
      a.radiance = colour * (power / (M_PI * area));
      out.area_lights.push_back(a);
      return;
    }
    Light l;
    l.loc = loc_of(t);
    l.photometric = true;  // already in holoray's unit: no NFF scaling
    if (type == "sun") {
      l.kind = LightKind::directional;
      l.direction = unit(t, "direction", type);
      // Irradiance S facing it: a white Lambertian surface shows S / pi.
      l.colour = colour * (number(t, "strength", 0, kBig).value_or(1) / M_PI);
      l.angle = number(t, "angle", 0, 180).value_or(0) * M_PI / 180;
      out.lights.push_back(l);
      return;
    }
    l.kind = type == "spot" ? LightKind::spot : LightKind::point;
    l.position = required_vec3(t, "position", type);
    // Intensity P / (4 pi) W/sr: irradiance P / (4 pi d^2) facing it, which a
    // white Lambertian surface shows divided by pi.
    l.colour = colour * (number(t, "power", 0, kBig).value_or(10) / (4 * M_PI * M_PI));
    l.kc = 0, l.kl = 0, l.kq = 1;
    l.radius = number(t, "radius", 0, kBig).value_or(0);
    if (type == "spot") {
      l.direction = unit(t, "direction", type);
      // Blender's cone as its glTF exporter writes it (outer half angle,
      // inner = outer (1 - blend)), with KHR_lights_punctual's smooth falloff.
      l.fall_end = number(t, "spot_size", 0, 180).value_or(45) * M_PI / 360;
      l.fall_start = l.fall_end * (1 - number(t, "spot_blend", 0, 1).value_or(0.15));
      l.smooth_cone = true;
    }
    out.lights.push_back(l);
  }
};

}  // namespace

LightsFile parse_lights_file(std::string_view text, const std::string& source) { return LightsParser(text, source).run(); }

LightsFile read_lights_file(const std::string& path) {
  const std::string text = read_text_file(path);
  return parse_lights_file(text, path);
}

}  // namespace holoray
