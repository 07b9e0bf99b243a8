#include "display/display_file.hpp"

#include <fmt/format.h>

#include <cmath>

#include "scene/file_text.hpp"
#include "scene/toml_fields.hpp"

namespace holoray {

const char* to_string(SubpixelOrder o) {
  switch (o) {
    case SubpixelOrder::none: return "none";
    case SubpixelOrder::rgb: return "rgb";
    case SubpixelOrder::bgr: return "bgr";
  }
  return "?";
}

namespace {

constexpr int64_t kMaxPanelSide = 1 << 20;  // pixels; buffers are checked against memory later

class DisplayParser : TomlFields {
 public:
  using TomlFields::TomlFields;

  DisplayDesc run() {
    const toml::table root = parse();
    check_keys(root, "the display file", {"name", "panel", "lens", "scene"});
    DisplayDesc d;
    d.source = source();
    const toml::table* panel = table(root, "panel");
    if (!panel) fail(root.source(), "expected a [panel] table (resolution, pixel_pitch_mm), found none");
    const toml::table* lens = table(root, "lens");
    if (!lens) fail(root.source(), "expected a [lens] table (grid, pitch_mm, gap_mm), found none");
    read_panel(*panel, d);
    read_lens(*lens, d);
    if (const toml::table* scene = table(root, "scene")) read_scene(*scene, d);
    return d;
  }

 private:
  // A required positive length in millimetres, named with its unit when refused.
  double length_mm(const toml::table& t, std::string_view key, std::string_view what) const {
    const toml::node* n = t.get(key);
    if (!n) fail(t.source(), fmt::format("expected '{}' ({}, mm), found none", key, what));
    const double v = as_number(*n, key);
    if (!(v > 0)) fail(n->source(), fmt::format("expected a positive '{}' ({}), found {} mm", key, what, v));
    return v;
  }

  void read_panel(const toml::table& p, DisplayDesc& d) const {
    check_keys(p, "[panel]", {"resolution", "pixel_pitch_mm", "subpixels"});
    const toml::node* res = p.get("resolution");
    const toml::array* a = res ? res->as_array() : nullptr;
    if (!a || a->size() != 2 || !(*a)[0].is_integer() || !(*a)[1].is_integer())
      fail(res ? res->source() : p.source(), "expected 'resolution' = [width, height] in pixels (integers)");
    for (int k = 0; k < 2; ++k) {
      const int64_t v = *(*a)[k].value_exact<int64_t>();
      if (v < 1 || v > kMaxPanelSide)
        fail((*a)[k].source(),
             fmt::format("expected a panel {} from 1 to {} pixels, found {} pixels", k ? "height" : "width", kMaxPanelSide, v));
      (k ? d.height : d.width) = static_cast<int>(v);
    }
    d.pixel_pitch_mm = length_mm(p, "pixel_pitch_mm", "the pixel pitch");
    const std::string sub = choice(p, "subpixels", {"rgb", "bgr", "none"}, "rgb");
    d.subpixels = sub == "none" ? SubpixelOrder::none : sub == "bgr" ? SubpixelOrder::bgr : SubpixelOrder::rgb;
  }

  void read_lens(const toml::table& l, DisplayDesc& d) const {
    check_keys(l, "[lens]", {"grid", "pitch_mm", "slant_deg", "gap_mm", "focal_length_mm", "offset_mm",
                             "view_distance_mm"});
    const std::string grid = choice(l, "grid", {"square", "hex", "lenticular"}, "lenticular");
    d.grid = grid == "square" ? Grid::square : grid == "hex" ? Grid::hex : Grid::lenticular;
    d.pitch_mm = length_mm(l, "pitch_mm", "the lens pitch");
    if (d.pitch_mm < d.pixel_pitch_mm)
      fail(l.get("pitch_mm")->source(),
           fmt::format("a lens of {} mm is narrower than a pixel ({} mm); expected 'pitch_mm' >= 'pixel_pitch_mm'",
                       d.pitch_mm, d.pixel_pitch_mm));
    if (const toml::node* s = l.get("slant_deg")) {
      d.slant_deg = as_number(*s, "slant_deg");
      if (d.grid != Grid::lenticular && d.slant_deg != 0)
        fail(s->source(), fmt::format("a slant goes with grid = \"lenticular\", not \"{}\"", grid));
      if (std::fabs(d.slant_deg) > 45)
        fail(s->source(), fmt::format("expected 'slant_deg' from -45 to 45 degrees, found {} degrees", d.slant_deg));
    }
    const bool gap = l.contains("gap_mm"), focal = l.contains("focal_length_mm");
    if (gap == focal)
      fail(l.source(), gap ? "give 'gap_mm' or 'focal_length_mm', not both"
                           : "expected 'gap_mm' (lens plane to panel, mm) or 'focal_length_mm', found neither");
    // A display shows its images at infinity focus: the panel in the focal plane.
    d.gap_mm = gap ? length_mm(l, "gap_mm", "lens plane to panel") : length_mm(l, "focal_length_mm", "the lens focal length");
    d.offset_mm = number(l, "offset_mm", -1e9, 1e9).value_or(0);
    if (const toml::node* v = l.get("view_distance_mm")) {
      if (d.grid != Grid::lenticular) fail(v->source(), "a view distance goes with grid = \"lenticular\"");
      d.view_distance_mm = length_mm(l, "view_distance_mm", "the viewing distance");
    }
  }

  void read_scene(const toml::table& s, DisplayDesc& d) const {
    check_keys(s, "[scene]", {"mode", "units_per_mm", "depth"});
    d.mode = choice(s, "mode", {"orthoscopic", "pseudoscopic"}, "orthoscopic") == "pseudoscopic"
                 ? RecordingMode::pseudoscopic
                 : RecordingMode::orthoscopic;
    if (const toml::node* u = s.get("units_per_mm")) {
      const double v = as_number(*u, "units_per_mm");
      if (!(v > 0)) fail(u->source(), fmt::format("expected a positive 'units_per_mm' (scene units per mm), found {}", v));
      d.units_per_mm = v;
    }
    d.depth = number(s, "depth", -1e30, 1e30).value_or(0);
  }
};

}  // namespace

DisplayDesc parse_display(std::string_view text, const std::string& source) {
  return DisplayParser(text, source).run();
}

DisplayDesc read_display_file(const std::string& path) { return parse_display(read_text_file(path), path); }

}  // namespace holoray
