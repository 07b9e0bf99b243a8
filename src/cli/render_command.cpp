#include "cli/light_options.hpp"
#include "cli/render_command.hpp"


#include <fmt/format.h>
#include <oneapi/tbb/global_control.h>
#include <oneapi/tbb/task_arena.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <mutex>
#include <optional>
#include <tuple>
#include <utility>

#include "cli/devices_command.hpp"
#include "cli/error_words.hpp"
#include "cli/option_parsing.hpp"
#include "cli/scene_warnings.hpp"
#include "cli/validators.hpp"
#include "cluster/band_exchange.hpp"
#include "cluster/mpi_world.hpp"
#include "cluster/row_bands.hpp"
#include "holoray/holoray.hpp"

namespace holoray::cli {

namespace {

// The colour file and its AOV files (aov_path: albedo beside it in its
// format, depth, normal and id as EXR), written band by band, top to bottom:
// whole in one process, as the bands arrive under mpirun.
class FrameFiles {
 public:
  FrameFiles(const std::string& output, int width, int height, const api::Aovs& aovs, api::Encoding encoding,
             api::ExrCompression exr) {
    const std::string ext = std::filesystem::path(output).extension().string().substr(1);
    auto add = [&](api::Image api::Result::*plane, const std::string& path, int channels, api::Encoding enc) {
      files_.emplace_back(plane, std::make_unique<api::ImageWriter>(path, width, height, channels, enc, exr));
    };
    add(&api::Result::colour, output, 3, encoding);
    if (aovs.albedo) add(&api::Result::albedo, api::aov_path(output, "albedo", ext), 3, encoding);
    if (aovs.depth) add(&api::Result::depth, api::aov_path(output, "depth", "exr"), 1, api::Encoding::linear);
    if (aovs.normal) add(&api::Result::normal, api::aov_path(output, "normal", "exr"), 3, api::Encoding::linear);
    if (aovs.id) add(&api::Result::id, api::aov_path(output, "id", "exr"), 1, api::Encoding::linear);
  }
  /// The next rows of every file: a band, or the whole image.
  void write(const api::Result& rows) {
    for (auto& [plane, writer] : files_) writer->write_rows(rows.*plane);
  }
  void finish() {
    for (auto& [plane, writer] : files_) writer->finish();
  }

 private:
  std::vector<std::pair<api::Image api::Result::*, std::unique_ptr<api::ImageWriter>>> files_;
};

// The lens array the options describe (each value checked by CLI11).
api::LensArray lens_array_of(const RenderCommandOptions& o) {
  api::LensArray a;
  a.grid = parse_grid(o.grid);
  a.mode = o.mode == "pseudoscopic" ? api::Mode::pseudoscopic : api::Mode::orthoscopic;
  parse_lens_count(o.lenses, a.lenses_x, a.lenses_y);
  a.pixels_per_lens = o.pixels_per_lens;
  a.rows = o.rows;
  if (!std::isnan(o.pitch)) a.pitch = o.pitch;
  if (!std::isnan(o.gap)) a.gap = o.gap;
  if (!std::isnan(o.fov_lens)) a.fov_lens_deg = o.fov_lens;
  a.view_distance = o.view_distance;
  a.placement = placement_of(o.origin, o.normal, o.up);
  return a;
}

// --shift X,Y: two finite numbers.
std::pair<double, double> parse_shift(const std::string& text) {
  const auto comma = text.find(',');
  try {
    size_t a = 0, b = 0;
    if (comma == std::string::npos) throw std::invalid_argument("");
    const double x = std::stod(text.substr(0, comma), &a), y = std::stod(text.substr(comma + 1), &b);
    if (a != comma || b != text.size() - comma - 1 || !std::isfinite(x) || !std::isfinite(y)) throw std::invalid_argument("");
    return {x, y};
  } catch (const std::exception&) {
    throw std::invalid_argument(fmt::format("--shift: expected X,Y (two finite numbers), got '{}'", text));
  }
}

// A CLI11 check of an X,Y,Z option.
CLI::Validator vec3(const char* option) {
  return parsed_by([option](const std::string& t) { parse_vec3(option, t); }, "X,Y,Z");
}

}  // namespace

std::vector<CLI::Option*> add_lens_array_options(CLI::App& cmd, RenderCommandOptions& o) {
  return {
      cmd.add_option("--grid", o.grid, "Lens grid")->check(one_of({"square", "hex", "lenticular"}))->capture_default_str(),
      cmd.add_option("--lenses", o.lenses, "Lens count NXxNY (lenticular: NY unused)")
          ->check(parsed_by([](const std::string& t) { int x, y; parse_lens_count(t, x, y); }, "NXxNY"))
          ->capture_default_str(),
      cmd.add_option("--pixels-per-lens", o.pixels_per_lens, "Pixels across one lens (P)")->check(in_range(1))->capture_default_str(),
      cmd.add_option("--rows", o.rows, "Image rows H for hex and lenticular (default: the contract's)")->check(in_range(1)),
      cmd.add_option("--fov-lens", o.fov_lens, "Lens field of view in degrees (default 20); sets the gap"),
      cmd.add_option("--gap", o.gap, "Lens plane to pixel panel distance, scene units"),
      cmd.add_option("--pitch", o.pitch, "Lens pitch, scene units (default: NFF view width / NX)"),
      cmd.add_option("--mode", o.mode, "orthoscopic (display-ready) or pseudoscopic (direct pickup)")
          ->check(one_of({"orthoscopic", "pseudoscopic"}))
          ->capture_default_str(),
      cmd.add_option("--view-distance", o.view_distance, "Lenticular vertical perspective distance V (default: infinite)")};
}

void add_focus_distance_option(CLI::App& cmd, RenderCommandOptions& o) {
  cmd.add_option("--focus-distance", o.focus_distance,
                  "The focal plane's distance from the viewpoint, scene units: where a lens array or a display's lens "
                  "sheet stands, a quilt's or Looking Glass's zero-parallax plane (default: the viewpoint's from-to-at "
                  "distance; a mesh file's camera: the depth of the scene's centre)")
      ->check(CLI::PositiveNumber);
}

CLI::App* add_render_command(CLI::App& app, RenderCommandOptions& o) {
  CLI::App* cmd = app.add_subcommand("render", "Render one elemental image array (EIA), or the scene's own pinhole view, from an NFF, Tachyon or mesh scene");
  cmd->add_option("scene", o.scene, "Scene file: NFF (.nff), Tachyon (.dat), or a mesh through assimp (.obj, .ply, .stl, .gltf, .glb, .3ds, .dae, .ac)")
      ->required()
      ->check(existing_file());
  cmd->add_option("-o,--output", o.output, "Output image: .png (8-bit) or .exr (float)")->required()->check(output_image());
  const auto [display, lg] = add_camera_options(*cmd, o.view, "the image");
  cmd->add_option("--sample-at", o.sample_at, "With --camera pinhole: where in each pixel its single sample lies: centre, or tachyon (the upper-right corner, where Tachyon samples; for pixel-for-pixel comparisons)")
      ->check(one_of({"centre", "tachyon"}))
      ->capture_default_str();
  cmd->add_option("--shift", o.shift, "With --camera pinhole: lens shift X,Y, the view's window moved right and up by these fractions of its larger side (as a Blender camera's shift)")
      ->check(parsed_by([](const std::string& t) { parse_shift(t); }, "X,Y"));
  const std::vector<CLI::Option*> array_options = add_lens_array_options(*cmd, o);
  for (CLI::Option* a : array_options) display->excludes(a), lg->excludes(a);
  CLI::Option* quilt = cmd->add_option("--quilt", o.quilt, "A Looking Glass quilt of CxR off-axis views (sheared frusta sharing the viewpoint's focal plane), tiled as Looking Glass tools expect: view 0, the leftmost, bottom left; written as NAME_qsCxRaASPECT.ext. --resolution sets one view's size (default 420x560)")
      ->check(parsed_by([](const std::string& t) {
        int c, r;
        parse_lens_count(t, c, r, "--quilt");
        if (int64_t{c} * r > 4096) throw std::invalid_argument(fmt::format("--quilt: at most 4096 views, got {}", t));
      }, "CxR"));
  cmd->add_option("--view-cone", o.view_cone, "With --quilt: degrees from the leftmost to the rightmost view")
      ->check(in_range(0, 180, true, "degrees"))
      ->needs(quilt)
      ->capture_default_str();
  add_focus_distance_option(*cmd, o);
  add_scene_read_options(*cmd, o.camera_name, o.texture_paths);
  cmd->add_option("--quilt-view", o.quilt_view, "With --quilt: render only view K (0 = leftmost) as a plain image, named as -o says")
      ->check(in_range(0))
      ->needs(quilt);
  cmd->add_option("--share-views", o.share_views,
                  "With --quilt and --integrator path: each view also takes the samples of S views on each side that see "
                  "the same surface, the BSDF evaluated for its own eye (about 1 + 2S samples a pixel; 0: none)")
      ->check(in_range(0, api::kMaxShareViews))
      ->needs(quilt);
  for (CLI::Option* a : array_options) quilt->excludes(a);
  quilt->excludes(display);
  lg->excludes(quilt);
  CLI::Option* origin = cmd->add_option("--origin", o.origin, "Array centre X,Y,Z (explicit placement, with --normal --up --pitch)")->check(vec3("--origin"));
  CLI::Option* normal = cmd->add_option("--normal", o.normal, "Array normal X,Y,Z, toward the viewer")->check(vec3("--normal"));
  CLI::Option* up = cmd->add_option("--up", o.up, "Up direction X,Y,Z (orthogonalised)")->check(vec3("--up"));
  for (CLI::Option* a : {origin, normal, up})
    for (CLI::Option* b : {origin, normal, up})
      if (a != b) a->needs(b);
  cmd->add_option("--spp", o.spp, "Samples per pixel (jittered inside the pixel)")->check(in_range(1))->capture_default_str();
  cmd->add_option("--seed", o.seed,
                  "With --integrator path: the samples' seed, 0 to 4294967295; renders with different seeds have "
                  "independent noise (as Cycles' Seed)")
      ->check(in_range(0, 4294967295.0))
      ->capture_default_str();
  cmd->add_option("--threads", o.threads, "Worker threads (0: all cores)")->check(in_range(0))->capture_default_str();
  cmd->add_option("--max-depth", o.max_depth, "Ray-tree depth limit, eye ray = 1 (default: the scene's Tachyon raydepth, else 5, the SPD's)")
      ->check(in_range(1, api::kMaxDepth));
  cmd->add_option("--style", o.style, "Pixel-tracing style: subaperture (16-ray packets of one pixel of 4x4 lenses), packet (16-ray packets of 4x4 pixels of one lens), horizontal or vertical (single rays, paper §6); auto picks the faster packets for the array")
      ->check(one_of({"auto", "subaperture", "packet", "horizontal", "vertical"}))
      ->capture_default_str();
  add_device_option(*cmd, o.device, "the GPU path renders what the CPU path renders, in float, without the shadow cache");
  add_light_options(*cmd, o.light, true);
  cmd->add_option("--aov", o.aovs, "Extra outputs, comma-separated: albedo,depth,normal,id")
      ->check(parsed_by([](const std::string& t) { parse_aovs(t); }, "LIST"));
  cmd->add_option("--encoding", o.encoding, "PNG encoding: linear, srgb, or auto (srgb for a mesh scene, linear for NFF and Tachyon)")
      ->check(one_of({"auto", "linear", "srgb"}))
      ->capture_default_str();
  add_cache_options(*cmd, o.cache);
  cmd->add_option("--exr-compression", o.exr_compression,
                  "Lossless compression of .exr files (the image and its AOVs); none is the largest and the fastest to "
                  "write and read")
      ->check(one_of({"zip", "zips", "piz", "rle", "none"}))
      ->capture_default_str();
  cmd->add_flag("-q,--quiet", o.quiet, "Print nothing but errors");
  cmd->add_flag("--progress", o.progress_lines,
                "Print the fraction traced to stderr as lines 'progress F' (F from 0 to 1, each percent once), for "
                "programs that drive holoray (the Blender add-on)");
  lay_out_help(*cmd,
               {{"Output", {"--output", "--aov", "--encoding", "--exr-compression", "--quiet", "--progress"}},
                {"Scene", {"--camera-name", "--texture-path"}},
                {"Camera", {"--camera", "--resolution", "--sample-at", "--shift", "--display", "--looking-glass", "--views", "--quilt",
                            "--view-cone", "--quilt-view", "--share-views", "--focus-distance"}},
                {"Lens array", {"--grid", "--lenses", "--pixels-per-lens", "--rows", "--fov-lens", "--gap", "--pitch", "--mode",
                                "--view-distance", "--origin", "--normal", "--up"}},
                {"Tracing", {"--device", "--spp", "--seed", "--threads", "--max-depth", "--style", "--cache", "--cache-cell", "--cache-memory"}},
                {"Light", light_option_names(true)}},
               {"holoray render examples/primitives.nff --grid hex --lenses 48x48 --pixels-per-lens 10 -o eia.png",
                "holoray render examples/primitives.nff --display examples/displays/lenticular_4k.toml -o panel.png"},
               "docs/guide/stills.md, docs/guide/displays.md");
  return cmd;
}

api::Camera camera_of(const RenderCommandOptions& o) {
  const CameraOptions& v = o.view;
  const bool pinhole = v.camera == "pinhole", quilt = !o.quilt.empty();
  camera_desc_rules(v, quilt, true);
  if (o.sample_at == "tachyon" && (!pinhole || o.spp != 1))
    throw std::invalid_argument("--sample-at tachyon: goes with --camera pinhole and one sample per pixel");
  // The cache's cells are sized in lens pitches (a display whose lenses are
  // whole pixels has them too: checked again once the camera is placed).
  if (cache_enabled(o.cache) && (pinhole || quilt || !v.looking_glass.empty()))
    throw std::invalid_argument("--cache: goes with the integral camera (its cells are sized in lens pitches)");
  const std::optional<double> focus = std::isnan(o.focus_distance) ? std::nullopt : std::optional(o.focus_distance);
  if (focus && pinhole)
    throw std::invalid_argument("--focus-distance: goes with a lens array, a display, --quilt or --looking-glass (the plane they stand at or focus on)");
  if (focus && !o.origin.empty())
    throw std::invalid_argument("--focus-distance: places by the viewpoint; --origin places explicitly: give one of them");
  if (!v.looking_glass.empty()) return api::LookingGlass{v.looking_glass, v.looking_glass_views, focus};
  if (!v.display.empty()) return api::Display{v.display, placement_of(o.origin, o.normal, o.up), focus};
  if (quilt) {
    api::Quilt q;
    parse_lens_count(o.quilt, q.columns, q.rows, "--quilt");
    q.view_cone_deg = o.view_cone;
    if (!v.resolution.empty()) parse_resolution(v.resolution, q.view_width, q.view_height);
    if (o.quilt_view >= q.columns * q.rows)
      throw std::invalid_argument(fmt::format("--quilt-view: a {}x{} quilt has views 0 to {}, got {}", q.columns, q.rows,
                                              q.columns * q.rows - 1, o.quilt_view));
    q.view = o.quilt_view;
    q.focus_distance = focus;
    return q;
  }
  if (!o.shift.empty() && !pinhole) throw std::invalid_argument("--shift: goes with --camera pinhole (a lens shift)");
  if (pinhole) {
    api::Pinhole p;
    if (!v.resolution.empty()) parse_resolution(v.resolution, p.width, p.height);
    p.tachyon_samples = o.sample_at == "tachyon";
    if (!o.shift.empty()) std::tie(p.shift_x, p.shift_y) = parse_shift(o.shift);
    return p;
  }
  api::LensArray a = lens_array_of(o);
  a.focus_distance = focus;
  return a;
}

namespace {

// The summary `render` prints: the scene, the camera, the times and rays.
void print_summary(const RenderCommandOptions& o, const api::Scene& scene, const api::Renderer& renderer,
                   const api::Result& result, double parse_s, double gather_s, double band_bytes, const std::string& output,
                   double write_s, const cluster::World& world) {
  const auto count = [](size_t n, const char* what) { return fmt::format("{} {}{}", n, what, n == 1 ? "" : "s"); };
  const size_t skipped = renderer.skipped_polygons();
  fmt::print("scene      {}: {}, {}{}\n", o.scene, count(scene.object_count(), "object"), count(scene.light_count(), "light"),
             skipped ? fmt::format(" ({} skipped)", count(skipped, "zero-area polygon")) : "");
  fmt::print("{}", renderer.describe());
  const api::RenderStats& st = result.stats;
  const std::string gpu = renderer.device_name();
  if (!gpu.empty())
    fmt::print("preprocess {:.3f} s (parse {:.3f} s, build {:.3f} s, GPU set-up {:.3f} s)\n", parse_s + st.build_seconds,
               parse_s, st.build_seconds - st.gpu_setup_seconds, st.gpu_setup_seconds);
  else
    fmt::print("preprocess {:.3f} s (parse {:.3f} s, build {:.3f} s)\n", parse_s + st.build_seconds, parse_s, st.build_seconds);
  const double per_ray = st.rays.total() ? 1.0 / double(st.rays.total()) : 0.0;
  if (!gpu.empty())
    fmt::print("trace      {:.3f} s on {}, {} spp (readback {:.3f} s; {:.1f} nodes and {:.1f} primitives per ray)\n",
               st.trace_seconds, gpu, o.spp, st.readback_seconds, double(st.nodes_visited) * per_ray,
               double(st.primitives_tested) * per_ray);
  else
    fmt::print("trace      {:.3f} s, {} spp, {} threads, {}{}\n", st.trace_seconds, o.spp,
             o.threads > 0 ? o.threads : tbb::this_task_arena::max_concurrency(),
             o.light.integrator == "path"
                 ? std::string("path integrator") +
                       (o.seed != 0 ? fmt::format(", seed {}", o.seed) : "") +
                       (o.share_views > 0 ? fmt::format(", views sharing samples with {} on each side", o.share_views) : "")
                 : fmt::format("{} style", renderer.style_name()),
             world.distributed() ? fmt::format(" per rank; {} ranks, bands of rows, wall time with the gather in {:.3f} s ({:.1f} MiB)",
                                               world.size(), gather_s, band_bytes / 1048576.0)
                                 : "");
  const api::RayCounts& r = st.rays;
  fmt::print("rays       eye {}, shadow {}, reflected {}, refracted {}; total {}, {:.2f} Mrays/s\n", r.eye, r.shadow,
             r.reflected, r.refracted, r.total(), st.trace_seconds > 0 ? r.total() / st.trace_seconds / 1e6 : 0.0);
  fmt::print("{}", result.cache_summary);
  fmt::print("wrote      {} ({:.3f} s{})\n", output, world.distributed() ? gather_s : write_s,
             world.distributed() ? ", gathering the bands" : "");
}

}  // namespace

int run_render(const RenderCommandOptions& o, const cluster::World& world) {
  bool rendering = false;  // past setup: an error now stops every rank (World::fail)
  try {
    // Everything the user typed is checked before the scene is read.
    const api::Encoding encoding = parse_encoding(o.encoding, o.scene);
    const api::ExrCompression exr = parse_exr_compression(o.exr_compression);
    const api::Aovs aovs = o.aovs.empty() ? api::Aovs{} : parse_aovs(o.aovs);
    const api::Style style = parse_style(o.style);
    const api::Camera camera = camera_of(o);
    std::unique_ptr<tbb::global_control> thread_cap;
    if (o.threads > 0)
      thread_cap = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, o.threads);

    const auto t_parse = Clock::now();
    api::Scene scene = api::Scene::load(o.scene, {o.camera_name, o.texture_paths});
    if (!o.light.lights.empty()) scene.add_lights(o.light.lights);
    const double parse_s = seconds_since(t_parse);
    if (!o.quiet) print_scene_warnings(scene.warnings(), scene.warning_count(), o.scene);

    api::RenderOptions ropt;
    ropt.spp = o.spp;
    ropt.threads = o.threads;
    ropt.max_depth = o.max_depth;
    const LightChoice light = light_choice(o.light);
    ropt.integrator = light.integrator;
    ropt.environment = light.environment;
    ropt.blender_principled = light.blender_principled;
    if (o.share_views > 0 && light.integrator != api::Integrator::path)
      throw std::invalid_argument("--share-views: views share path samples: go with --integrator path");
    if (o.share_views > 0 && o.device != "cpu")
      throw std::invalid_argument("--share-views: views share their samples on the CPU only: leave --device at cpu");
    ropt.share_views = o.share_views;
    if (o.seed != 0 && light.integrator != api::Integrator::path)
      throw std::invalid_argument("--seed: Whitted's integrator draws no random samples: go with --integrator path");
    ropt.seed = static_cast<uint32_t>(o.seed);
    ropt.aovs = aovs;
    ropt.style = style;
    // Several ranks on a machine share its GPUs out, one each in turn.
    ropt.device = world.distributed() ? api::device_of_local_rank(o.device, world.local_rank()) : o.device;
    ropt.cache = cache_options(o.cache);
    ropt.count_work = true;  // a still's summary gives the GPU's nodes and primitives per ray
    // Under mpirun: bands of whole lens rows of an EIA, else rows of 32 (the
    // line renderers' tile); the image never depends on them. A rank holds
    // only its own bands, rank 0 one band more (cluster/band_exchange.hpp),
    // each copied once as it is written.
    std::vector<RowBand> bands;
    if (world.distributed())
      ropt.memory_share = [&](int height, int band_rows) {
        bands = row_bands(height, band_rows, world.size());
        int64_t own = 0, largest = 0;
        for (const RowBand& b : bands) {
          largest = std::max<int64_t>(largest, b.y1 - b.y0);
          if (b.rank == world.rank()) own += b.y1 - b.y0;
        }
        const int64_t held = own + (world.rank() == 0 ? largest : 0);
        return api::MemoryShare{held, largest,
                                held < height ? fmt::format(" on rank {} of {}", world.rank(), world.size()) : ""};
      };
    const bool tty = !o.quiet && !o.progress_lines && world.rank() == 0 && ::isatty(STDERR_FILENO);
    std::mutex progress_mutex;
    int shown = -1;
    if (tty || o.progress_lines)
      ropt.progress = [&](double f) {
        const int pct = static_cast<int>(f * 100);
        // Every percent for a program that reads them; a terminal's counter may skip one.
        std::unique_lock lock(progress_mutex, std::defer_lock);
        if (o.progress_lines) lock.lock();
        else if (!lock.try_lock()) return;
        if (o.progress_lines ? pct <= shown : pct == shown) return;
        shown = pct;
        if (o.progress_lines) std::fprintf(stderr, "progress %.2f\n", pct / 100.0);
        else std::fprintf(stderr, "\rtracing %3d%%", pct);
        std::fflush(stderr);
      };
    const api::Renderer renderer(scene, camera, ropt);
    const int width = renderer.width(), height = renderer.height();

    if (!world.agree(true, "")) return 1;
    rendering = true;
    // A quilt's name tells Looking Glass tools its layout.
    const auto* quilt = std::get_if<api::Quilt>(&camera);
    const std::string output =
        quilt && quilt->view < 0 ? api::quilt_file_name(o.output, {quilt->columns, quilt->rows, quilt->view_width,
                                                                   quilt->view_height, quilt->view_cone_deg})
                                 : o.output;
    api::Result result;
    double gather_s = 0, band_bytes = 0, write_s = 0;
    if (world.distributed()) {
      // Bands of rows dealt round robin (cluster/row_bands.hpp); each rank
      // traces its own, rank 0 writes them to the files in order as they
      // arrive (the gather time includes those writes).
      const auto t_trace = Clock::now();
      std::vector<api::Result> mine;
      for (const RowBand& b : bands) {
        if (b.rank != world.rank()) continue;
        const api::Result band = renderer.render(std::array<int, 2>{b.y0, b.y1});
        mine.push_back(band);
        api::RayCounts& r = result.stats.rays;
        const api::RayCounts& n = band.stats.rays;
        r.eye += n.eye, r.shadow += n.shadow, r.reflected += n.reflected, r.refracted += n.refracted;
        r.shadow_cached += n.shadow_cached, r.cache_samples += n.cache_samples;
        result.cache_summary = band.cache_summary;
      }
      result.stats.build_seconds = renderer.build_stats().build_seconds;
      result.stats.gpu_setup_seconds = renderer.build_stats().gpu_setup_seconds;
      const auto t_gather = Clock::now();
      std::optional<FrameFiles> files;
      if (world.rank() == 0) files.emplace(output, width, height, aovs, encoding, exr);
      cluster::stream_bands(world, bands, mine, width, aovs, [&](const RowBand&, const api::Result& b) { files->write(b); },
                            band_bytes);
      if (files) files->finish();
      gather_s = seconds_since(t_gather);
      result.stats.trace_seconds = seconds_since(t_trace);
      api::RayCounts& r = result.stats.rays;
      for (uint64_t* n : {&r.eye, &r.shadow, &r.reflected, &r.refracted, &r.shadow_cached, &r.cache_samples})
        *n = static_cast<uint64_t>(world.sum(static_cast<int64_t>(*n)));
      band_bytes = world.sum(band_bytes);
      if (world.rank() != 0) return 0;
      if (tty) std::fprintf(stderr, "\r             \r");
    } else {
      result = renderer.render();
      if (tty) std::fprintf(stderr, "\r             \r");
      const auto t_write = Clock::now();
      FrameFiles files(output, width, height, aovs, encoding, exr);
      files.write(result);
      files.finish();
      write_s = seconds_since(t_write);
    }
    if (!o.quiet) print_summary(o, scene, renderer, result, parse_s, gather_s, band_bytes, output, write_s, world);
    return 0;
  } catch (const std::exception& e) {
    return world.fail(error_report(e), rendering);
  }
}

}  // namespace holoray::cli
