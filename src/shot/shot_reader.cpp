#include "shot/shot_reader.hpp"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <cmath>
#include <filesystem>
#include <initializer_list>
#include <set>

#include "scene/file_text.hpp"
#include "scene/parse_error.hpp"

namespace holoray {

namespace {

constexpr int64_t kMaxFrames = 1'000'000;
constexpr int64_t kMaxLensCount = 1 << 20;
constexpr int64_t kMaxPixelsPerLens = 4096;

class ShotParser {
 public:
  ShotParser(std::string_view text, std::string source) : text_(text), source_(std::move(source)) {}

  Shot run() {
    check_code_points();
    toml::table root;
    try {
      root = toml::parse(text_, source_);
    } catch (const toml::parse_error& e) {
      fail(e.source(), std::string(e.description()));
    }
    Shot shot;
    shot.source = source_;
    check_keys(root, "the shot", {"frames", "fps", "spp", "background", "array", "camera", "object"});
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
  // toml++ 3.3.0 (Debian 12) reaches __builtin_unreachable when it tests
  // U+00A1..U+0499, U+2C5E..U+3057 (but U+3000) or U+FB26..U+FEFE for whitespace, which its
  // scanner does in places that depend on the state it is in (found by
  // fuzz_shot). Those code points are refused anywhere, before it sees them,
  // with a message naming the character. Other non-ASCII text is passed on.
  void check_code_points() const {
    const std::string_view t = text_;
    int line = 1;
    size_t line_start = 0;
    for (size_t i = 0; i < t.size(); ++i) {
      const auto b0 = static_cast<unsigned char>(t[i]);
      if (b0 == '\n') {
        ++line, line_start = i + 1;
        continue;
      }
      // Only two- and three-byte UTF-8 sequences can encode the bad ranges.
      char32_t c = 0;
      if ((b0 & 0xE0) == 0xC0 && i + 1 < t.size() && (t[i + 1] & 0xC0) == 0x80) {
        c = (char32_t(b0 & 0x1F) << 6) | char32_t(t[i + 1] & 0x3F);
      } else if ((b0 & 0xF0) == 0xE0 && i + 2 < t.size() && (t[i + 1] & 0xC0) == 0x80 && (t[i + 2] & 0xC0) == 0x80) {
        c = (char32_t(b0 & 0x0F) << 12) | (char32_t(t[i + 1] & 0x3F) << 6) | char32_t(t[i + 2] & 0x3F);
      }
      const bool bad = (c >= 0xA1 && c <= 0x499) || (c >= 0x2C5E && c <= 0x3057 && c != 0x3000) || (c >= 0xFB26 && c <= 0xFEFE);
      if (bad)
        throw ParseError(source_, SourceLoc{line, static_cast<int>(i - line_start) + 1},
                         fmt::format("found the character U+{:04X}, which shot files cannot hold (a limitation of the "
                                     "TOML library, toml++ 3.3.0); use ASCII names",
                                     static_cast<uint32_t>(c)),
                         line_text(line));
    }
  }

  [[noreturn]] void fail(const toml::source_region& where, const std::string& message) const {
    const int line = static_cast<int>(where.begin.line), col = static_cast<int>(where.begin.column);
    throw ParseError(source_, SourceLoc{line, col}, message, line_text(line));
  }
  std::string line_text(int line) const {
    size_t pos = 0;
    for (int l = 1; l < line && pos != std::string_view::npos; ++l) {
      pos = text_.find('\n', pos);
      if (pos != std::string_view::npos) ++pos;
    }
    if (pos == std::string_view::npos || pos > text_.size()) return {};
    const size_t end = text_.find('\n', pos);
    std::string s(text_.substr(pos, end == std::string_view::npos ? std::string_view::npos : end - pos));
    if (!s.empty() && s.back() == '\r') s.pop_back();
    return s;
  }

  // Typos must not pass silently: every key has to be one we read.
  void check_keys(const toml::table& t, std::string_view where, std::initializer_list<std::string_view> known) const {
    for (auto&& [key, value] : t) {
      bool ok = false;
      for (std::string_view k : known) ok = ok || key.str() == k;
      if (!ok) {
        std::string list;
        for (std::string_view k : known) list += fmt::format("{}{}", list.empty() ? "" : ", ", k);
        fail(key.source(), fmt::format("unknown key '{}' in {} (expected one of: {})", key.str(), where, list));
      }
    }
  }

  const toml::table* table(const toml::table& t, std::string_view key) const {
    const toml::node* n = t.get(key);
    if (!n) return nullptr;
    if (!n->is_table()) fail(n->source(), fmt::format("expected '{}' to be a table", key));
    return n->as_table();
  }

  std::optional<int64_t> integer(const toml::table& t, std::string_view key, int64_t lo, int64_t hi,
                                 bool required = false) const {
    const toml::node* n = t.get(key);
    if (!n) {
      if (required) fail(t.source(), fmt::format("expected '{}' (an integer from {} to {}), found none", key, lo, hi));
      return std::nullopt;
    }
    const auto v = n->value_exact<int64_t>();
    if (!v) fail(n->source(), fmt::format("expected '{}' to be an integer", key));
    if (*v < lo || *v > hi) fail(n->source(), fmt::format("expected '{}' from {} to {}, found {}", key, lo, hi, *v));
    return v;
  }

  double as_number(const toml::node& n, std::string_view key) const {
    std::optional<double> v;
    if (n.is_floating_point()) v = n.value_exact<double>();
    else if (n.is_integer()) v = static_cast<double>(*n.value_exact<int64_t>());
    if (!v) fail(n.source(), fmt::format("expected '{}' to be a number", key));
    if (!std::isfinite(*v)) fail(n.source(), fmt::format("expected '{}' to be finite, found {}", key, *v));
    return *v;
  }

  std::optional<double> number(const toml::table& t, std::string_view key, double lo, double hi) const {
    const toml::node* n = t.get(key);
    if (!n) return std::nullopt;
    const double v = as_number(*n, key);
    if (v < lo || v > hi) fail(n->source(), fmt::format("expected '{}' from {} to {}, found {}", key, lo, hi, v));
    return v;
  }

  std::optional<std::string> string(const toml::table& t, std::string_view key) const {
    const toml::node* n = t.get(key);
    if (!n) return std::nullopt;
    if (!n->is_string()) fail(n->source(), fmt::format("expected '{}' to be a string", key));
    return std::string(*n->value_exact<std::string>());
  }

  std::string choice(const toml::table& t, std::string_view key, std::initializer_list<std::string_view> options,
                     std::string_view fallback) const {
    const auto s = string(t, key);
    if (!s) return std::string(fallback);
    std::string list;
    for (std::string_view o : options) {
      if (*s == o) return *s;
      list += fmt::format("{}{}", list.empty() ? "" : ", ", o);
    }
    fail(t.get(key)->source(), fmt::format("expected '{}' to be one of {}, found '{}'", key, list, *s));
  }

  std::optional<Vec3> vec3(const toml::table& t, std::string_view key, bool scalar_ok = false) const {
    const toml::node* n = t.get(key);
    if (!n) return std::nullopt;
    if (scalar_ok && (n->is_integer() || n->is_floating_point())) {
      const double v = as_number(*n, key);
      return Vec3{v, v, v};
    }
    const toml::array* a = n->as_array();
    if (!a || a->size() != 3)
      fail(n->source(), fmt::format("expected '{}' to be [x, y, z]{}", key, scalar_ok ? " or one number" : ""));
    return Vec3{as_number((*a)[0], key), as_number((*a)[1], key), as_number((*a)[2], key)};
  }

  Interpolation interpolation(const toml::table& t) const {
    return choice(t, "interpolation", {"linear", "smooth"}, "linear") == "smooth" ? Interpolation::smooth
                                                                                 : Interpolation::linear;
  }

  std::string resolve(const std::string& name) const {
    const std::filesystem::path p(name);
    if (p.is_absolute()) return name;
    return (std::filesystem::path(source_).parent_path() / p).lexically_normal().string();
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
        if (length(cross(key.from - key.at, key.up)) == 0)
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

  std::string_view text_;
  std::string source_;
};

}  // namespace

Shot parse_shot(std::string_view text, const std::string& source) { return ShotParser(text, source).run(); }

Shot read_shot_file(const std::string& path) { return parse_shot(read_text_file(path), path); }

}  // namespace holoray
