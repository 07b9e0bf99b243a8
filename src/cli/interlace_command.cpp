#include "cli/interlace_command.hpp"

#include <fmt/format.h>

#include "cli/error_words.hpp"
#include "cli/option_parsing.hpp"
#include "cli/validators.hpp"
#include "holoray/image.hpp"
#include "holoray/preview.hpp"
#include "holoray/stopwatch.hpp"

namespace holoray::cli {

CLI::App* add_interlace_command(CLI::App& app, InterlaceCommandOptions& o) {
  CLI::App* cmd = app.add_subcommand("interlace", "A Looking Glass's native panel image from a quilt and the device's calibration");
  cmd->add_option("quilt-image", o.input, "Quilt image (views tiled as Looking Glass tools do: view 0 bottom left), e.g. NAME_qs8x6a0.75.png")->required();
  cmd->add_option("--looking-glass", o.calibration, "The device's calibration file (visual.json)")->required();
  cmd->add_option("-o,--output", o.output, "Native panel image (.png or .exr)")->required();
  cmd->add_option("--quilt", o.quilt, "Columns x rows of the quilt (default: read from the file's _qsCxR name)");
  cmd->add_option("--encoding", o.encoding, "PNG encoding: linear or srgb (the quilt's values are passed on as they are)")->capture_default_str();
  cmd->add_flag("-q,--quiet", o.quiet, "Print nothing but errors");
  lay_out_help(*cmd, {},
               {"holoray render examples/primitives.nff --quilt 8x6 -o quilt.png",
                "holoray interlace quilt_qs8x6a0.75.png --looking-glass visual.json -o native.png"},
               "docs/guide/displays.md");
  return cmd;
}

int run_interlace(const InterlaceCommandOptions& o) {
  try {
    if (!api::is_image_output(o.output))
      throw std::invalid_argument(fmt::format("-o: unsupported output '{}' (use .png or .exr)", o.output));
    const api::Encoding encoding = parse_encoding(o.encoding);
    api::QuiltLayout q;
    parse_quilt_layout(o.quilt, o.input, q.columns, q.rows);
    const api::Image quilt = api::read_image(o.input);
    const auto start = Clock::now();
    const api::Image panel = api::interlace_quilt(quilt, q.columns, q.rows, o.calibration);
    api::write_image(o.output, panel, encoding);
    if (!o.quiet) {
      fmt::print("panel      {}x{} px, Looking Glass ({}), from a {}x{} quilt of {}x{} views\n", panel.width(),
                 panel.height(), o.calibration, q.columns, q.rows, quilt.width() / q.columns, quilt.height() / q.rows);
      fmt::print("wrote      {} ({:.3f} s)\n", o.output, seconds_since(start));
    }
    return 0;
  } catch (const std::exception& e) {
    fmt::print(stderr, "{}\n", error_line(e));
  }
  return 1;
}

}  // namespace holoray::cli
