// holoray/cli: the light options shared by `render` and `animate` (issue 70;
// api::Integrator, api::Environment): --integrator, --environment,
// --environment-colour, --environment-strength, --environment-rotation,
// --blender-principled, and render's --lights.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "holoray/render.hpp"

namespace holoray::cli {

struct LightCommandOptions {
  std::string integrator = "whitted", environment, environment_colour, lights;
  double environment_strength = 1, environment_rotation = 0;
  bool blender_principled = false;
};

/// Registers the options on `cmd`; --lights only with `lights_file` (a
/// still's scene takes a lights file; a shot's scenes are its own).
void add_light_options(CLI::App& cmd, LightCommandOptions& o, bool lights_file);

/// The option names, for the help's "Light" group.
std::vector<std::string> light_option_names(bool lights_file);

/// The integrator, environment and material model as the API takes them.
/// Throws std::invalid_argument naming --environment-colour when malformed.
struct LightChoice {
  api::Integrator integrator = api::Integrator::whitted;
  api::Environment environment;
  bool blender_principled = false;
};
LightChoice light_choice(const LightCommandOptions& o);

}  // namespace holoray::cli
