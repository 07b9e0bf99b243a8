// holoray/cli: `holoray web RESULT... -o DIR`: a light-field page of an EIA
// or a quilt (or an animation's frames of either) that any browser opens
// (docs/guide/web.md); `holoray web --serve DIR` serves it on this machine.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace holoray::cli {

struct WebCommandOptions {
  std::vector<std::string> inputs;  ///< one still, or an animation's frames in order
  std::string output, grid = "square", quilt, name, encoding = "auto", looking_glass, serve, host = "127.0.0.1";
  int pixels_per_lens = 8, port = 8000;
  double fps = 24;
  bool quiet = false;
};

CLI::App* add_web_command(CLI::App& app, WebCommandOptions& opts);
/// Returns the exit status (0 success, 1 failure with one message on
/// stderr). With --serve it returns only on failure (the server runs until
/// the process is stopped).
int run_web(const WebCommandOptions& opts);

}  // namespace holoray::cli
