#include "scene/nff_reader.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "scene/file_text.hpp"
#include "scene/tessellate.hpp"
#include "scene/tokenizer.hpp"

namespace holoray {
namespace {

class NffParser {
 public:
  NffParser(std::string_view text, const std::string& source, const NffLimits& limits)
      : tok_(text, source), limits_(limits) {
    scene_.source = source;
  }

  SceneDesc run() {
    while (!tok_.at_end()) {
      const Token kw = tok_.next();
      if (kw.text == "v") viewpoint(kw);
      else if (kw.text == "b") scene_.background = colour("background colour");
      else if (kw.text == "l") light(kw);
      else if (kw.text == "f") material(kw);
      else if (kw.text == "c") cone(kw);
      else if (kw.text == "s") sphere(kw);
      else if (kw.text == "p") polygon(kw, false);
      else if (kw.text == "pp") polygon(kw, true);
      else tok_.fail_expected(kw, "an NFF entity (v, b, l, f, c, s, p, pp)");
    }
    return std::move(scene_);
  }

 private:
  Vec3 vec3(std::string_view what) {
    Vec3 v;
    v.x = tok_.number(what);
    v.y = tok_.number(what);
    v.z = tok_.number(what);
    return v;
  }
  Vec3 colour(std::string_view what) { return vec3(what); }

  void viewpoint(const Token& kw) {
    if (scene_.viewpoint)
      tok_.fail(kw.loc, fmt::format("expected one viewpoint, found a second 'v' (the first is on line {})",
                                    scene_.viewpoint->loc.line));
    Viewpoint v;
    v.loc = kw.loc;
    tok_.expect("from");
    v.from = vec3("a 'from' coordinate");
    tok_.expect("at");
    v.at = vec3("an 'at' coordinate");
    const Token up_tok = tok_.peek();
    tok_.expect("up");
    v.up = vec3("an 'up' component");
    tok_.expect("angle");
    const Token angle_value = tok_.peek();
    v.angle_deg = tok_.number("the view angle in degrees");
    if (!(v.angle_deg > 0 && v.angle_deg < 180))
      tok_.fail(angle_value.loc, fmt::format("expected a view angle between 0 and 180 degrees, found {}", angle_value.text));
    if (tok_.peek().text == "hither") {
      tok_.next();
      v.hither = tok_.number("the hither distance");
    }
    if (tok_.peek().text == "resolution") {
      tok_.next();
      v.xres = static_cast<int>(std::min(tok_.integer("the x resolution"), 1L << 30));
      v.yres = static_cast<int>(std::min(tok_.integer("the y resolution"), 1L << 30));
    }
    if (!(length(v.from - v.at) > 0)) tok_.fail(v.loc, "expected 'from' and 'at' to differ, found the same point");
    if (!up_orients(v.at - v.from, v.up))
      tok_.fail(up_tok.loc, "expected an 'up' direction not parallel to the view direction, found a parallel or zero one");
    scene_.viewpoint = v;
  }

  void light(const Token& kw) {
    Light l;
    l.loc = kw.loc;
    l.position = vec3("a light position coordinate");
    if (tok_.next_is_number()) l.colour = colour("a light colour component");  // optional RGB (nff-notes §4)
    if (static_cast<long>(scene_.lights.size()) >= limits_.max_lights)
      tok_.fail(kw.loc, fmt::format("expected at most {} lights in one file, found more", limits_.max_lights));
    scene_.lights.push_back(l);
  }

  void material(const Token& kw) {
    Material m;
    m.loc = kw.loc;
    m.colour = colour("a fill colour component");
    m.kd = tok_.number("Kd (diffuse coefficient)");
    m.ks = tok_.number("Ks (specular coefficient)");
    m.shine = tok_.number("Shine (Phong exponent)");
    const Token t_tok = tok_.peek();
    m.transmittance = tok_.number("T (transmittance)");
    const Token ior_tok = tok_.peek();
    m.ior = tok_.number("the index of refraction");
    if (m.transmittance > 0 && !(m.ior > 0))
      tok_.fail(ior_tok.loc, fmt::format("expected a positive index of refraction for a transmitting material, found {}", ior_tok.text));
    if (m.transmittance < 0) tok_.fail(t_tok.loc, fmt::format("expected a transmittance >= 0, found {}", t_tok.text));
    if (m.transmittance == 0) m.ior = 1;  // opaque SPD materials carry ior 0 (nff-notes §11)
    scene_.materials.push_back(m);
    material_ = static_cast<int>(scene_.materials.size()) - 1;
  }

  void add(const Token& kw, auto shape) {
    if (static_cast<long>(scene_.objects.size()) >= limits_.max_objects)
      tok_.fail(kw.loc, fmt::format("expected at most {} objects in one file, found more", limits_.max_objects));
    scene_.objects.push_back(ObjectDesc{std::move(shape), material_, kw.loc});
  }

  void sphere(const Token& kw) {
    SphereDesc s;
    s.centre = vec3("a sphere centre coordinate");
    const Token r = tok_.peek();
    s.radius = tok_.number("the sphere radius");
    if (s.radius == 0) tok_.fail(r.loc, "expected a non-zero sphere radius, found 0");
    if (s.radius < 0) warn(r.loc, "negative sphere radius: only the inside is visible (nff-notes, 's')");
    add(kw, s);
  }

  void cone(const Token& kw) {
    ConeDesc c;
    c.base = vec3("a cone base coordinate");
    const Token br = tok_.peek();
    c.base_radius = tok_.number("the cone base radius");
    c.apex = vec3("a cone apex coordinate");
    const Token ar = tok_.peek();
    c.apex_radius = tok_.number("the cone apex radius");
    if (c.base == c.apex) tok_.fail(kw.loc, "expected distinct cone base and apex, found the same point");
    if (c.base_radius == 0 && c.apex_radius == 0) tok_.fail(br.loc, "expected a non-zero cone radius, found both radii 0");
    if ((c.base_radius < 0) != (c.apex_radius < 0) && c.base_radius != 0 && c.apex_radius != 0)
      tok_.fail(ar.loc, fmt::format("expected cone radii of the same sign (both negative: inside only), found {} and {}",
                                    br.text, ar.text));
    add(kw, c);
  }

  void polygon(const Token& kw, bool patch) {
    const Token count_tok = tok_.peek();
    const long n = tok_.integer(patch ? "a patch vertex count" : "a polygon vertex count");
    if (n < 3) tok_.fail(count_tok.loc, fmt::format("expected a vertex count of at least 3, found {}", n));
    if (n > limits_.max_polygon_vertices)
      tok_.fail(count_tok.loc, fmt::format("expected a vertex count of at most {}, found {}", limits_.max_polygon_vertices, n));
    PolygonDesc p;
    // No reserve(n): a lying count must not allocate before the vertices exist.
    for (long i = 0; i < n; ++i) {
      p.vertices.push_back(vec3("a vertex coordinate"));
      if (patch) p.normals.push_back(vec3("a vertex normal component"));
    }
    if (polygon_normal(p.vertices) == Vec3{}) warn(kw.loc, "polygon with no area (collinear or repeated vertices), skipped");
    add(kw, std::move(p));
  }

  // Accepted but probably not what the author meant; the caller shows them.
  void warn(SourceLoc loc, std::string_view message) {
    if (static_cast<long>(scene_.warning_count++) >= limits_.max_warnings_kept) return;
    scene_.warnings.push_back(fmt::format("{}:{}:{}: warning: {}", tok_.source(), loc.line, loc.col, message));
  }

  Tokenizer tok_;
  NffLimits limits_;
  SceneDesc scene_;
  int material_ = -1;
};

}  // namespace

SceneDesc parse_nff(std::string_view text, const std::string& source, const NffLimits& limits) {
  return NffParser(text, source, limits).run();
}

SceneDesc read_nff_file(const std::string& path, const NffLimits& limits) {
  return parse_nff(read_text_file(path), path, limits);
}

}  // namespace holoray
