#include "cli/light_options.hpp"

#include "cli/option_parsing.hpp"
#include "cli/validators.hpp"

namespace holoray::cli {

void add_light_options(CLI::App& cmd, LightCommandOptions& o, bool lights_file) {
  cmd.add_option("--integrator", o.integrator,
                 "How light is computed: whitted (the paper's: point lights, hard shadows, mirror and refraction rays) or "
                 "path (path tracing: soft light from an environment and emissive surfaces, light between surfaces; "
                 "noise falls as 1/sqrt(--spp))")
      ->check(one_of({"whitted", "path"}))
      ->capture_default_str();
  if (lights_file)
    cmd.add_option("--lights", o.lights,
                   "A lights file (TOML): point, spot, sun and area lights in Blender's units, added to the scene's "
                   "(docs/lights.md); area lights, radii and sun angles light --integrator path")
        ->check(CLI::ExistingFile);
  cmd.add_option("--environment", o.environment,
                 "With --integrator path: the light around the scene, an equirectangular .hdr or .exr image, mapped as "
                 "Blender maps an Environment Texture (default: the scene's background colour)")
      ->check(CLI::ExistingFile);
  cmd.add_option("--environment-colour", o.environment_colour, "With --integrator path: a constant environment R,G,B (linear)")
      ->check(parsed_by([](const std::string& t) { parse_vec3("--environment-colour", t); }, "R,G,B"));
  cmd.add_option("--environment-strength", o.environment_strength, "With --environment or --environment-colour: its multiplier")
      ->check(in_range(0))
      ->capture_default_str();
  cmd.add_option("--environment-rotation", o.environment_rotation,
                 "With --environment: degrees about the scene's up axis (a Blender Mapping node's Z rotation)")
      ->capture_default_str();
  cmd.add_flag("--blender-principled", o.blender_principled,
               "With --integrator path: glTF materials as Blender 3.x's Principled BSDF shades them (Burley's diffuse, "
               "whole under the specular layer), for scenes exported from Blender; default: glTF's own BRDF");
}

std::vector<std::string> light_option_names(bool lights_file) {
  std::vector<std::string> names{"--integrator"};
  if (lights_file) names.push_back("--lights");
  for (const char* n : {"--environment", "--environment-colour", "--environment-strength", "--environment-rotation",
                        "--blender-principled"})
    names.push_back(n);
  return names;
}

LightChoice light_choice(const LightCommandOptions& o) {
  LightChoice c;
  c.integrator = o.integrator == "path" ? api::Integrator::path : api::Integrator::whitted;
  c.environment.file = o.environment;
  if (!o.environment_colour.empty()) c.environment.colour = parse_vec3("--environment-colour", o.environment_colour);
  c.environment.strength = o.environment_strength;
  c.environment.rotation_deg = o.environment_rotation;
  c.blender_principled = o.blender_principled;
  return c;
}

}  // namespace holoray::cli
