#include "cli/subaperture_command.hpp"

#include <fmt/format.h>

#include <cmath>

#include "cli/error_words.hpp"
#include "cli/option_parsing.hpp"
#include "cli/validators.hpp"
#include "holoray/image.hpp"
#include "holoray/preview.hpp"

namespace holoray::cli {

CLI::App* add_subaperture_command(CLI::App& app, SubapertureCommandOptions& o) {
  CLI::App* cmd = app.add_subcommand("subaperture", "Extract a sub-aperture view (pixel u,v of every elemental image)");
  cmd->add_option("eia", o.input, "Elemental image array (PNG, EXR, JPEG, PPM, Targa, BMP)")->required();
  cmd->add_option("-o,--output", o.output, "Output image (.png or .exr)")->required();
  cmd->add_option("--grid", o.grid, "Lens grid of the EIA: square, hex or lenticular")->capture_default_str();
  cmd->add_option("--pixels-per-lens", o.pixels_per_lens, "Pixels across one lens (P)")->capture_default_str();
  cmd->add_option("--u", o.u, "Column within the elemental image, 0..P-1 (default P/2)");
  cmd->add_option("--v", o.v, "Row within the elemental image, 0..P-1 (default P/2)");
  cmd->add_option("--encoding", o.encoding, "PNG encoding of the output: linear or srgb")->capture_default_str();
  lay_out_help(*cmd, {},
               {"holoray subaperture eia.png --pixels-per-lens 8 -o centre.png",
                "holoray subaperture eia.png --pixels-per-lens 8 --u 0 --v 4 -o leftmost.png"},
               "docs/guide/stills.md");
  return cmd;
}

int run_subaperture(const SubapertureCommandOptions& o) {
  try {
    if (!api::is_image_output(o.output))
      throw std::invalid_argument(fmt::format("-o: unsupported output '{}' (use .png or .exr)", o.output));
    const api::EiaLayout layout{parse_grid(o.grid), o.pixels_per_lens};
    const api::Encoding encoding = parse_encoding(o.encoding);
    const api::Image eia = api::read_image(o.input);
    api::write_image(o.output, api::subaperture_view(eia, layout, o.u, o.v), encoding);
    return 0;
  } catch (const std::exception& e) {
    fmt::print(stderr, "{}\n", error_line(e));
    return 1;
  }
}

}  // namespace holoray::cli
