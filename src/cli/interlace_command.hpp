// holoray/cli: `holoray interlace QUILT --looking-glass CAL.json -o PANEL`:
// a Looking Glass's native panel image made from a quilt of views.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

namespace holoray::cli {

struct InterlaceCommandOptions {
  std::string input, output, calibration, quilt, encoding = "linear";
  bool quiet = false;
};

CLI::App* add_interlace_command(CLI::App& app, InterlaceCommandOptions& opts);
/// Returns the exit status (0 success, 1 failure with one message on stderr).
int run_interlace(const InterlaceCommandOptions& opts);

}  // namespace holoray::cli
