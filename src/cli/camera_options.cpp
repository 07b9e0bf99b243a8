#include "cli/camera_options.hpp"

#include <stdexcept>

#include "cli/option_parsing.hpp"
#include "cli/validators.hpp"

namespace holoray::cli {

std::array<CLI::Option*, 2> add_camera_options(CLI::App& cmd, CameraOptions& o, const std::string& what) {
  cmd.add_option("--camera", o.camera,
                 "integral (the EIA) or pinhole (" + what +
                     " as the viewpoint's ordinary view: previews, comparisons with other ray tracers)")
      ->check(one_of({"integral", "pinhole"}))
      ->capture_default_str();
  cmd.add_option("--resolution", o.resolution,
                 "With --camera pinhole: the view's size WxH (default: the scene's resolution, else 512x512)")
      ->check(parsed_by([](const std::string& t) { int w, h; parse_resolution(t, w, h); }, "WxH"));
  CLI::Option* display =
      cmd.add_option("--display", o.display,
                     "Display file (TOML, docs/display-files.md): " + what +
                         " as that display's native panel image, each subpixel along its own line through its own lens")
          ->check(existing_file());
  CLI::Option* glass =
      cmd.add_option("--looking-glass", o.looking_glass,
                     "A Looking Glass's calibration file (visual.json): " + what +
                         " as its native panel image, each subpixel along the view its lenticule gives it")
          ->check(existing_file())
          ->excludes(display);
  cmd.add_option("--views", o.looking_glass_views,
                 "With --looking-glass: the views N of the quilt the native image is the continuous version of")
      ->check(in_range(1, 4096))
      ->needs(glass)
      ->capture_default_str();
  return {display, glass};
}

void camera_desc_rules(const CameraOptions& o, bool quilt, bool still) {
  const bool pinhole = o.camera == "pinhole";
  if (pinhole && !o.looking_glass.empty())
    throw std::invalid_argument("--looking-glass: renders the panel's own views; it goes without --camera pinhole");
  if (pinhole && !o.display.empty())
    throw std::invalid_argument("--display: renders the panel through its lenses; it goes without --camera pinhole");
  if (pinhole && quilt) throw std::invalid_argument("--quilt: renders its own views; it goes without --camera pinhole");
  if (!o.resolution.empty()) {
    if (!o.looking_glass.empty()) throw std::invalid_argument("--resolution: the calibration sets a Looking Glass panel's size");
    if (!pinhole && !quilt)
      throw std::invalid_argument(
          still ? "--resolution: goes with --camera pinhole or --quilt (an EIA's size is --lenses x --pixels-per-lens)"
                : "--resolution: goes with --camera pinhole (an EIA's size is the shot's [array])");
  }
}

std::optional<api::Placement> placement_of(const std::string& origin, const std::string& normal, const std::string& up) {
  if (origin.empty() && normal.empty() && up.empty()) return std::nullopt;
  if (origin.empty() || normal.empty() || up.empty())
    throw std::invalid_argument("--origin, --normal and --up: give all three, or none");
  return api::Placement{parse_vec3("--origin", origin), parse_vec3("--normal", normal), parse_vec3("--up", up)};
}

void add_scene_read_options(CLI::App& cmd, std::string& camera_name, std::vector<std::string>& texture_paths) {
  cmd.add_option("--camera-name", camera_name,
                 "The mesh file's camera to look through, by its name in the file (default: the file's first camera)");
  cmd.add_option("--texture-path", texture_paths,
                 "A folder where textures the scene file names but that do not exist are looked for by base name, "
                 "after the file's own folder; repeat for more, searched in order")
      ->check(CLI::ExistingDirectory)
      ->allow_extra_args(false);
}

}  // namespace holoray::cli
