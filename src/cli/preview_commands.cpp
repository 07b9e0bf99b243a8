#include "cli/preview_commands.hpp"

#include <fmt/format.h>

#include "cli/error_words.hpp"
#include "cli/option_parsing.hpp"
#include "cli/validators.hpp"
#include "holoray/image.hpp"
#include "holoray/preview.hpp"

namespace holoray::cli {

CLI::App* add_simulate_command(CLI::App& app, SimulateCommandOptions& o) {
  CLI::App* cmd = app.add_subcommand("simulate", "What an eye sees on a display: a panel image seen through its lens sheet from one eye position");
  cmd->add_option("panel", o.input, "The display's native image (render --display), or an EIA of a whole-pixel display")->required();
  cmd->add_option("--display", o.display, "The display file the panel image was made for (docs/display-files.md)")->required();
  cmd->add_option("--eye", o.eye, "Eye position X,Y,Z in millimetres, display frame: origin at the panel centre on the lens plane, x right, y up, z toward the viewer")->capture_default_str();
  cmd->add_option("-o,--output", o.output, "Output image (.png or .exr)")->required();
  cmd->add_option("--width", o.width, "Output width in pixels (the height keeps the panel's aspect)")->capture_default_str();
  cmd->add_option("--samples", o.samples, "Samples per output pixel along each axis, averaged as the eye integrates")->capture_default_str();
  cmd->add_option("--encoding", o.encoding, "PNG encoding: linear or srgb")->capture_default_str();
  lay_out_help(*cmd, {},
               {"holoray simulate panel.png --display examples/displays/lenticular_4k.toml --eye -40,0,600 -o left.png",
                "holoray simulate panel.png --display examples/displays/lenticular_4k.toml --eye 40,0,600 -o right.png"},
               "docs/guide/displays.md");
  return cmd;
}

CLI::App* add_views_command(CLI::App& app, ViewsCommandOptions& o) {
  CLI::App* cmd = app.add_subcommand("views", "An EIA's sub-aperture views: all as one grid (.png, .exr), or a parallax sweep across the horizontal ones (.gif)");
  cmd->add_option("eia", o.input, "Elemental image array (PNG, EXR, JPEG, PPM, Targa, BMP)")->required();
  cmd->add_option("-o,--output", o.output, "views.png or views.exr (grid: view (u, v) at tile column u, row v), or views.gif (sweep)")->required();
  cmd->add_option("--grid", o.grid, "Lens grid of the EIA: square, hex or lenticular")->capture_default_str();
  cmd->add_option("--pixels-per-lens", o.pixels_per_lens, "Pixels across one lens (P)")->capture_default_str();
  cmd->add_option("--fps", o.fps, "With .gif: frames per second")->capture_default_str();
  cmd->add_option("--encoding", o.encoding, "8-bit encoding: linear or srgb")->capture_default_str();
  lay_out_help(*cmd, {},
               {"holoray views eia.png --pixels-per-lens 8 -o views.gif",
                "holoray views eia.png --pixels-per-lens 8 -o views.png"},
               "docs/guide/displays.md");
  return cmd;
}

int run_simulate(const SimulateCommandOptions& o) {
  try {
    if (!api::is_image_output(o.output))
      throw std::invalid_argument(fmt::format("-o: unsupported output '{}' (use .png or .exr)", o.output));
    const api::Encoding encoding = parse_encoding(o.encoding);
    api::SimulateOptions so;
    so.eye_mm = parse_vec3("--eye", o.eye);
    so.width = o.width;
    so.samples = o.samples;
    const api::Image panel = api::read_image(o.input);
    api::write_image(o.output, api::simulate_view(panel, o.display, so), encoding);
    return 0;
  } catch (const std::exception& e) {
    fmt::print(stderr, "{}\n", error_report(e));
  }
  return 1;
}

int run_views(const ViewsCommandOptions& o) {
  try {
    const bool gif = api::lower_extension(o.output) == ".gif";
    if (!gif && !api::is_image_output(o.output))
      throw std::invalid_argument(fmt::format("-o: unsupported output '{}' (use .png, .exr or .gif)", o.output));
    if (gif && (o.fps < 1 || o.fps > 100)) throw std::invalid_argument(fmt::format("--fps: must be 1 to 100, got {}", o.fps));
    const api::Encoding encoding = parse_encoding(o.encoding);
    const api::EiaLayout layout{parse_grid(o.grid), o.pixels_per_lens};
    const api::Image eia = api::read_image(o.input);
    if (gif) api::write_animation(o.output, api::view_sweep(eia, layout), o.fps, encoding);
    else api::write_image(o.output, api::view_grid(eia, layout), encoding);
    return 0;
  } catch (const std::exception& e) {
    fmt::print(stderr, "{}\n", error_line(e));
  }
  return 1;
}

}  // namespace holoray::cli
