#include "cli/preview_commands.hpp"

#include <fmt/format.h>

#include "camera/subaperture.hpp"
#include "cli/error_words.hpp"
#include "cli/option_parsing.hpp"
#include "cli/validators.hpp"
#include "display/display_file.hpp"
#include "image/image_io.hpp"
#include "preview/simulate.hpp"
#include "preview/views.hpp"
#include "scene/parse_error.hpp"

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
    if (!is_supported_output(o.output))
      throw std::invalid_argument(fmt::format("-o: unsupported output '{}' (use .png or .exr)", o.output));
    const Encoding encoding = parse_encoding(o.encoding);
    SimulateOptions so;
    so.eye_mm = parse_vec3("--eye", o.eye);
    so.width = o.width;
    so.samples = o.samples;
    const DisplayDesc display = read_display_file(o.display);
    write_image(o.output, simulate_view(as_rgb(read_image(o.input)), display, so), encoding);
    return 0;
  } catch (const ParseError& e) {
    fmt::print(stderr, "{}\n", e.what());
  } catch (const std::exception& e) {
    fmt::print(stderr, "{}\n", error_line(e));
  }
  return 1;
}

int run_views(const ViewsCommandOptions& o) {
  try {
    const bool gif = lower_extension(o.output) == ".gif";
    if (!gif && !is_supported_output(o.output))
      throw std::invalid_argument(fmt::format("-o: unsupported output '{}' (use .png, .exr or .gif)", o.output));
    if (gif && (o.fps < 1 || o.fps > 100)) throw std::invalid_argument(fmt::format("--fps: must be 1 to 100, got {}", o.fps));
    const Encoding encoding = parse_encoding(o.encoding);
    const Grid grid = parse_grid(o.grid);
    const ImageBuffer eia = as_rgb(read_image(o.input));
    const LensArray cam(eia_layout(eia.width, eia.height, grid, o.pixels_per_lens));
    if (gif) write_animation(o.output, view_sweep(eia, cam), o.fps, encoding);
    else write_image(o.output, view_grid(eia, cam), encoding);
    return 0;
  } catch (const std::exception& e) {
    fmt::print(stderr, "{}\n", error_line(e));
  }
  return 1;
}

}  // namespace holoray::cli
