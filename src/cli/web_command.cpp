#include "cli/web_command.hpp"

#include <fmt/format.h>

#include <cstdio>
#include <filesystem>

#include "cli/error_words.hpp"
#include "cli/option_parsing.hpp"
#include "cli/validators.hpp"
#include "holoray/image.hpp"
#include "holoray/web.hpp"

namespace holoray::cli {

CLI::App* add_web_command(CLI::App& app, WebCommandOptions& o) {
  CLI::App* cmd = app.add_subcommand("web", "Write a light-field page of an EIA or a quilt that any browser opens, or serve one");
  CLI::Option* input = cmd->add_option("result", o.inputs,
                                       "EIA or quilt image (PNG, EXR, JPEG, ...), a quilt by --quilt or its _qsCxR name; "
                                       "several: an animation's frames, in order")
                           ->check(CLI::ExistingFile);
  CLI::Option* output = cmd->add_option("-o,--output", o.output, "Folder to write the page into (made if missing)");
  cmd->add_option("--grid", o.grid, "Lens grid of the EIA: square, hex or lenticular")->capture_default_str();
  cmd->add_option("--pixels-per-lens", o.pixels_per_lens, "Pixels across one lens of the EIA (P)")
      ->check(CLI::Range(1, 4096))
      ->capture_default_str();
  cmd->add_option("--quilt", o.quilt, "The result is a quilt of CxR views (default: from a _qsCxR file name)");
  cmd->add_option("--looking-glass", o.looking_glass,
                  "A Looking Glass's calibration (visual.json), for a quilt: the page's Looking Glass window shows the "
                  "device's native image")
      ->check(CLI::ExistingFile);
  cmd->add_option("--name", o.name, "Name shown under the view (default: the first file's stem)");
  cmd->add_option("--fps", o.fps, "An animation's frames per second")->check(CLI::Range(0.1, 1000.0))->capture_default_str();
  cmd->add_option("--encoding", o.encoding,
                  "How the image's values become the page's sRGB codes: auto (srgb for EXR and HDR, whose values are "
                  "linear light; else as they are), linear or srgb")
      ->check(CLI::IsMember({"auto", "linear", "srgb"}))
      ->capture_default_str();
  CLI::Option* serve = cmd->add_option("--serve", o.serve, "Serve the page in this folder over HTTP until stopped")
                           ->check(CLI::ExistingDirectory);
  cmd->add_option("--port", o.port, "Port to serve on (0: a free one)")->check(CLI::Range(0, 65535))->capture_default_str();
  cmd->add_option("--host", o.host, "Address to serve on")->capture_default_str();
  cmd->add_flag("-q,--quiet", o.quiet, "Print nothing but errors (and the address served)");
  serve->excludes(input)->excludes(output);
  input->needs(output);
  output->needs(input);
  lay_out_help(*cmd, {},
               {"holoray render examples/primitives.nff --lenses 64x64 --pixels-per-lens 9 -o eia.png",
                "holoray web eia.png --pixels-per-lens 9 -o page", "holoray web --serve page"},
               "docs/guide/web.md");
  return cmd;
}

namespace {

int serve(const WebCommandOptions& o) {
  api::serve_folder(o.serve, o.host, o.port, [&](const std::string& url) {
    fmt::print("serving    {} at {} (Ctrl-C stops)\n", o.serve, url);
    std::fflush(stdout);
  });
  return 0;
}

}  // namespace

int run_web(const WebCommandOptions& o) {
  try {
    if (!o.serve.empty()) return serve(o);
    if (o.inputs.empty()) {
      fmt::print(stderr, "holoray: error: web: give the result to show (an EIA or a quilt) and -o DIR, or --serve DIR\n");
      return 2;
    }
    const std::string& first = o.inputs.front();
    const std::string ext = api::lower_extension(first);
    const api::Encoding encoding = o.encoding == "auto" ? (ext == ".exr" || ext == ".hdr" ? api::Encoding::srgb : api::Encoding::linear)
                                                        : parse_encoding(o.encoding);
    const std::string name = o.name.empty() ? std::filesystem::path(first).stem().string() : o.name;
    const bool quilt = !o.quilt.empty() || names_quilt(first);
    int columns = 0, rows = 0;
    if (quilt) parse_quilt_layout(o.quilt, first, columns, rows);
    if (!quilt && !o.looking_glass.empty())
      throw std::invalid_argument("--looking-glass: a Looking Glass shows a quilt (--quilt CxR, or a _qsCxR file name), not an EIA");
    const api::EiaLayout layout{parse_grid(o.grid), o.pixels_per_lens};
    // One frame held at a time, however long the animation.
    api::WebAnimation page(o.output, name, encoding, o.fps);
    int width = 0, height = 0;
    for (const std::string& input : o.inputs) {
      const api::Image image = api::read_image(input);
      width = image.width(), height = image.height();
      if (quilt) page.add_quilt(image, columns, rows, o.looking_glass);
      else page.add_eia(image, layout);
    }
    page.finish();
    if (!o.quiet) {
      const std::string frames = o.inputs.size() > 1 ? fmt::format("; {} frames at {} fps", o.inputs.size(), o.fps) : "";
      if (quilt)
        fmt::print("page       {}/index.html: a {}x{} quilt of {}x{} views{}\n", o.output, columns, rows, width / columns,
                   height / rows, frames);
      else
        fmt::print("page       {}/index.html: a {} EIA of {}x{} px, {} pixels per lens{}\n", o.output, o.grid, width, height,
                   o.pixels_per_lens, frames);
    }
    if (!o.quiet) fmt::print("open it    holoray web --serve {}   (or any static server)\n", o.output);
    return 0;
  } catch (const std::exception& e) {
    fmt::print(stderr, "{}\n", error_line(e));
  }
  return 1;
}

}  // namespace holoray::cli
