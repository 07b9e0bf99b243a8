// holoray/cli: `holoray subaperture EIA -o VIEW`: one sub-aperture image of an EIA.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

namespace holoray::cli {

struct SubapertureCommandOptions {
  std::string input, output, grid = "square", encoding = "linear";
  int pixels_per_lens = 8, u = -1, v = -1;  // -1: the centre pixel P/2
};

CLI::App* add_subaperture_command(CLI::App& app, SubapertureCommandOptions& opts);
/// Returns the exit status (0 success, 1 failure with one message on stderr).
int run_subaperture(const SubapertureCommandOptions& opts);

}  // namespace holoray::cli
