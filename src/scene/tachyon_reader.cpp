#include "scene/tachyon_reader.hpp"

#include <fmt/format.h>


#include <algorithm>
#include <cctype>
#include <cmath>
#include <deque>
#include <filesystem>
#include <map>
#include <memory>
#include <numbers>
#include <stdexcept>

#include "image/image_io.hpp"
#include "scene/file_text.hpp"
#include "scene/tokenizer.hpp"

namespace holoray {
namespace {

std::string upper(std::string_view s) {
  std::string u(s);
  for (char& c : u) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return u;
}

// Constructs of Tachyon's language that holoray does not read yet, with what
// to say about them (tachyon-notes §6).
const std::map<std::string, std::string_view>& unsupported_objects() {
  static const std::map<std::string, std::string_view> m{
      {"SPHEREARRAY", "sphere arrays"},
      {"SCALARVOL", "scalar volumes"},
      {"SKY_LIGHT", "ambient-occlusion sky lights"},
      {"SCAPE", "landscapes"},
      {"SHADER_MODE", "shader modes"},
      {"MGFFILE", "MGF files"},
      {"BACKGROUND_GRADIENT", "gradient backgrounds"},
      {"START_CLIPGROUP", "clip groups"},
      {"END_CLIPGROUP", "clip groups"},
      {"CYLINDER", "infinite cylinders; fcylinder is read"},
  };
  return m;
}

class TachyonParser {
 public:
  TachyonParser(std::string_view text, const std::string& source, const TachyonLimits& limits) : limits_(limits) {
    scene_.source = source;
    scene_.shading = ShadingModel::tachyon;
    push_file(text, source);
  }

  SceneDesc run() {
    // Tachyon skips `#` comments before BEGIN_SCENE; the tokenizer already does.
    expect_kw("BEGIN_SCENE");
    expect_kw("RESOLUTION");
    xres_ = resolution("the x resolution");
    yres_ = resolution("the y resolution");
    while (object()) {
    }
    // A Tachyon camera has no look-at point; the array needs one (contract,
    // "Placement": its width is the view's at `at`). Take the depth of the
    // centre of the scene's bounded objects, as a shot's camera path does.
    if (scene_.viewpoint) {
      Viewpoint& v = *scene_.viewpoint;
      Bounds3 b;
      for (const ObjectDesc& o : scene_.objects) {
        if (const auto* s = std::get_if<SphereDesc>(&o.shape)) b.extend(s->centre);
        else if (const auto* c = std::get_if<ConeDesc>(&o.shape)) b.extend(c->base), b.extend(c->apex);
        else if (const auto* p = std::get_if<PolygonDesc>(&o.shape)) for (const Vec3& q : p->vertices) b.extend(q);
        else if (const auto* m = std::get_if<TriangleMeshDesc>(&o.shape)) for (const Vec3& q : m->vertices) b.extend(q);
      }
      const Vec3 view = v.at - v.from;
      const double depth = b.empty() ? 0 : dot(b.centre() - v.from, view);
      if (depth > 0) v.at = v.from + view * depth;
    }
    if (!scene_.viewpoint) {
      // Tachyon's default camera (rt_newscene): at the origin looking down +z, zoom 1.
      Viewpoint v;
      v.from = {0, 0, 0};
      v.at = {0, 0, 1};
      v.up = {0, 1, 0};
      v.angle_deg = zoom_to_angle(1);
      v.xres = xres_, v.yres = yres_;
      v.mirrored = true;
      scene_.viewpoint = v;
    }
    return std::move(scene_);
  }

 private:
  struct File {
    std::string text;
    std::string source;
    std::unique_ptr<Tokenizer> tok;
  };

  Tokenizer& tok() { return *files_.back().tok; }

  void push_file(std::string_view text, const std::string& source) {
    File& f = files_.emplace_back();
    f.text = std::string(text);
    f.source = source;
    f.tok = std::make_unique<Tokenizer>(f.text, source);
  }

  // Full field of view of Tachyon's perspective camera: an image plane 1/zoom
  // tall at distance 1 from the eye (camera.c, camera_init).
  static double zoom_to_angle(double zoom) { return 2 * std::atan(0.5 / zoom) * 180 / std::numbers::pi; }

  int resolution(std::string_view what) {
    const Token t = tok().peek();
    const long v = tok().integer(what);
    if (v < 1 || v > (1L << 20)) tok().fail(t.loc, fmt::format("expected {} from 1 to 1048576, found {}", what, t.text));
    return static_cast<int>(v);
  }

  bool is_kw(const Token& t, std::string_view kw) const { return upper(t.text) == kw; }

  Token expect_kw(std::string_view kw) {
    const Token t = tok().next();
    if (!is_kw(t, kw)) tok().fail_expected(t, fmt::format("'{}'", kw));
    return t;
  }

  Vec3 vec3(std::string_view what) {
    Vec3 v;
    v.x = tok().number(what);
    v.y = tok().number(what);
    v.z = tok().number(what);
    return v;
  }

  // KEYWORD value: the pattern of most of Tachyon's fields.
  double keyed(std::string_view kw, std::string_view what) {
    expect_kw(kw);
    return tok().number(what);
  }
  Vec3 keyed_vec3(std::string_view kw, std::string_view what) {
    expect_kw(kw);
    return vec3(what);
  }
  Vec3 keyed_unit(std::string_view kw, std::string_view what) {
    expect_kw(kw);
    return unit(what);
  }

  Vec3 unit(std::string_view what) {
    const Token t = tok().peek();
    const Vec3 v = vec3(what);
    if (!(length(v) > 0)) tok().fail(t.loc, fmt::format("expected a non-zero {}, found (0, 0, 0)", what));
    return normalize(v);
  }

  double positive(std::string_view what) {
    const Token t = tok().peek();
    const double v = tok().number(what);
    if (!(v > 0)) tok().fail(t.loc, fmt::format("expected a positive {}, found {}", what, t.text));
    return v;
  }

  // One top-level item; false at END_SCENE or the end of the file.
  bool object() {
    const Token kw = tok().next();
    if (kw.text.empty()) {
      if (files_.size() > 1) {
        files_.pop_back();
        return true;
      }
      return false;
    }
    const std::string k = upper(kw.text);
    if (k == "END_SCENE") {
      if (files_.size() > 1) tok().fail(kw.loc, "expected the end of the included file, found 'END_SCENE'");
      return false;
    }
    if (k == "CAMERA") camera(kw);
    else if (k == "BACKGROUND") scene_.background = vec3("a background colour component");
    else if (k == "TEXDEF") texdef();
    else if (k == "TEXALIAS") texalias();
    else if (k == "LIGHT") light(kw, LightKind::point);
    else if (k == "SPOTLIGHT") light(kw, LightKind::spot);
    else if (k == "DIRECTIONAL_LIGHT") directional_light(kw);
    else if (k == "SPHERE") sphere(kw);
    else if (k == "FCYLINDER") fcylinder(kw);
    else if (k == "POLYCYLINDER") polycylinder(kw);
    else if (k == "RING") ring(kw);
    else if (k == "PLANE") plane(kw);
    else if (k == "BOX") box(kw);
    else if (k == "TRI") triangle(kw, false);
    else if (k == "VCSTRI") vcstri(kw);
    else if (k == "VERTEXARRAY") vertex_array(kw);
    else if (k == "STRI") triangle(kw, true);
    else if (k == "INCLUDE") include(kw);
    else if (k == "IMAGEDEF") imagedef();
    else if (k == "FOG") fog();
    else if (k == "TPOLYFILE") tpolyfile(kw);
    else if (auto it = unsupported_objects().find(k); it != unsupported_objects().end())
      tok().fail(kw.loc, fmt::format("'{}' ({}) is not supported yet (docs/tachyon-notes.md §6)", kw.text, it->second));
    else
      tok().fail_expected(kw, "a Tachyon object or declaration (camera, light, texdef, sphere, tri, plane, ...)");
    return true;
  }

  void camera(const Token& kw) {
    if (scene_.viewpoint) tok().fail(kw.loc, "expected one camera, found a second 'camera'");
    Token t = tok().next();
    if (is_kw(t, "PROJECTION")) {
      const Token p = tok().next();
      if (!is_kw(p, "PERSPECTIVE"))
        tok().fail(p.loc, fmt::format("the {} projection is not supported yet (perspective only)", describe_token(p)));
      t = tok().next();
    }
    if (!is_kw(t, "ZOOM")) tok().fail_expected(t, "'ZOOM' (or 'PROJECTION')");
    const double zoom = positive("the camera zoom");
    expect_kw("ASPECTRATIO");
    const Token a = tok().peek();
    const double aspect = tok().number("the aspect ratio");
    if (aspect != 1)
      tok().fail(a.loc, fmt::format("an aspect ratio other than 1 is not supported yet (square pixels), found {}", a.text));
    expect_kw("ANTIALIASING");
    tok().integer("the antialiasing sample count");  // holoray's --spp decides
    expect_kw("RAYDEPTH");
    const Token d = tok().peek();
    const long depth = tok().integer("the ray depth");
    if (depth < 1) tok().fail(d.loc, fmt::format("expected a ray depth of at least 1, found {}", d.text));
    if (depth > 16) warn(d.loc, fmt::format("raydepth {} is past holoray's cap; 16 used", d.text));
    Viewpoint v;
    v.loc = kw.loc;
    v.from = keyed_vec3("CENTER", "a camera centre coordinate");
    const Vec3 view = keyed_unit("VIEWDIR", "view direction");
    const Token up_tok = expect_kw("UPDIR");
    v.up = vec3("an up direction component");
    if (!up_orients(view, v.up))
      tok().fail(up_tok.loc, "expected an up direction not parallel to the view direction, found a parallel or zero one");
    const Token end = tok().next();
    if (is_kw(end, "FRUSTUM")) tok().fail(end.loc, "camera frustums are not supported yet");
    if (!is_kw(end, "END_CAMERA")) tok().fail_expected(end, "'END_CAMERA'");
    v.at = v.from + view;  // moved to the scene's depth once the objects are read (run())
    v.angle_deg = zoom_to_angle(zoom);
    v.xres = xres_, v.yres = yres_;
    v.mirrored = true;
    scene_.viewpoint = v;
    scene_.max_depth = static_cast<int>(std::min(depth, 16L));
  }

  // The texture after an object: `texture <body>` inline, or a name.
  int texture_ref() {
    const Token t = tok().next();
    if (t.text.empty()) tok().fail_expected(t, "a texture name or 'TEXTURE'");
    if (is_kw(t, "TEXTURE")) return texture_body(t);
    const auto it = textures_.find(std::string(t.text));
    if (it != textures_.end()) return it->second;
    // Tachyon prints "Undefined texture" and uses its default; so do we, loudly.
    warn(t.loc, fmt::format("undefined texture '{}': Tachyon's default (white, ambient 0.1, diffuse 0.9) used",
                            t.text));
    return default_material();
  }

  int default_material() {
    if (default_material_ < 0) {
      Material m;
      m.model = ShadingModel::tachyon;
      m.colour = {1, 1, 1};
      m.ambient = 0.1, m.kd = 0.9, m.ks = 0;
      scene_.materials.push_back(m);
      default_material_ = static_cast<int>(scene_.materials.size()) - 1;
    }
    return default_material_;
  }

  // A name defined again keeps its first texture: Tachyon's texture hash
  // does not replace an entry (VMD's exports reuse names past txt999, and
  // lattice.dat renders wrong without this). Warned, since it surprises.
  void name_texture(const Token& name, int material) {
    const auto [it, fresh] = textures_.try_emplace(std::string(name.text), material);
    if (!fresh)
      warn(name.loc, fmt::format("texture '{}' defined again: Tachyon keeps the first definition", name.text));
  }

  void texdef() {
    const Token name = tok().next();
    if (name.text.empty()) tok().fail_expected(name, "a texture name");
    name_texture(name, texture_body(name));
  }

  void texalias() {
    const Token name = tok().next();
    if (name.text.empty()) tok().fail_expected(name, "a texture name");
    const Token old = tok().next();
    const auto it = textures_.find(std::string(old.text));
    if (it == textures_.end()) tok().fail(old.loc, fmt::format("expected a defined texture name, found {}", describe_token(old)));
    name_texture(name, it->second);
  }

  // AMBIENT a DIFFUSE d SPECULAR s OPACITY o [PHONG PLASTIC|METAL p PHONG_SIZE e]
  // COLOR r g b TEXFUNC n [its parameters] (parse.c, GetTexBody).
  // With `vertex_coloured` (vcstri), `VCST` stands where COLOR and TEXFUNC
  // would: the colour comes from the vertices (parse.c, GetTexBody mode 1).
  int texture_body(const Token& at, bool vertex_coloured = false) {
    Material m;
    m.model = ShadingModel::tachyon;
    m.loc = at.loc;
    m.ambient = keyed("AMBIENT", "the ambient coefficient");
    m.kd = keyed("DIFFUSE", "the diffuse coefficient");
    m.ks = keyed("SPECULAR", "the specular (mirror) coefficient");
    expect_kw("OPACITY");
    const Token o = tok().peek();
    const double opacity = tok().number("the opacity");
    if (opacity < 0 || opacity > 1) tok().fail(o.loc, fmt::format("expected an opacity from 0 to 1, found {}", o.text));
    m.transmittance = 1 - opacity;
    m.ior = 1;
    Token t = tok().next();
    if (is_kw(t, "TRANSMODE")) tok().fail(t.loc, "Raster3D transparency modes (transmode) are not supported yet");
    if (is_kw(t, "OUTLINE")) tok().fail(t.loc, "outlines are not supported yet");
    m.shine = 100;  // Tachyon's phong_size when no PHONG is given (its weight is then 0)
    if (is_kw(t, "PHONG")) {
      const Token kind = tok().next();
      m.phong_metal = is_kw(kind, "METAL");
      if (!m.phong_metal && !is_kw(kind, "PLASTIC")) tok().fail_expected(kind, "'PLASTIC' or 'METAL'");
      m.phong = tok().number("the phong highlight weight");
      m.shine = keyed("PHONG_SIZE", "the phong exponent");
      t = tok().next();
    }
    if (vertex_coloured) {
      if (!is_kw(t, "VCST")) tok().fail_expected(t, "'VCST'");
      m.colour = {1, 1, 1};
      scene_.materials.push_back(m);
      return static_cast<int>(scene_.materials.size()) - 1;
    }
    if (!is_kw(t, "COLOR")) tok().fail_expected(t, "'COLOR'");
    m.colour = vec3("a texture colour component");
    expect_kw("TEXFUNC");
    const Token f = tok().peek();
    const long func = tok().integer("a texture function number (0 to 10)");
    switch (func) {
      case 0: break;
      case 1: case 4: case 6: m.texture = procedural(f, func); break;
      case 7: case 8: case 9: case 10: m.texture = image_texture(f, func); break;
      default: {
        static constexpr std::string_view names[] = {"constant", "3D checker", "grit", "marble", "wood", "gradient",
                                                     "cylindrical checker", "cylindrical image", "spherical image",
                                                     "planar image", "volume image"};
        if (func > 10) tok().fail(f.loc, fmt::format("expected a texture function from 0 to 10, found {}", f.text));
        tok().fail(f.loc, fmt::format("texfunc {} ({}) is not supported yet (0, 1, 4 and 6 to 10 are)", func,
                                      names[func]));
      }
    }
    scene_.materials.push_back(m);
    return static_cast<int>(scene_.materials.size()) - 1;
  }

  void placement(TextureDesc& t) {
    t.centre = keyed_vec3("CENTER", "a texture centre coordinate");
    t.rotate = keyed_vec3("ROTATE", "a texture rotation component");
    t.scale = keyed_vec3("SCALE", "a texture scale component");
  }

  int procedural(const Token& at, long func) {
    TextureDesc t;
    t.loc = at.loc;
    t.kind = static_cast<TextureDesc::Kind>(func);
    placement(t);
    if (t.kind == TextureDesc::Kind::wood && (t.scale.x == 0 || t.scale.y == 0 || t.scale.z == 0))
      tok().fail(at.loc, "expected a non-zero scale for the wood texture, found a zero component");
    scene_.textures.push_back(t);
    return static_cast<int>(scene_.textures.size()) - 1;
  }

  // texfunc 7 (cylindrical), 8 (spherical), 9 (planar), 10 (volume): an
  // image map name, the placement, the u and v axes for planar and volume
  // maps and the w axis for volume maps.
  int image_texture(const Token& at, long func) {
    TextureDesc t;
    t.loc = at.loc;
    t.kind = static_cast<TextureDesc::Kind>(func);
    const Token file = tok().next();
    if (file.text.empty()) tok().fail_expected(file, "an image file name");
    placement(t);
    if (t.kind == TextureDesc::Kind::planar_image || t.kind == TextureDesc::Kind::volume_image) {
      t.uaxis = keyed_vec3("UAXIS", "a u axis component");
      t.vaxis = keyed_vec3("VAXIS", "a v axis component");
    }
    if (t.kind == TextureDesc::Kind::volume_image) t.waxis = keyed_vec3("WAXIS", "a w axis component");
    t.image = image(file);
    scene_.textures.push_back(t);
    return static_cast<int>(scene_.textures.size()) - 1;
  }

  // Where a file named in the scene is: beside the naming file, else (as
  // Tachyon, which opens it as written) relative to the working folder.
  // Only regular files are opened: a device or a pipe (/dev/zero, a FIFO)
  // would read forever.
  std::string locate(const Token& name) {
    namespace fs = std::filesystem;
    const fs::path p(name.text);
    std::string found = p.string();
    std::error_code ec;
    if (!p.is_absolute()) {
      const fs::path beside = fs::path(files_.back().source).parent_path() / p;
      if (fs::exists(beside, ec)) found = beside.string();
    }
    if (fs::exists(found, ec) && !fs::is_regular_file(found, ec))
      tok().fail(name.loc, fmt::format("expected a regular file, found '{}', which is not one", found));
    return found;
  }

  // IMAGEDEF name FORMAT RGB24 RESOLUTION x y z ENCODING HEX texels: an image
  // map written in the scene, x fastest, then y, then z (z > 1: a volume for
  // texfunc 10). A texel is 3 hex digits (one per channel, f = 255) or 6
  // (two per channel). Texture functions find it by name before any file.
  void imagedef() {
    const Token name = tok().next();
    if (name.text.empty()) tok().fail_expected(name, "an image name");
    const Token format = tok().next();
    if (!is_kw(format, "FORMAT")) tok().fail_expected(format, "'FORMAT'");
    const Token rgb = tok().next();
    if (!is_kw(rgb, "RGB24")) tok().fail_expected(rgb, "'RGB24' (the only inline image format)");
    expect_kw("RESOLUTION");
    const Token res = tok().peek();
    long size[3];
    for (long& n : size) {
      n = tok().integer("an image resolution (x y z)");
      if (n < 1 || n > limits_.max_image_pixels)
        tok().fail(res.loc, fmt::format("expected an image resolution of 1 to {} texels per axis, found {}",
                                        limits_.max_image_pixels, n));
    }
    // Each factor is at most the bound, so the products cannot overflow.
    if (size[0] * size[1] > limits_.max_image_pixels || size[0] * size[1] * size[2] > limits_.max_image_pixels)
      tok().fail(res.loc, fmt::format("expected an image of at most {} texels, found {}x{}x{}",
                                      limits_.max_image_pixels, size[0], size[1], size[2]));
    expect_kw("ENCODING");
    const Token enc = tok().next();
    if (!is_kw(enc, "HEX")) tok().fail_expected(enc, "'HEX' (the only inline image encoding)");
    ImageMap img;
    img.path = std::string(name.text);
    img.width = static_cast<int>(size[0]), img.height = static_cast<int>(size[1]), img.depth = static_cast<int>(size[2]);
    const long texels = size[0] * size[1] * size[2];
    img.rgb.reserve(size_t(texels) * 3);
    for (long i = 0; i < texels; ++i) {
      const Token t = tok().next();
      const size_t digits = t.text.size() / 3;
      if ((t.text.size() != 3 && t.text.size() != 6) ||
          t.text.find_first_not_of("0123456789abcdefABCDEF") != std::string_view::npos)
        tok().fail_expected(t, fmt::format("texel {} of {} of image '{}': 3 or 6 hex digits", i + 1, texels, name.text));
      for (size_t c = 0; c < 3; ++c) {
        const int v = std::stoi(std::string(t.text.substr(c * digits, digits)), nullptr, 16);
        img.rgb.push_back(static_cast<unsigned char>(digits == 1 ? v * 17 : v));
      }
    }
    if (inline_images_.count(img.path))
      warn(name.loc, fmt::format("image '{}' defined again: Tachyon keeps the first definition", name.text));
    else {
      scene_.images.push_back(std::move(img));
      inline_images_[std::string(name.text)] = static_cast<int>(scene_.images.size()) - 1;
    }
  }

  // Tachyon's stand-in for an image it cannot load (imageio.c): 4x4 white.
  int stand_in_image(const Token& file) {
    const std::string key = std::string(file.text);
    if (auto it = inline_images_.find(key); it != inline_images_.end()) return it->second;
    warn(file.loc, fmt::format("no inline image '{}' (IMAGEDEF) was defined: Tachyon's stand-in (4x4 white) used",
                               file.text));
    ImageMap img;
    img.path = key;
    img.width = img.height = 4;
    img.rgb.assign(4 * 4 * 3, 255);
    scene_.images.push_back(std::move(img));
    inline_images_[key] = static_cast<int>(scene_.images.size()) - 1;
    return inline_images_[key];
  }

  int image(const Token& file) {
    if (auto it = inline_images_.find(std::string(file.text)); it != inline_images_.end()) return it->second;
    // "::name" is the inline-image convention: no file is meant, so an
    // undefined one takes Tachyon's stand-in (imagedef.dat tests exactly
    // that); a file that cannot be read is an error.
    if (file.text.starts_with("::")) return stand_in_image(file);
    const std::string path = locate(file);
    if (auto it = images_.find(path); it != images_.end()) return it->second;
    ImageHeader header;
    try {
      header = read_image_header(path);
    } catch (const ImageReadError& e) {
      tok().fail(file.loc, fmt::format("cannot read the image map '{}': {}", path, e.reason()));
    }
    if (header.width < 1 || header.height < 1 || int64_t{header.width} * header.height > limits_.max_image_pixels)
      tok().fail(file.loc, fmt::format("expected an image map of at most {} pixels, found {}x{} in '{}'",
                                       limits_.max_image_pixels, header.width, header.height, path));
    ImageBuffer raw;
    try {
      raw = read_image(path);
    } catch (const ImageReadError& e) {
      tok().fail(file.loc, fmt::format("cannot read the image map '{}': {}", path, e.reason()));
    }
    ImageMap img;
    img.path = path;
    img.width = raw.width, img.height = raw.height;
    // Tachyon keeps rows in the order the file stores them and maps v = 0 to
    // the first: the top row of a PPM or PNG, the bottom row of a Targa
    // (stored bottom-up). read_image hands every format over top-down.
    // Channels past the third (alpha) are dropped; a grey image fills all
    // three; values become 8-bit codes rounded to nearest.
    const bool bottom_up = header.format == "targa";
    const int nch = raw.channels;
    img.rgb.resize(size_t(raw.width) * raw.height * 3);
    for (int y = 0; y < raw.height; ++y)
      for (int x = 0; x < raw.width; ++x)
        for (int c = 0; c < 3; ++c)
          img.rgb[(size_t(bottom_up ? raw.height - 1 - y : y) * raw.width + x) * 3 + c] =
              static_cast<unsigned char>(std::clamp(raw.at(x, y)[std::min(c, nch - 1)] * 255.0f + 0.5f, 0.0f, 255.0f));
    scene_.images.push_back(std::move(img));
    const int id = static_cast<int>(scene_.images.size()) - 1;
    images_[path] = id;
    return id;
  }

  void light(const Token& kw, LightKind kind) {
    Light l;
    l.loc = kw.loc;
    l.kind = kind;
    l.position = keyed_vec3("CENTER", "a light centre coordinate");
    expect_kw("RAD");
    const Token rad_tok = tok().peek();
    const double radius = tok().number("the light radius");
    if (radius < 0) tok().fail(rad_tok.loc, fmt::format("expected a light radius >= 0, found {}", rad_tok.text));
    if (kind == LightKind::spot) {
      l.direction = keyed_unit("DIRECTION", "spotlight direction");
      expect_kw("FALLOFF_START");
      const double start = tok().number("the falloff start angle (degrees)");
      expect_kw("FALLOFF_END");
      const Token e = tok().peek();
      const double end = tok().number("the falloff end angle (degrees)");
      if (!(end >= start)) tok().fail(e.loc, fmt::format("expected a falloff end >= its start ({}), found {}", start, e.text));
      l.fall_start = start * std::numbers::pi / 180;
      l.fall_end = end * std::numbers::pi / 180;
    }
    const Token t = tok().next();
    if (is_kw(t, "ATTENUATION")) {
      l.kc = keyed("CONSTANT", "the constant attenuation");
      l.kl = keyed("LINEAR", "the linear attenuation");
      l.kq = keyed("QUADRATIC", "the quadratic attenuation");
      if (l.kc < 0 || l.kl < 0 || l.kq < 0 || l.kc + l.kl + l.kq <= 0)
        tok().fail(t.loc, "expected attenuation coefficients >= 0, not all 0");
      expect_kw("COLOR");
    } else if (!is_kw(t, "COLOR")) {
      tok().fail_expected(t, "'COLOR' or 'ATTENUATION'");
    }
    l.colour = vec3("a light colour component");
    add_light(kw, l);
    // Tachyon draws a point light or spotlight as a sphere in its colour,
    // seen by eye and mirror rays but casting no shadow (light.c).
    if (radius > 0) {
      Material glow;
      glow.model = ShadingModel::tachyon;
      glow.emitter = true;
      glow.colour = l.colour;
      glow.loc = kw.loc;
      scene_.materials.push_back(glow);
      add(kw, SphereDesc{l.position, radius, false}, static_cast<int>(scene_.materials.size()) - 1);
    }
  }

  void directional_light(const Token& kw) {
    Light l;
    l.loc = kw.loc;
    l.kind = LightKind::directional;
    l.direction = keyed_unit("DIRECTION", "light direction");
    l.colour = keyed_vec3("COLOR", "a light colour component");
    add_light(kw, l);
  }

  void add_light(const Token& kw, const Light& l) {
    if (static_cast<long>(scene_.lights.size()) >= limits_.max_lights)
      tok().fail(kw.loc, fmt::format("expected at most {} lights in one file, found more", limits_.max_lights));
    scene_.lights.push_back(l);
  }

  void add(const Token& kw, auto shape, int material) {
    if (static_cast<long>(scene_.objects.size()) >= limits_.max_objects)
      tok().fail(kw.loc, fmt::format("expected at most {} objects in one file, found more", limits_.max_objects));
    scene_.objects.push_back(ObjectDesc{std::move(shape), material, kw.loc});
  }

  void sphere(const Token& kw) {
    expect_kw("CENTER");
    SphereDesc s;
    s.centre = vec3("a sphere centre coordinate");
    expect_kw("RAD");
    s.radius = positive("sphere radius");
    add(kw, s, texture_ref());
  }

  // Tachyon's fcylinder is open (no caps), like NFF's cone with equal radii.
  void fcylinder(const Token& kw) {
    ConeDesc c;
    c.base = keyed_vec3("BASE", "a cylinder base coordinate");
    c.apex = keyed_vec3("APEX", "a cylinder apex coordinate");
    if (c.base == c.apex) tok().fail(kw.loc, "expected distinct cylinder base and apex, found the same point");
    expect_kw("RAD");
    c.base_radius = c.apex_radius = positive("cylinder radius");
    add(kw, c, texture_ref());
  }

  // A sphere at every point and an open cylinder between neighbours
  // (Tachyon's rt_polycylinder), all one material.
  void polycylinder(const Token& kw) {
    expect_kw("POINTS");
    const Token n_tok = tok().peek();
    const long n = tok().integer("a point count");
    if (n < 1 || n > limits_.max_polycylinder_points)
      tok().fail(n_tok.loc, fmt::format("expected a point count from 1 to {}, found {}", limits_.max_polycylinder_points, n));
    std::vector<Vec3> points;
    for (long i = 0; i < n; ++i) points.push_back(vec3("a polycylinder point coordinate"));
    expect_kw("RAD");
    const double r = positive("polycylinder radius");
    const int material = texture_ref();
    for (size_t i = 0; i < points.size(); ++i) {
      add(kw, SphereDesc{points[i], r}, material);
      if (i > 0 && points[i] != points[i - 1]) add(kw, ConeDesc{points[i - 1], points[i], r, r}, material);
    }
  }

  // An annulus (a disc when inner is 0) as one triangle mesh: 256 segments,
  // which keeps its edge within 8e-5 of its radius, under a pixel in any
  // view that shows the whole ring.
  void ring(const Token& kw) {
    const Vec3 c = keyed_vec3("CENTER", "a ring centre coordinate");
    const Vec3 n = keyed_unit("NORMAL", "ring normal");
    expect_kw("INNER");
    const Token in_tok = tok().peek();
    const double inner = tok().number("the inner radius");
    expect_kw("OUTER");
    const Token out_tok = tok().peek();
    const double outer = tok().number("the outer radius");
    if (inner < 0) tok().fail(in_tok.loc, fmt::format("expected an inner radius >= 0, found {}", in_tok.text));
    if (!(outer > inner)) tok().fail(out_tok.loc, fmt::format("expected an outer radius larger than the inner ({}), found {}", inner, out_tok.text));
    const Frame f = Frame::from_normal_up(c, n, std::fabs(n.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0});
    constexpr int kSegments = 256;
    TriangleMeshDesc m;
    for (int i = 0; i < kSegments; ++i) {
      const double a = 2 * std::numbers::pi * i / kSegments;
      const Vec3 dir = f.x * std::cos(a) + f.y * std::sin(a);
      m.vertices.push_back(c + dir * outer);
      m.vertices.push_back(c + dir * inner);
    }
    for (uint32_t i = 0; i < kSegments; ++i) {
      const uint32_t o0 = 2 * i, i0 = 2 * i + 1, o1 = 2 * ((i + 1) % kSegments), i1 = o1 + 1;
      m.triangles.push_back({o0, o1, i0});  // counter-clockwise about n (f.x, f.y, n right-handed)
      if (inner > 0) m.triangles.push_back({i0, o1, i1});
    }
    add(kw, std::move(m), texture_ref());
  }

  void plane(const Token& kw) {
    PlaneDesc p;
    p.point = keyed_vec3("CENTER", "a plane centre coordinate");
    p.normal = keyed_unit("NORMAL", "plane normal");
    add(kw, p, texture_ref());
  }

  // An axis-aligned box as 12 outward-facing triangles.
  void box(const Token& kw) {
    const Vec3 lo = keyed_vec3("MIN", "a box corner coordinate");
    const Vec3 hi = keyed_vec3("MAX", "a box corner coordinate");
    const Vec3 a{std::fmin(lo.x, hi.x), std::fmin(lo.y, hi.y), std::fmin(lo.z, hi.z)};
    const Vec3 b{std::fmax(lo.x, hi.x), std::fmax(lo.y, hi.y), std::fmax(lo.z, hi.z)};
    if (!(a.x < b.x && a.y < b.y && a.z < b.z)) tok().fail(kw.loc, "expected a box with volume, found a flat or empty one");
    TriangleMeshDesc m;
    for (int i = 0; i < 8; ++i) m.vertices.push_back({i & 1 ? b.x : a.x, i & 2 ? b.y : a.y, i & 4 ? b.z : a.z});
    // Faces as corner bit patterns, counter-clockwise seen from outside.
    static constexpr uint32_t faces[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                             {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
    for (const auto& q : faces) {
      m.triangles.push_back({q[0], q[1], q[2]});
      m.triangles.push_back({q[0], q[2], q[3]});
    }
    add(kw, std::move(m), texture_ref());
  }

  void triangle(const Token& kw, bool smooth) {
    PolygonDesc p;
    for (const char* v : {"V0", "V1", "V2"}) p.vertices.push_back(keyed_vec3(v, "a vertex coordinate"));
    if (smooth)
      for (const char* n : {"N0", "N1", "N2"}) p.normals.push_back(keyed_vec3(n, "a vertex normal component"));
    if (length(cross(p.vertices[1] - p.vertices[0], p.vertices[2] - p.vertices[0])) == 0)
      warn(kw.loc, "triangle with no area (collinear or repeated vertices), skipped");
    add(kw, std::move(p), texture_ref());
  }

  // TPOLYFILE SCALE s ROT r CENTER c FILE f texture: triangles from a file of
  // "3 x y z x y z x y z" records, each vertex scaled, rotated by Tachyon's
  // InitRot3d of r degrees (reproduced as it is, rz1 = sin(ry) included) and
  // moved by c, wound v1 v0 v2 (parse.c, GetTPolyFile).
  void tpolyfile(const Token& kw) {
    const Vec3 scale = keyed_vec3("SCALE", "a scale component");
    const Vec3 r = keyed_vec3("ROT", "a rotation angle (degrees)") * (3.1415926 / 180.0);
    const Vec3 centre = keyed_vec3("CENTER", "a centre coordinate");
    expect_kw("FILE");
    const Token name = tok().next();
    if (name.text.empty()) tok().fail_expected(name, "a polygon file name");
    const int material = texture_ref();
    const std::string path = locate(name);
    std::string text;
    try {
      text = read_text_file(path);
    } catch (const std::runtime_error& e) {
      tok().fail(name.loc, e.what());
    }
    const double cx = std::cos(r.x), sx = std::sin(r.x), cy = std::cos(r.y), sy = std::sin(r.y), cz = std::cos(r.z),
                 sz = std::sin(r.z);
    const Vec3 row_x{cy * cz, sx * sy * cz - cx * sz, sx * sz + cx * cz * sy};
    const Vec3 row_y{cy * sz, cx * cz + sx * sy * sz, cx * sy * sz - sx * cz};
    const Vec3 row_z{sy, sx * cy, cx * cy};
    auto place = [&](const Vec3& v) {
      const Vec3 s = mul(v, scale);
      return Vec3{dot(row_x, s), dot(row_y, s), dot(row_z, s)} + centre;
    };
    Tokenizer poly(text, path);
    while (!poly.at_end()) {
      const Token count = poly.peek();
      if (count.text != "3") break;  // Tachyon stops at the first record that is not a triangle
      poly.next();
      Vec3 v[3];
      for (Vec3& p : v) {
        p.x = poly.number("a vertex coordinate");
        p.y = poly.number("a vertex coordinate");
        p.z = poly.number("a vertex coordinate");
      }
      PolygonDesc tri;
      tri.vertices = {place(v[1]), place(v[0]), place(v[2])};
      add(kw, std::move(tri), material);
    }
  }

  // FOG LINEAR|EXP|EXP2|OFF START s END e DENSITY d COLOR rgb
  void fog() {
    const Token mode = tok().next();
    FogDesc f;
    const std::string m = upper(mode.text);
    bool off = false;
    if (m == "LINEAR") f.mode = FogDesc::Mode::linear;
    else if (m == "EXP") f.mode = FogDesc::Mode::exp;
    else if (m == "EXP2") f.mode = FogDesc::Mode::exp2;
    else if (m == "OFF") off = true;
    else tok().fail_expected(mode, "'LINEAR', 'EXP', 'EXP2' or 'OFF'");
    f.start = keyed("START", "the fog start distance");
    expect_kw("END");
    const Token e = tok().peek();
    f.end = tok().number("the fog end distance");
    if (f.mode == FogDesc::Mode::linear && !off && !(f.end > f.start))
      tok().fail(e.loc, fmt::format("expected a fog end past its start ({}), found {}", f.start, e.text));
    f.density = keyed("DENSITY", "the fog density");
    f.colour = keyed_vec3("COLOR", "a fog colour component");
    if (off) scene_.fog.reset();
    else scene_.fog = f;
  }

  // VCSTRI V0 V1 V2 N0 N1 N2 C0 C1 C2 <texture body ending in VCST>: a
  // smooth triangle coloured by its vertices.
  void vcstri(const Token& kw) {
    TriangleMeshDesc m;
    for (const char* v : {"V0", "V1", "V2"}) m.vertices.push_back(keyed_vec3(v, "a vertex coordinate"));
    for (const char* n : {"N0", "N1", "N2"}) m.normals.push_back(keyed_vec3(n, "a vertex normal component"));
    for (const char* c : {"C0", "C1", "C2"}) m.colours.push_back(keyed_vec3(c, "a vertex colour component"));
    m.triangles.push_back({0, 1, 2});
    const int material = texture_body(kw, true);
    add(kw, std::move(m), material);
  }

  // VERTEXARRAY NUMVERTS n COORDS (n points) NORMALS (n normals), then any of
  // COLORS (n colours), TEXTURE <body>, TRIMESH f (f index triples) and
  // TRISTRIP m (m indices), until END_VERTEXARRAY (parse.c,
  // GetVertexArray). Each TRIMESH or TRISTRIP is one object of the
  // texture given before it (Tachyon's default before any); with COLORS its
  // vertices colour it.
  void vertex_array(const Token& kw) {
    expect_kw("NUMVERTS");
    const Token n_tok = tok().peek();
    const long n = tok().integer("a vertex count");
    if (n < 1 || n > limits_.max_objects)
      tok().fail(n_tok.loc, fmt::format("expected a vertex count from 1 to {}, found {}", limits_.max_objects, n));
    TriangleMeshDesc base;
    expect_kw("COORDS");
    for (long i = 0; i < n; ++i) base.vertices.push_back(vec3("a vertex coordinate"));
    expect_kw("NORMALS");
    for (long i = 0; i < n; ++i) base.normals.push_back(vec3("a vertex normal component"));
    int material = -1;
    for (;;) {
      const Token t = tok().next();
      if (is_kw(t, "END_VERTEXARRAY")) return;
      if (is_kw(t, "COLORS")) {
        base.colours.clear();
        for (long i = 0; i < n; ++i) base.colours.push_back(vec3("a vertex colour component"));
      } else if (is_kw(t, "TEXTURE")) {
        material = texture_body(t);
      } else if (is_kw(t, "TRIMESH") || is_kw(t, "TRISTRIP")) {
        const bool strip = is_kw(t, "TRISTRIP");
        const Token c_tok = tok().peek();
        const long count = tok().integer(strip ? "a strip length" : "a triangle count");
        if (count > limits_.max_objects)
          tok().fail(c_tok.loc, fmt::format("expected at most {}, found {}", limits_.max_objects, count));
        std::vector<uint32_t> idx;
        for (long i = 0; i < (strip ? count : 3 * count); ++i) {
          const Token v = tok().peek();
          const long k = tok().integer("a vertex index");
          if (k >= n) tok().fail(v.loc, fmt::format("expected a vertex index below {}, found {}", n, k));
          idx.push_back(static_cast<uint32_t>(k));
        }
        TriangleMeshDesc m = base;
        if (strip) {
          // Every other triangle of a strip is wound the other way round.
          for (size_t i = 0; i + 2 < idx.size(); ++i)
            m.triangles.push_back(i % 2 == 0 ? std::array<uint32_t, 3>{idx[i], idx[i + 1], idx[i + 2]}
                                             : std::array<uint32_t, 3>{idx[i + 1], idx[i], idx[i + 2]});
        } else {
          for (size_t i = 0; i + 2 < idx.size(); i += 3) m.triangles.push_back({idx[i], idx[i + 1], idx[i + 2]});
        }
        if (!m.triangles.empty()) add(kw, std::move(m), material < 0 ? default_material() : material);
      } else {
        tok().fail_expected(t, "'COLORS', 'TEXTURE', 'TRIMESH', 'TRISTRIP' or 'END_VERTEXARRAY'");
      }
    }
  }

  void include(const Token& kw) {
    const Token name = tok().next();
    if (name.text.empty()) tok().fail_expected(name, "an include file name");
    if (static_cast<int>(files_.size()) > limits_.max_include_depth)
      tok().fail(kw.loc, fmt::format("expected includes nested at most {} deep, found deeper (a file including itself?)",
                                     limits_.max_include_depth));
    const std::string path = locate(name);
    std::string text;
    try {
      text = read_text_file(path);
    } catch (const std::runtime_error& e) {
      tok().fail(name.loc, e.what());
    }
    push_file(text, path);
  }

  void warn(SourceLoc loc, std::string_view message) {
    if (static_cast<long>(scene_.warning_count++) >= limits_.max_warnings_kept) return;
    scene_.warnings.push_back(fmt::format("{}:{}:{}: warning: {}", tok().source(), loc.line, loc.col, message));
  }

  TachyonLimits limits_;
  SceneDesc scene_;
  std::deque<File> files_;
  std::map<std::string, int> textures_;  // name -> material
  std::map<std::string, int> images_;    // resolved path -> image
  std::map<std::string, int> inline_images_;  // IMAGEDEF name -> image
  int default_material_ = -1;
  int xres_ = 512, yres_ = 512;
};

}  // namespace

SceneDesc parse_tachyon(std::string_view text, const std::string& source, const TachyonLimits& limits) {
  return TachyonParser(text, source, limits).run();
}

SceneDesc read_tachyon_file(const std::string& path, const TachyonLimits& limits) {
  return parse_tachyon(read_text_file(path), path, limits);
}

}  // namespace holoray
