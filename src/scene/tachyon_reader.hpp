// holoray/scene: reader for Tachyon's scene language (`.dat`, John E. Stone's
// Tachyon ray tracer, the renderer the paper adapted; its Room, Small-balls
// and Teapot are in this format). docs/tachyon-notes.md has the grammar as
// holoray reads it, what each construct becomes and what is not supported.
//
// Keywords are case-insensitive, texture names are not (as in Tachyon). The
// file is parsed into a SceneDesc whose materials all follow Tachyon's
// shading (ShadingModel::tachyon) and whose viewpoint is the Tachyon camera
// (mirrored: Tachyon's screen is left-handed). Image maps named by `texfunc 9`
// are read here (image/image_io.hpp: PPM, Targa, PNG, JPEG, ...), relative to the scene file's folder
// (then the working folder, where Tachyon looks).
//
// A construct holoray does not support yet (volumes, landscapes, inline
// images, clip groups, the noise textures, other projections, outlines, ...)
// is refused with `file:line:col` naming it, never skipped. Included files,
// polygon files and image maps must be regular files.
#pragma once

#include <string>
#include <string_view>

#include "scene/scene_desc.hpp"

namespace holoray {

/// Guards against absurd files, checked before anything is stored.
struct TachyonLimits {
  long max_objects = 20'000'000;  ///< as NffLimits::max_objects
  long max_lights = 10'000;       ///< as NffLimits::max_lights
  long max_polycylinder_points = 1'000'000;
  int max_include_depth = 16;     ///< nested `include`s (a file including itself stops here)
  long max_image_pixels = 1L << 28;  ///< per image map (768 MiB of RGB)
  long max_warnings_kept = 100;
};

/// Parses Tachyon text. `source` names the file in messages and locates
/// `include` files and image maps (relative to its folder). Throws ParseError
/// ("file:line:col: error: ...") on malformed or unsupported input, and for
/// an image map or include file that cannot be read.
SceneDesc parse_tachyon(std::string_view text, const std::string& source, const TachyonLimits& limits = {});

/// Reads and parses a `.dat` file. Throws std::runtime_error when it cannot
/// be read, ParseError when it is malformed.
SceneDesc read_tachyon_file(const std::string& path, const TachyonLimits& limits = {});

}  // namespace holoray
