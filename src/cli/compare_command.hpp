// holoray/cli: `holoray compare A B`: MSE, RMSE and PSNR per channel and overall.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

namespace holoray::cli {

struct CompareCommandOptions {
  std::string a, b;
};

CLI::App* add_compare_command(CLI::App& app, CompareCommandOptions& opts);
int run_compare(const CompareCommandOptions& opts);

}  // namespace holoray::cli
