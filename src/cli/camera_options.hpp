// holoray/cli: the camera options `render` and `animate` share (--camera,
// --resolution, --display, --looking-glass, --views, and how the scene file
// is read: --camera-name, --texture-path), declared once with their CLI11
// checks and the rules between them.
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

#include "holoray/camera.hpp"

namespace holoray::cli {

/// The shared camera options as typed.
struct CameraOptions {
  std::string camera = "integral";  ///< --camera integral|pinhole
  std::string resolution;           ///< --resolution WxH (pinhole; render's --quilt: one view)
  std::string display;              ///< --display FILE (display-files.md)
  std::string looking_glass;        ///< --looking-glass CAL.json
  int looking_glass_views = api::LookingGlass{}.views;  ///< --views N
};

/// Registers the options on `cmd`; `what` words the help for a still
/// ("the image") or a shot ("each frame"). Returns --display and
/// --looking-glass, for the command's own `excludes`.
std::array<CLI::Option*, 2> add_camera_options(CLI::App& cmd, CameraOptions& o, const std::string& what);

/// The rules between the camera options that CLI11 cannot say, checked
/// before any file is read. `quilt`: render's --quilt CxR was given (it
/// takes --resolution as one view's size); `still`: render's (else
/// animate's) wording. Throws std::invalid_argument: a panel or a quilt goes
/// without `--camera pinhole`; --resolution goes with the pinhole camera or
/// a quilt.
void camera_desc_rules(const CameraOptions& o, bool quilt, bool still);

/// --camera-name NAME (the mesh file's camera the viewpoint is) and
/// --texture-path DIR (repeatable: folders a texture the file names is
/// looked for in, by its base name), for api::LoadOptions.
void add_scene_read_options(CLI::App& cmd, std::string& camera_name, std::vector<std::string>& texture_paths);

/// --origin, --normal and --up as an explicit placement (CLI11 makes them
/// go together); nullopt when none is given.
std::optional<api::Placement> placement_of(const std::string& origin, const std::string& normal, const std::string& up);

}  // namespace holoray::cli
