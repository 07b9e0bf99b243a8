#include "cli/animate_command.hpp"


#include <algorithm>

#include <fmt/format.h>
#include <oneapi/tbb/global_control.h>

#include <charconv>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <thread>
#include <type_traits>

#include "cli/devices_command.hpp"
#include "cli/error_words.hpp"
#include "cli/interrupt.hpp"
#include "cli/machine.hpp"
#include "cli/option_parsing.hpp"
#include "cli/scene_warnings.hpp"
#include "cli/validators.hpp"
#include "cluster/group_dealer.hpp"
#include "cluster/mpi_world.hpp"
#include "holoray/holoray.hpp"

namespace holoray::cli {

namespace {

std::string frame_path(const std::string& dir, int frame, int frames, const std::string& ext) {
  const int digits = std::max(4, static_cast<int>(std::to_string(frames - 1).size()));
  return (std::filesystem::path(dir) / fmt::format("frame_{:0{}}.{}", frame, digits, ext)).string();
}

// A run killed outright (SIGKILL, power loss) can leave the temporary file of
// the frame it was writing (image_io's ".<stem>.tmp<pid>.<ext>"); a resumed
// run removes them so the folder ends as an uninterrupted run leaves it.
// Only those of its own frames [first, last]: tasks rendering other ranges
// into the same folder may be writing theirs right now.
void remove_stale_temporaries(const std::string& dir, int first, int last) {
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if (!name.starts_with(".frame_") || name.find(".tmp") == std::string::npos) continue;
    int frame = -1;
    const char* digits = name.data() + 7;
    std::from_chars(digits, name.data() + name.size(), frame);
    if (frame >= first && frame <= last) std::filesystem::remove(e.path(), ec);
  }
}

// --keyframe-interval K: a whole number of frames, at least 1 ("auto" is
// handled by the caller).
int keyframe_interval_of(const std::string& k) {
  int interval = 0;
  const auto [end, err] = std::from_chars(k.data(), k.data() + k.size(), interval);
  if (k != "auto" && (err != std::errc() || end != k.data() + k.size() || interval < 1))
    throw std::invalid_argument(
        fmt::format("--keyframe-interval: must be a whole number of frames, at least 1, or auto; got '{}'", k));
  return interval;
}

// "A:B" (inclusive) or "N" for --frames; -1 ends mean "not given".
void parse_frame_range(const std::string& text, int& first, int& last) {
  const auto colon = text.find(':');
  auto number = [&](std::string_view part, int& out) {
    const auto r = std::from_chars(part.data(), part.data() + part.size(), out);
    return !part.empty() && r.ec == std::errc() && r.ptr == part.data() + part.size() && out >= 0;
  };
  const bool ok = colon == std::string::npos
                      ? number(text, first) && (last = first, true)
                      : number(std::string_view(text).substr(0, colon), first) &&
                            number(std::string_view(text).substr(colon + 1), last);
  if (!ok) throw std::invalid_argument(fmt::format("--frames: expected A:B (first and last frame, from 0) or N, got '{}'", text));
  if (last < first) throw std::invalid_argument(fmt::format("--frames: the last frame comes before the first in '{}'", text));
}

}  // namespace

CLI::App* add_animate_command(CLI::App& app, AnimateCommandOptions& o) {
  CLI::App* cmd = app.add_subcommand("animate", "Render an animated shot (TOML) as numbered EIA frames");
  cmd->add_option("shot", o.shot, "Shot file (TOML, docs/shot-format.md)")->required()->check(existing_file());
  cmd->add_option("-o,--output", o.output, "Output folder (created if missing)")->required();
  cmd->add_option("--method", o.method, "reverse (keyframes + every eye ray traced, shading reused: faster than full on every bench shot; the default), reproject (keyframes + the paper's forward reprojection) or full (trace every frame; the default and only choice with --camera pinhole)")
      ->check(one_of({"reverse", "reproject", "full"}));
  add_camera_options(*cmd, o.view, "each frame (placed by the frame's viewpoint, traced in full)");
  cmd->add_option("--keyframe-interval", o.keyframe_interval,
                  "K: trace every K-th frame and the last; auto: place keyframes by how far point images move "
                  "(--keyframe-motion), sparse where nothing moves, dense where it moves fast")
      ->check(parsed_by([](const std::string& k) { keyframe_interval_of(k); }, "K|auto"))
      ->capture_default_str();
  cmd->add_option("--keyframe-motion", o.keyframe_motion,
                  "With --keyframe-interval auto: the most pixels a point image may move between a frame and its "
                  "earlier keyframe")
      ->capture_default_str();
  cmd->add_option("--max-keyframe-interval", o.max_keyframe_interval,
                  "With --keyframe-interval auto: the most frames from one keyframe to the next")
      ->check(in_range(1))
      ->capture_default_str();
  cmd->add_option("--reuse", o.reuse,
                  "What a reprojected pixel reuses. --method reproject: geometry (default; re-shade the reused hit) or "
                  "color (the keyframe colour); --method reverse: color (default; the keyframe colour) or visibility "
                  "(light visibility and reflected light reused, local shading exact)");
  cmd->add_option("--fill", o.fill, "Missed pixels: trace or interpolate")->check(one_of({"trace", "interpolate"}))->capture_default_str();
  cmd->add_option("--rebuild-above", o.rebuild_above, "With --fill interpolate: trace the holes of a frame with more than this percent of them (wider holes interpolate worse than holding a keyframe)")
      ->check(in_range(0, 100, false, "percent"))
      ->capture_default_str();
  cmd->add_option("--reach", o.reach, "near (one lens per point) or all (every lens that sees it)")->check(one_of({"near", "all"}))->capture_default_str();
  cmd->add_flag("--no-leak-check", o.no_leak_check, "Keep points seen through gaps of nearer surfaces");
  cmd->add_option("--format", o.format, "Frame format")->check(one_of({"png", "exr"}))->capture_default_str();
  cmd->add_option("--encoding", o.encoding, "PNG encoding: linear, srgb, or auto (srgb when the shot's first scene file is a mesh, linear for NFF and Tachyon)")
      ->check(one_of({"auto", "linear", "srgb"}))
      ->capture_default_str();
  cmd->add_option("--report", o.report, "Also trace every frame in full and write the quality/time tables here (.md)");
  cmd->add_option("--frames", o.frames, "Render only frames A:B (inclusive, from 0; or one frame N) and the keyframes they need, as a render farm's task does: ranges covering the shot, run apart (even at once, into one folder), give the folder of one run")
      ->check(parsed_by([](const std::string& t) { int a, b; parse_frame_range(t, a, b); }, "A:B"));
  cmd->add_flag("--resume", o.resume, "Skip frames already in the output folder (a --video is encoded again from all the frames)");
  cmd->add_option("--video", o.video, "Also write the frames as a video once all are done: .mkv (FFV1, lossless: decoded frames equal the 8-bit frames) or .mp4 (H.264); written under a temporary name and renamed when complete")
      ->check(parsed_by([](const std::string& v) {
        if (!api::is_video_output(v))
          throw std::invalid_argument(fmt::format("--video: '{}' is neither .mkv (FFV1, lossless) nor .mp4 (H.264)", v));
      }, "OUT.mkv|OUT.mp4"));
  cmd->add_option("--crf", o.crf, "With --video .mp4: H.264 constant rate factor, 0 (best) to 51 (default 18)")
      ->check(in_range(0, 51))
      ->needs("--video");
  cmd->add_option("--threads", o.threads, "Worker threads (0: all cores)")->check(in_range(0))->capture_default_str();
  cmd->add_option("--seed", o.seed,
                  "With --integrator path: the samples' seed, 0 to 4294967295, every frame's (as Cycles' Seed)")
      ->check(in_range(0, 4294967295.0))
      ->capture_default_str();
  cmd->add_flag("--animated-seed", o.animated_seed,
                "With --integrator path: each frame's seed is --seed plus the frame's number, so that each frame's "
                "noise is its own (as Cycles' Animated Seed)");
  add_device_option(*cmd, o.device,
                    "on a GPU every frame is traced in full (--method full; reuse stays on the CPU), the scene laid out "
                    "again where something moved");
  add_cache_options(*cmd, o.cache);
  add_light_options(*cmd, o.light, false);
  cmd->add_flag("-q,--quiet", o.quiet, "Print nothing but errors");
  cmd->add_flag("-v,--verbose", o.verbose, "Also print the time of each reprojection stage");
  add_scene_read_options(*cmd, o.camera_name, o.texture_paths);
  lay_out_help(*cmd,
               {{"Output", {"--output", "--format", "--encoding", "--video", "--crf", "--report", "--quiet", "--verbose"}},
                {"Scene", {"--camera-name", "--texture-path"}},
                {"Camera", {"--camera", "--resolution", "--display", "--looking-glass", "--views"}},
                {"Reuse", {"--method", "--reuse", "--fill", "--rebuild-above", "--reach", "--no-leak-check", "--cache",
                           "--cache-cell", "--cache-memory"}},
                {"Keyframes", {"--keyframe-interval", "--keyframe-motion", "--max-keyframe-interval"}},
                {"Tracing", {"--device", "--threads", "--seed", "--animated-seed"}},
                {"Light", light_option_names(false)},
                {"Farms and interruptions", {"--frames", "--resume"}}},
               {"holoray animate examples/shots/swinging_box.toml -o frames/ --video frames/shot.mkv",
                "holoray animate examples/shots/swinging_box.toml -o views/ --camera pinhole --resolution 256x256"},
               "docs/guide/animation.md, docs/guide/cluster.md");
  return cmd;
}

namespace {

// One frame's line: traced (a keyframe), copied from its keyframe, or
// reprojected with its shares of pixels (and, verbose, its stages' times).
void print_frame(const std::string& rank_tag, int f, const api::FrameRow& r, bool verbose) {
  if (r.keyframe) {
    fmt::print("{}frame {:>5}  traced       {:.3f} s\n", rank_tag, f, r.seconds);
  } else if (r.copied_from >= 0) {
    fmt::print("{}frame {:>5}  copied       {:.3f} s  keyframe {} (same camera, nothing moved){}\n", rank_tag, f,
               r.seconds, r.copied_from, r.difference ? fmt::format(", PSNR {:.2f} dB", r.difference->psnr()) : "");
  } else {
    const double px = static_cast<double>(r.pixels);
    fmt::print("{}frame {:>5}  reprojected  {:.3f} s  {:.1f}% reused, {:.1f}% traced, {:.1f}% interpolated{}\n", rank_tag, f,
               r.seconds, 100 * r.reprojected / px, 100 * r.traced / px, 100 * r.interpolated / px,
               r.difference ? fmt::format(", PSNR {:.2f} dB", r.difference->psnr()) : "");
    if (verbose)
      fmt::print("             splat {:.3f} s, merge {:.3f} s, leaks {:.3f} s, check {:.3f} s, fill {:.3f} s\n",
                 r.stage_seconds[0], r.stage_seconds[1], r.stage_seconds[2], r.stage_seconds[3], r.stage_seconds[4]);
  }
  std::fflush(stdout);
}

// Every rank's frame reports (one per frame written) on rank 0, in frame
// order (collective: every rank has finished writing). api::FrameRow is
// plain data: its bytes travel as they are.
void gather_reports(const cluster::World& world, std::vector<api::FrameRow>& reports) {
  static_assert(std::is_trivially_copyable_v<api::FrameRow>);
  std::vector<unsigned char> bytes(reports.size() * sizeof(api::FrameRow));
  if (!reports.empty()) std::memcpy(bytes.data(), reports.data(), bytes.size());
  bytes = world.gather(bytes);
  reports.resize(bytes.size() / sizeof(api::FrameRow));
  if (!reports.empty()) std::memcpy(reports.data(), bytes.data(), bytes.size());
  std::sort(reports.begin(), reports.end(), [](const api::FrameRow& a, const api::FrameRow& b) { return a.frame < b.frame; });
}

// The video, from the frames on disk, in order: it shows exactly what the
// folder holds, and a resumed run rebuilds it whole.
void write_video(const AnimateCommandOptions& o, int frames, const std::string& ext, api::Encoding encoding,
                 const api::VideoOptions& vo) {
  const auto t0 = Clock::now();
  std::optional<api::VideoWriter> video;
  for (int f = 0; f < frames; ++f) {
    const api::Image img = api::read_image(frame_path(o.output, f, frames, ext));
    if (!video) video.emplace(o.video, img.width(), img.height(), vo);
    if (img.channels() < 3) throw std::runtime_error(fmt::format("frame {} has {} channels, not RGB", f, img.channels()));
    // PNG frames hold their codes already; EXR frames are encoded as PNG frames would be.
    video->add_frame(img, ext == "png" ? api::Encoding::linear : encoding);
  }
  video->finish();
  if (!o.quiet)
    fmt::print("video      {}: {} frames, {}, {:.3f} s\n", o.video, frames, api::video_codec_name(o.video, vo),
               seconds_since(t0));
}

// -o's folder made, and the folders --video and --report write into there.
void make_output_folders(const AnimateCommandOptions& o) {
  std::error_code ec;
  std::filesystem::create_directories(o.output, ec);
  if (!std::filesystem::is_directory(o.output))
    throw std::runtime_error(fmt::format("-o: cannot create the folder '{}'{}", o.output, ec ? ": " + ec.message() : ""));
  if (!o.video.empty()) {  // after -o's folder is made: the video may go in it
    const auto dir = std::filesystem::path(o.video).parent_path();
    if (!dir.empty() && !std::filesystem::is_directory(dir))
      throw std::invalid_argument(fmt::format("--video: folder '{}' does not exist", dir.string()));
  }
  if (!o.report.empty()) {
    const auto dir = std::filesystem::path(o.report).parent_path();
    if (!dir.empty() && !std::filesystem::is_directory(dir))
      throw std::invalid_argument(fmt::format("--report: folder '{}' does not exist", dir.string()));
  }
}

// --report: the command that reproduces the run, the EIA, the machine and
// every frame's row (api::report_markdown).
void write_report(const AnimateCommandOptions& o, const cluster::World& world, const api::Animation& animation,
                  const std::string& method, const std::string& reuse, const std::string& key_args, api::Method chosen,
                  const std::vector<api::FrameRow>& reports) {
  std::string cmdline = fmt::format("{}holoray animate {} -o {} --method {} --cache {}",
                                    world.distributed() ? fmt::format("mpirun -np {} ", world.size()) : "", o.shot,
                                    o.output, method, o.cache.cache);
  if (chosen == api::Method::reproject)
    cmdline += fmt::format(" {} --reuse {} --fill {} --rebuild-above {:g} --reach {}{}", key_args, reuse, o.fill,
                           o.rebuild_above, o.reach, o.no_leak_check ? " --no-leak-check" : "");
  else if (chosen == api::Method::reverse)
    cmdline += fmt::format(" {} --reuse {}", key_args, reuse);
  api::write_text_file(o.report,
                  api::report_markdown(fmt::format("holoray animate: {}", std::filesystem::path(o.shot).filename().string()),
                                  {fmt::format("- command: `{} --report {}`", cmdline, o.report),
                                   fmt::format("- EIA: {}", animation.array_summary()),
                                   fmt::format("- machine: {}, {} threads{}", machine_description(),
                                               o.threads > 0 ? o.threads : static_cast<int>(std::thread::hardware_concurrency()),
                                               world.distributed()
                                                   ? fmt::format(" per rank, {} ranks (seconds are each frame's own, "
                                                                 "on the rank that made it)", world.size())
                                                   : "")},
                                  reports));
  if (!o.quiet) fmt::print("report     {}\n", o.report);
}

// The options as the API takes them, with the words the summary and the
// report repeat. Each word is checked here; the rules between them are the
// API's (api::Animation), which names what it refuses by its own names,
// said here as options (error_words.hpp).
struct AnimateChoice {
  api::AnimateOptions options;
  std::string method, reuse, ext;  ///< --method, --reuse (defaults resolved), --format
  api::VideoOptions video;
  bool auto_keys = false;  ///< --keyframe-interval auto
};

AnimateChoice choose(const AnimateCommandOptions& o) {
  AnimateChoice c;
  api::AnimateOptions& ao = c.options;
  camera_desc_rules(o.view, false, false);
  const bool pinhole = o.view.camera == "pinhole";
  const bool glass = !o.view.looking_glass.empty();
  const bool panel = glass || !o.view.display.empty();
  const bool path = o.light.integrator == "path";
  c.method = !o.method.empty() ? o.method : pinhole || panel || path || o.device != "cpu" ? "full" : "reverse";
  ao.method = pick<api::Method>("--method", c.method,
                                {{"full", api::Method::full}, {"reproject", api::Method::reproject}, {"reverse", api::Method::reverse}});
  if (glass) {
    ao.camera = api::LookingGlass{o.view.looking_glass, o.view.looking_glass_views, std::nullopt};  // the viewpoint's focus
  } else if (panel) {
    ao.camera = api::Display{o.view.display, std::nullopt, std::nullopt};
  } else if (pinhole) {
    api::Pinhole p;
    if (!o.view.resolution.empty()) parse_resolution(o.view.resolution, p.width, p.height);
    ao.camera = p;
  }
  c.reuse = !o.reuse.empty() ? o.reuse : ao.method == api::Method::reverse ? "color" : "geometry";
  if (ao.method == api::Method::reverse) pick<int>("--reuse", c.reuse, {{"visibility", 0}, {"color", 1}});
  else pick<int>("--reuse", c.reuse, {{"geometry", 0}, {"color", 1}});
  ao.reuse = o.reuse;
  ao.reach = pick<std::string>("--reach", o.reach, {{"near", "near"}, {"all", "all"}});
  ao.fill = pick<std::string>("--fill", o.fill, {{"trace", "trace"}, {"interpolate", "interpolate"}});
  ao.leak_check = !o.no_leak_check;
  const LightChoice light = light_choice(o.light);
  ao.integrator = light.integrator;
  if (light.integrator != api::Integrator::path && (o.seed != 0 || o.animated_seed))
    throw std::invalid_argument(fmt::format("{}: Whitted's integrator draws no random samples: go with --integrator path",
                                            o.seed != 0 ? "--seed" : "--animated-seed"));
  ao.seed = static_cast<uint32_t>(o.seed);
  ao.animated_seed = o.animated_seed;
  ao.environment = light.environment;
  ao.blender_principled = light.blender_principled;
  c.ext = pick<std::string>("--format", o.format, {{"png", "png"}, {"exr", "exr"}});
  if (!o.video.empty()) {
    const bool h264 = !api::is_lossless_video(o.video);
    if (o.crf != -1 && !h264) throw std::invalid_argument("--crf: goes with an .mp4 video (FFV1 is lossless)");
    if (o.crf != -1) c.video.crf = o.crf;
  }
  const api::Encoding encoding_choice = parse_encoding(o.encoding, "");  // checked now; "auto" is resolved once the shot is read
  if (o.encoding != "auto") ao.encoding = encoding_choice;
  c.auto_keys = o.keyframe_interval == "auto";
  const int interval = c.auto_keys ? 0 : keyframe_interval_of(o.keyframe_interval);
  if (!(o.keyframe_motion > 0) || !std::isfinite(o.keyframe_motion))
    throw std::invalid_argument(fmt::format("--keyframe-motion: must be a positive number of pixels, got {}", o.keyframe_motion));
  ao.keyframe_interval = interval;
  ao.keyframe_motion = o.keyframe_motion;
  ao.max_keyframe_interval = o.max_keyframe_interval;
  ao.rebuild_above_percent = o.rebuild_above;
  ao.threads = o.threads;
  ao.device = o.device;
  ao.reference = !o.report.empty();
  ao.cache = cache_options(o.cache);  // checked before the shot is read
  return c;
}

}  // namespace

int run_animate(const AnimateCommandOptions& o, const cluster::World& world) {
  bool rendering = false;  // past setup: an error now stops every rank (World::fail)
  try {
    const AnimateChoice c = choose(o);
    api::AnimateOptions ao = c.options;
    const std::string &method = c.method, &reuse = c.reuse, &ext = c.ext;
    api::VideoOptions vo = c.video;
    const bool auto_keys = c.auto_keys;
    const int interval = ao.keyframe_interval;
    std::unique_ptr<tbb::global_control> thread_cap;
    if (o.threads > 0)
      thread_cap = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, o.threads);

    int range_first = 0, range_last = -1;
    if (!o.frames.empty()) parse_frame_range(o.frames, range_first, range_last);
    // Frames outside the range count as done: never written, and their
    // keyframes traced only where a frame in the range needs one. The
    // keyframes are the whole shot's, so a range's frames are one run's.
    int frames = 0;
    ao.done = [&](int f) {
      return f < range_first || f > range_last || (o.resume && std::filesystem::exists(frame_path(o.output, f, frames, ext)));
    };
    std::optional<cluster::GroupDealer> dealer;
    if (world.distributed()) {
      ao.next_group = [&] { return dealer->next(); };
      ao.device = api::device_of_local_rank(ao.device, world.local_rank());  // the machine's GPUs, one each in turn
    }
    const StopOnSignal interrupt;
    ao.stop = [&] {
      if (!interrupt.requested()) return false;
      if (dealer) dealer->stop();
      return true;
    };
    ao.load = {o.camera_name, o.texture_paths};
    api::Animation animation(o.shot, ao);
    frames = animation.frame_count();
    if (o.frames.empty()) range_last = frames - 1;
    if (range_last >= frames)
      throw std::invalid_argument(fmt::format("--frames: the shot has frames 0 to {}, got '{}'", frames - 1, o.frames));
    const bool whole_shot = range_first == 0 && range_last == frames - 1;
    if (!o.video.empty() && !whole_shot)
      throw std::invalid_argument("--video: needs every frame; after the ranges, run the whole shot with --resume --video");
    const std::string key_args =
        auto_keys ? fmt::format("--keyframe-interval auto --keyframe-motion {:g} --max-keyframe-interval {}",
                                o.keyframe_motion, o.max_keyframe_interval)
                  : fmt::format("--keyframe-interval {}", interval);
    make_output_folders(o);
    // Rank 0 alone, before any rank starts (agree() below waits for all).
    if (o.resume && world.rank() == 0) remove_stale_temporaries(o.output, range_first, range_last);
    // Under mpirun, ranks are dealt groups of frames (cluster/group_dealer):
    // weighted by the frames each has left to render.
    if (world.distributed()) {
      std::vector<double> weights;
      for (const auto& [first, last] : animation.groups()) {
        int left = 0;
        for (int f = first; f <= last; ++f) left += !ao.done(f);
        weights.push_back(left);
      }
      dealer.emplace(world, std::move(weights));
    }
    const std::string rank_tag = world.distributed() ? fmt::format("rank {:>2}  ", world.rank()) : "";

    if (!o.quiet && world.rank() == 0) {
      for (const auto& w : animation.warnings()) print_scene_warnings(w.text, w.count, w.source);
      fmt::print("shot       {}: {} frames at {:g} fps, {} scene file(s)\n", o.shot, frames, animation.fps(),
                 animation.object_count());
      fmt::print("{}", animation.describe());
      if (const std::string gpu = animation.device_name(); !gpu.empty()) fmt::print("device     {}\n", gpu);
      if (world.distributed())
        fmt::print("ranks      {}: groups of frames (a keyframe and the frames up to the next) dealt by rank 0\n", world.size());
    }
    if (!world.agree(true, "")) return 1;
    rendering = true;
    const auto run_start = Clock::now();

    std::vector<api::FrameRow> reports;
    // Each frame encoded and written on the writer's thread while the next
    // traces; two wait at most. Its seconds are not in FrameRow::seconds.
    api::BackgroundWriter writer(2);
    animation.run([&](int f, const api::Image& colour, const api::FrameRow& r) {
      writer.submit(frame_path(o.output, f, frames, ext), colour, animation.encoding());
      reports.push_back(r);
      if (!o.quiet) print_frame(rank_tag, f, r, o.verbose);
    });
    writer.finish();
    const double write_seconds = writer.write_seconds();

    const cluster::DealStats deal = dealer ? dealer->finish() : cluster::DealStats{};
    // On rank 0, for the totals and --report.
    if (world.distributed()) gather_reports(world, reports);
    const api::RunTotals s = api::totals(reports);
    const int64_t written_all = static_cast<int64_t>(reports.size());  // on rank 0
    const double write_seconds_all = world.sum(write_seconds);
    const int64_t interrupted_ranks = world.sum(int64_t{interrupt.requested() ? 1 : 0});
    const double wall_s = seconds_since(run_start);
    if (interrupted_ranks > 0) {
      if (world.rank() == 0)
        fmt::print(stderr, "holoray: interrupted by {} after {} new frames; every frame in '{}' is complete; "
                   "rerun with --resume to finish\n",
                   interrupt.requested() ? (interrupt.signal() == SIGINT ? "SIGINT" : "SIGTERM") : "a signal", written_all, o.output);
      return interrupt.requested() ? interrupt.exit_status() : 128 + SIGTERM;
    }
    if (world.rank() != 0) return 0;
    if (!o.video.empty()) {
      vo.fps = animation.fps();
      write_video(o, frames, ext, animation.encoding(), vo);
    }
    if (!o.quiet) {
      const int in_range = range_last - range_first + 1;
      fmt::print("wrote      {} frames to {}{}{}\n", written_all, o.output,
                 whole_shot ? "" : fmt::format(" (frames {} to {})", range_first, range_last),
                 o.resume ? fmt::format(" ({} already there)", in_range - written_all) : "");
      if (world.distributed())
        fmt::print("ranks      {} ranks, {:.3f} s wall; {} groups dealt, {} started apart from their rank's previous group "
                   "(a keyframe traced twice each), {} steals, {} bytes of requests; {:.3f} s writing frames (all ranks)\n",
                   world.size(), wall_s, deal.groups_dealt, deal.unchained_starts, deal.steals, deal.request_bytes,
                   write_seconds_all);
      fmt::print("time       {:.3f} s{}\n", s.seconds,
                 ao.reference ? fmt::format(" (full ray tracing {:.3f} s, {:.1f}% saved, mean PSNR {:.2f} dB)", s.full_seconds,
                                            s.saved_percent, s.mean_psnr)
                              : "");
    }
    if (!o.report.empty()) write_report(o, world, animation, method, reuse, key_args, ao.method, reports);
    return 0;
  } catch (const std::exception& e) {
    return world.fail(error_report(e), rendering);
  }
}

}  // namespace holoray::cli
