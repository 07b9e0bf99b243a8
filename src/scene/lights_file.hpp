// holoray/scene: a lights file (docs/lights.md, "Lights file"): lights in
// Blender's words and units, in the scene's frame, read into plain structs
// in holoray's units. What the Blender add-on writes for the lights its
// glTF export cannot carry (area lights, light radii, sun angles), and what
// a user writes by hand to light any scene.
#pragma once

#include <string>
#include <vector>

#include "scene/scene_desc.hpp"

namespace holoray {

struct LightsFile {
  std::vector<Light> lights;            ///< point, spot, sun
  std::vector<AreaLightDesc> area_lights;
};

/// Parses a lights file's `text` (TOML; `source` names it in messages).
/// Conversions, as Cycles renders Blender's lights (measured against Blender
/// 3.4 and 4.3): a point or spot light of power P W and colour c has
/// intensity c P / (4 pi) W/sr, a sun of strength S gives irradiance S, an
/// area light of power P and area A has radiance c P / (pi A), one-sided
/// (Cycles 4's; Cycles 3 took c P / (4 A)). Throws
/// ParseError at file:line:col for a malformed file, an unknown key, a
/// value out of range.
LightsFile parse_lights_file(std::string_view text, const std::string& source);
/// read_text_file(path) parsed; std::runtime_error when it cannot be read.
LightsFile read_lights_file(const std::string& path);

}  // namespace holoray
