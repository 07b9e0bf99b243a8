// holoray/cli: looking at an output without a display (issue 14, item 4).
//   holoray simulate PANEL --display FILE --eye X,Y,Z -o view.png
//   holoray views EIA -o views.png|views.gif [--grid G --pixels-per-lens P]
#pragma once

#include <CLI/CLI.hpp>
#include <string>

namespace holoray::cli {

struct SimulateCommandOptions {
  std::string input, output, display, eye = "0,0,600", encoding = "linear";
  int width = 800, samples = 3;
};

struct ViewsCommandOptions {
  std::string input, output, grid = "square", encoding = "linear";
  int pixels_per_lens = 8, fps = 12;
};

CLI::App* add_simulate_command(CLI::App& app, SimulateCommandOptions& opts);
CLI::App* add_views_command(CLI::App& app, ViewsCommandOptions& opts);
/// Each returns the exit status (0 success, 1 failure with one message on stderr).
int run_simulate(const SimulateCommandOptions& opts);
int run_views(const ViewsCommandOptions& opts);

}  // namespace holoray::cli
