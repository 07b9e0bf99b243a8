// holoray/cli: `holoray render SCENE -o OUT`: one still EIA.
#pragma once

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "cli/light_options.hpp"
#include "cli/cache_options.hpp"
#include "cli/camera_options.hpp"
#include "cluster/mpi_world.hpp"

namespace holoray::cli {

/// Options of `holoray render` as typed: CLI11 checks each value
/// (add_render_command), run_render the rules between them that CLI11
/// cannot say.
struct RenderCommandOptions {
  std::string scene, output;
  std::string grid = "square", mode = "orthoscopic", lenses = "64x64", aovs, encoding = "auto", style = "auto", device = "cpu";
  int pixels_per_lens = 8, rows = 0, spp = 1, threads = 0, max_depth = 0;  // max_depth 0: the scene's, else 5
  int64_t seed = 0;  // 0 to 2^32 - 1 (api::RenderOptions::seed)
  LightCommandOptions light;  ///< --integrator, --lights, --environment...
  double fov_lens = NAN, gap = NAN, pitch = NAN, view_distance = INFINITY;  // NaN: not given
  std::string origin, normal, up;
  CameraOptions view;                 ///< --camera, --resolution, --display, --looking-glass, --views
  std::string sample_at = "centre";   ///< --sample-at (pinhole)
  std::string shift;                  ///< --shift X,Y (pinhole lens shift)
  std::string quilt;                  ///< --quilt CxR: a Looking Glass quilt of C*R views
  double view_cone = 40;              ///< --view-cone DEG
  double focus_distance = NAN;        ///< --focus-distance D (arrays, displays, quilt, Looking Glass); NaN: not given
  std::string camera_name;            ///< --camera-name NAME: the mesh file's camera
  std::vector<std::string> texture_paths;  ///< --texture-path DIR, repeatable
  int quilt_view = -1;                ///< --quilt-view K: only view K, as a plain image
  int share_views = 0;                ///< --share-views S: a quilt's views share path samples with S on each side
  CacheCommandOptions cache;
  bool quiet = false;
  bool progress_lines = false;  ///< --progress: `progress F` lines on stderr
  std::string exr_compression = "zip";  ///< --exr-compression
};

/// The lens array's options (--grid, --lenses, --pixels-per-lens, --rows,
/// --fov-lens, --gap, --pitch, --mode, --view-distance) on `cmd`, checked
/// by CLI11; returned for the command's own `excludes`.
std::vector<CLI::Option*> add_lens_array_options(CLI::App& cmd, RenderCommandOptions& o);
/// --focus-distance D on `cmd`.
void add_focus_distance_option(CLI::App& cmd, RenderCommandOptions& o);
/// The camera the options name, with the rules between options that CLI11
/// cannot say (each value it checked already). Throws std::invalid_argument
/// naming the option.
api::Camera camera_of(const RenderCommandOptions& o);

/// Registers the subcommand and its options on `app`.
CLI::App* add_render_command(CLI::App& app, RenderCommandOptions& opts);

/// Runs it; returns the process exit status (0 success, 1 failure). Errors
/// go to stderr as one message; nothing is written on failure. Under mpirun
/// (`world` distributed) the ranks split the image in bands of rows.
int run_render(const RenderCommandOptions& opts, const cluster::World& world);

}  // namespace holoray::cli
