// holoray/cli: `holoray animate SHOT -o DIR`: an animated shot as numbered
// frames, fully ray traced or with temporal reprojection between keyframes.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "cli/light_options.hpp"
#include "cli/cache_options.hpp"
#include "cli/camera_options.hpp"
#include "cluster/mpi_world.hpp"

namespace holoray::cli {

struct AnimateCommandOptions {
  std::string shot, output, method, fill = "trace", reuse, reach = "near";  // method "": reverse (integral), full (pinhole)
  CameraOptions view;                   ///< --camera, --resolution, --display, --looking-glass, --views
  std::string camera_name;              ///< --camera-name NAME (replaces the shot's camera_name)
  std::vector<std::string> texture_paths;  ///< --texture-path DIR, after the shot's texture_path
  std::string format = "png", encoding = "auto", report;
  std::string frames;                   ///< --frames A:B (inclusive) or N: only those frames
  std::string video;                    ///< --video PATH (.mkv FFV1 lossless, .mp4 H.264)
  int crf = -1;                         ///< --crf N (H.264; -1: 18)
  std::string keyframe_interval = "8";  ///< K, or "auto" (keyframe_schedule.hpp)
  double keyframe_motion = 4;           ///< auto: most pixels a point image moves from its keyframe
  int max_keyframe_interval = 32;       ///< auto: longest run of frames between keyframes
  int threads = 0;
  int64_t seed = 0;            ///< --seed: 0 to 2^32 - 1 (api::AnimateOptions::seed)
  bool animated_seed = false;  ///< --animated-seed
  std::string device = "cpu";  ///< --device
  double rebuild_above = 5;  // percent of holes
  bool resume = false, no_leak_check = false, quiet = false, verbose = false;
  CacheCommandOptions cache;
  LightCommandOptions light;           ///< --integrator, --environment... (no --lights: a shot's scenes are its own)
};

CLI::App* add_animate_command(CLI::App& app, AnimateCommandOptions& opts);

/// Returns the exit status (0 success, 1 failure). Frames are written as
/// DIR/frame_NNNN.EXT, each to a temporary name then renamed; with --video,
/// the video is encoded from the finished frames once all are there. Under
/// mpirun (`world` distributed) the ranks are dealt groups of frames.
int run_animate(const AnimateCommandOptions& opts, const cluster::World& world);

}  // namespace holoray::cli
