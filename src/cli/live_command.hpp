// holoray/cli: `holoray live SCENE [camera options]`: the scene in a window,
// rendered on the GPU path as fast as the device renders it, moved with the
// mouse and keys (docs/guide/live.md).
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "cli/render_command.hpp"

namespace holoray::cli {

/// Options of `holoray live` as typed: render's camera and lens array
/// options (in `camera`), and the window's own.
struct LiveCommandOptions {
  RenderCommandOptions camera;
  std::string monitor;      ///< --monitor N|NAME
  bool fullscreen = false;  ///< --fullscreen
  bool windowed = false;    ///< --windowed
  int exit_after = 0;       ///< --exit-after N frames
  bool offscreen = false;   ///< --offscreen (no window)
  std::string screenshot;   ///< --screenshot FILE
  std::string events;       ///< --events FILE
  std::string record;       ///< --record DIR
  std::string shot;         ///< --shot FILE (instead of a scene)
  bool play = false;        ///< --play
  bool simulate = false;    ///< --simulate
  int max_spp = 256;        ///< --max-spp (the path integrator's refinement)
};

CLI::App* add_live_command(CLI::App& app, LiveCommandOptions& o);

/// Runs it: 0 when the window was closed (or --exit-after reached), 1 with
/// one message on stderr for an error, 128 + N after signal N.
int run_live(const LiveCommandOptions& o);

}  // namespace holoray::cli
