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

#include "camera/placement.hpp"
#include "camera/quilt_camera.hpp"
#include "display/display_file.hpp"
#include "display/display_placement.hpp"
#include "display/looking_glass.hpp"
#include "cli/machine.hpp"
#include "cli/option_parsing.hpp"
#include "cli/validators.hpp"
#include "cluster/band_exchange.hpp"
#include "cluster/mpi_world.hpp"
#include "cluster/row_bands.hpp"
#include "cli/scene_warnings.hpp"
#include "image/image_io.hpp"
#include "render/frame_camera.hpp"
#include "render/renderer.hpp"
#include "scene/mesh_reader.hpp"
#include "scene/nff_reader.hpp"
#include "scene/parse_error.hpp"

namespace holoray::cli {

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// The colour file and its AOV files (aov_path: albedo beside it in its
// format, depth, normal and id as EXR), written band by band, top to bottom:
// whole in one process, as the bands arrive under mpirun.
class FrameFiles {
 public:
  FrameFiles(const std::string& output, int width, int height, const AovSet& aovs, Encoding encoding) {
    const std::string ext = std::filesystem::path(output).extension().string().substr(1);
    const FrameBuffers shape = allocate_frame(width, 1, aovs);  // each plane's channels
    auto add = [&](ImageBuffer FrameBuffers::*plane, const std::string& path, Encoding enc) {
      files_.emplace_back(plane, std::make_unique<ImageWriter>(path, width, height, (shape.*plane).channels, enc));
    };
    add(&FrameBuffers::colour, output, encoding);
    if (aovs.albedo) add(&FrameBuffers::albedo, aov_path(output, "albedo", ext), encoding);
    if (aovs.depth) add(&FrameBuffers::depth, aov_path(output, "depth", "exr"), Encoding::linear);
    if (aovs.normal) add(&FrameBuffers::normal, aov_path(output, "normal", "exr"), Encoding::linear);
    if (aovs.id) add(&FrameBuffers::id, aov_path(output, "id", "exr"), Encoding::linear);
  }
  /// The next rows of every file.
  void write(const FrameBuffers& rows) {
    for (auto& [plane, writer] : files_) writer->write_rows(rows.*plane);
  }
  void finish() {
    for (auto& [plane, writer] : files_) writer->finish();
  }

 private:
  std::vector<std::pair<ImageBuffer FrameBuffers::*, std::unique_ptr<ImageWriter>>> files_;
};

// The lens array the options describe (each value checked by CLI11).
ArraySettings resolve_settings(const RenderCommandOptions& o) {
  ArraySettings s;
  s.grid = parse_grid(o.grid);
  s.mode = o.mode == "pseudoscopic" ? RecordingMode::pseudoscopic : RecordingMode::orthoscopic;
  parse_lens_count(o.lenses, s.lenses_x, s.lenses_y);
  s.pixels_per_lens = o.pixels_per_lens;
  s.rows = o.rows;
  if (!std::isnan(o.pitch)) s.pitch = o.pitch;
  if (!std::isnan(o.gap)) s.gap = o.gap;
  if (!std::isnan(o.fov_lens)) s.fov_lens_deg = o.fov_lens;
  s.view_distance = o.view_distance;
  if (!o.origin.empty()) s.origin = parse_vec3("--origin", o.origin);
  if (!o.normal.empty()) s.normal = parse_vec3("--normal", o.normal);
  if (!o.up.empty()) s.up = parse_vec3("--up", o.up);
  return s;
}

// A CLI11 check of an X,Y,Z option.
CLI::Validator vec3(const char* option) {
  return parsed_by([option](const std::string& t) { parse_vec3(option, t); }, "X,Y,Z");
}

}  // namespace

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
  CLI::Option* array_options[] = {
      cmd->add_option("--grid", o.grid, "Lens grid")->check(one_of({"square", "hex", "lenticular"}))->capture_default_str(),
      cmd->add_option("--lenses", o.lenses, "Lens count NXxNY (lenticular: NY unused)")
          ->check(parsed_by([](const std::string& t) { int x, y; parse_lens_count(t, x, y); }, "NXxNY"))
          ->capture_default_str(),
      cmd->add_option("--pixels-per-lens", o.pixels_per_lens, "Pixels across one lens (P)")->check(in_range(1))->capture_default_str(),
      cmd->add_option("--rows", o.rows, "Image rows H for hex and lenticular (default: the contract's)")->check(in_range(1)),
      cmd->add_option("--fov-lens", o.fov_lens, "Lens field of view in degrees (default 20); sets the gap"),
      cmd->add_option("--gap", o.gap, "Lens plane to pixel panel distance, scene units"),
      cmd->add_option("--pitch", o.pitch, "Lens pitch, scene units (default: NFF view width / NX)"),
      cmd->add_option("--mode", o.mode, "orthoscopic (display-ready) or pseudoscopic (direct pickup)")
          ->check(one_of({"orthoscopic", "pseudoscopic"}))
          ->capture_default_str(),
      cmd->add_option("--view-distance", o.view_distance, "Lenticular vertical perspective distance V (default: infinite)")};
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
  cmd->add_option("--quilt-view", o.quilt_view, "With --quilt: render only view K (0 = leftmost) as a plain image, named as -o says")
      ->check(in_range(0))
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
  cmd->add_option("--threads", o.threads, "Worker threads (0: all cores)")->check(in_range(0))->capture_default_str();
  cmd->add_option("--max-depth", o.max_depth, "Ray-tree depth limit, eye ray = 1 (default: the scene's Tachyon raydepth, else 5, the SPD's)")
      ->check(in_range(1, kDepthCap));
  cmd->add_option("--style", o.style, "Pixel-tracing style: subaperture (16-ray packets of one pixel of 4x4 lenses), packet (16-ray packets of 4x4 pixels of one lens), horizontal or vertical (single rays, paper §6); auto picks the faster packets for the array")
      ->check(one_of({"auto", "subaperture", "packet", "horizontal", "vertical"}))
      ->capture_default_str();
  cmd->add_option("--aov", o.aovs, "Extra outputs, comma-separated: albedo,depth,normal,id")
      ->check(parsed_by([](const std::string& t) { parse_aovs(t); }, "LIST"));
  cmd->add_option("--encoding", o.encoding, "PNG encoding: linear, srgb, or auto (srgb for a mesh scene, linear for NFF and Tachyon)")
      ->check(one_of({"auto", "linear", "srgb"}))
      ->capture_default_str();
  add_cache_options(*cmd, o.cache);
  cmd->add_flag("-q,--quiet", o.quiet, "Print nothing but errors");
  lay_out_help(*cmd,
               {{"Output", {"--output", "--aov", "--encoding", "--quiet"}},
                {"Camera", {"--camera", "--resolution", "--sample-at", "--display", "--looking-glass", "--views", "--quilt",
                            "--view-cone", "--quilt-view"}},
                {"Lens array", {"--grid", "--lenses", "--pixels-per-lens", "--rows", "--fov-lens", "--gap", "--pitch", "--mode",
                                "--view-distance", "--origin", "--normal", "--up"}},
                {"Tracing", {"--spp", "--threads", "--max-depth", "--style", "--cache", "--cache-cell", "--cache-memory"}}},
               {"holoray render examples/primitives.nff --grid hex --lenses 48x48 --pixels-per-lens 10 -o eia.png",
                "holoray render examples/primitives.nff --display examples/displays/lenticular_4k.toml -o panel.png"},
               "docs/guide/stills.md, docs/guide/displays.md");
  return cmd;
}

namespace {

using Kind = FrameCameraDesc::Kind;

// The camera the options name, with the rules between options that CLI11
// cannot say (each value it checked already).
FrameCameraDesc camera_choice_of(const RenderCommandOptions& o) {
  FrameCameraDesc c = camera_desc(o.view, !o.quilt.empty(), true);
  c.array = resolve_settings(o);
  if (c.kind == Kind::quilt) {
    QuiltDesc& q = c.quilt;
    parse_lens_count(o.quilt, q.columns, q.rows, "--quilt");
    q.view_cone_deg = o.view_cone;
    if (c.width > 0) q.view_width = c.width, q.view_height = c.height;
    if (o.quilt_view >= q.columns * q.rows)
      throw std::invalid_argument(fmt::format("--quilt-view: a {}x{} quilt has views 0 to {}, got {}", q.columns, q.rows,
                                              q.columns * q.rows - 1, o.quilt_view));
    c.quilt_view = o.quilt_view;
  }
  c.tachyon_samples = o.sample_at == "tachyon";
  if (c.tachyon_samples && (c.kind != Kind::pinhole || o.spp != 1))
    throw std::invalid_argument("--sample-at tachyon: goes with --camera pinhole and one sample per pixel");
  // The cache's cells are sized in lens pitches (a display whose lenses are
  // whole pixels has them too: checked again once the camera is placed).
  if (cache_enabled(o.cache) && c.kind != Kind::integral && c.kind != Kind::display)
    throw std::invalid_argument("--cache on: goes with the integral camera (its cells are sized in lens pitches)");
  return c;
}

// Refuses, before anything is allocated, an image whose buffers would not
// fit in 80% of memory: the frame and its AOVs, the 8-bit or float copy
// made on output, and a panel's samples (three per pixel with subpixels).
// Under mpirun a rank holds only its own `bands`, rank 0 one band more
// (cluster/band_exchange.hpp), each copied once as it is written.
void refuse_if_too_large(const FrameCamera& camera, const AovSet& aovs, const cluster::World& world,
                         const std::vector<RowBand>& bands) {
  const int width = camera.width(), height = camera.height();
  const int64_t pixels = static_cast<int64_t>(width) * height;
  int64_t samples = static_cast<int64_t>(camera.panel_samples_per_row()) * height;
  int64_t held = pixels, copied = pixels;
  if (world.distributed()) {
    int64_t own = 0, largest = 0;
    for (const RowBand& b : bands) {
      largest = std::max<int64_t>(largest, b.y1 - b.y0);
      if (b.rank == world.rank()) own += b.y1 - b.y0;
    }
    held = (own + (world.rank() == 0 ? largest : 0)) * width;
    copied = largest * width;
    samples = samples / height * (held / width);
  }
  const uint64_t need = frame_bytes(held, aovs) + static_cast<uint64_t>(copied) * 12 + frame_bytes(samples, aovs);
  const uint64_t have = physical_memory_bytes();
  if (have && need > have / 10 * 8)
    throw std::length_error(fmt::format("a {}x{} image needs {:.2f} GiB of buffers{}, more than 80% of this machine's {:.2f} GiB",
                                        width, height, need / 1073741824.0,
                                        held < pixels ? fmt::format(" on rank {} of {}", world.rank(), world.size()) : "",
                                        have / 1073741824.0));
}

// What happened, for the printed summary.
struct RenderRun {
  double parse_s = 0, build_s = 0, write_s = 0, gather_s = 0, band_bytes = 0;
  std::string output;
  TraceStyle style = TraceStyle::packet;
  RenderStats stats;
};

// The summary `render` prints: the scene, the camera, the times and rays.
void print_summary(const RenderCommandOptions& o, const SceneDesc& desc, const RenderScene& scene,
                   const FrameCameraDesc& choice, const FrameCamera& camera, const ShadowCache* cache,
                   const RenderRun& run, const cluster::World& world) {
  const int width = camera.width(), height = camera.height();
  const auto count = [](size_t n, const char* what) { return fmt::format("{} {}{}", n, what, n == 1 ? "" : "s"); };
  fmt::print("scene      {}: {}, {}{}\n", o.scene, count(desc.objects.size(), "object"), count(desc.lights.size(), "light"),
             scene.skipped_polygons() ? fmt::format(" ({} skipped)", count(scene.skipped_polygons(), "zero-area polygon")) : "");
  if (camera.glass) {
    fmt::print("panel      {}x{} px, Looking Glass ({}): RGB subpixels, each along its lenticule's view, view cone {:.4g} deg\n",
               width, height, o.view.looking_glass, camera.glass->calibration().view_cone_deg);
  } else if (camera.quilt) {
    const QuiltDesc& q = camera.quilt->desc();
    fmt::print("quilt      {}x{} px: {}x{} views of {}x{} px, view cone {:.4g} deg, sheared frusta on the viewpoint's focal plane\n",
               width, height, q.columns, q.rows, q.view_width, q.view_height, q.view_cone_deg);
  } else if (choice.kind == Kind::quilt) {
    const QuiltDesc& q = choice.quilt;
    fmt::print("view       {}x{} px, quilt view {} of {}x{} (view cone {:.4g} deg)\n", width, height, o.quilt_view, q.columns,
               q.rows, q.view_cone_deg);
  } else if (choice.kind == Kind::pinhole) {
    fmt::print("view       {}x{} px, pinhole, field of view {:.4g} deg (the scene's viewpoint)\n", width, height,
               camera.view->desc().fov_deg);
  } else if (camera.panel) {
    const DisplayDesc& d = *choice.display;
    const DisplayGeometry& g = camera.panel->geometry();
    fmt::print("panel      {}x{} px, {} ({} per pixel), {} grid{}, {}\n", width, height,
               d.subpixels == SubpixelOrder::none ? "whole pixels" : fmt::format("{} subpixels", to_string(d.subpixels)),
               d.samples_per_pixel() == 1 ? "one line" : "three lines", to_string(d.grid),
               d.slant_deg != 0 ? fmt::format(" slanted {:.4g} deg", d.slant_deg) : "", to_string(d.mode));
    fmt::print("lenses     pitch {:.6g} mm ({:.6g} px across a row), gap {:.6g} mm; {:.6g} scene units per mm\n",
               d.pitch_mm, d.pixels_per_lens(), d.gap_mm, g.pixel_pitch / d.pixel_pitch_mm);
  } else {
    if (choice.display) fmt::print("display    {}: whole pixels per lens, rendered as the EIA below\n", o.view.display);
    const LensArray& a = *camera.array;
    const LensArrayDesc& d = a.desc();
    fmt::print("EIA        {}x{} px, {} grid, {}x{} lenses x {} px, {}\n", width, height, to_string(d.grid),
               a.lens_count_x(), a.lens_count_y(), d.pixels_per_lens, to_string(d.mode));
    fmt::print("lenses     pitch {:.6g}, gap {:.6g}, field of view {:.4g} deg\n", d.pitch, d.gap, a.lens_fov_deg());
  }
  fmt::print("preprocess {:.3f} s (parse {:.3f} s, build {:.3f} s)\n", run.parse_s + run.build_s, run.parse_s, run.build_s);
  fmt::print("trace      {:.3f} s, {} spp, {} threads, {} style{}\n", run.stats.trace_seconds, o.spp,
             o.threads > 0 ? o.threads : tbb::this_task_arena::max_concurrency(), to_string(run.style),
             world.distributed() ? fmt::format(" per rank; {} ranks, bands of rows, wall time with the gather in {:.3f} s ({:.1f} MiB)",
                                               world.size(), run.gather_s, run.band_bytes / 1048576.0)
                                 : "");
  const RayCounts& r = run.stats.rays;
  fmt::print("rays       eye {}, shadow {}, reflected {}, refracted {}; total {}, {:.2f} Mrays/s\n", r.eye, r.shadow,
             r.reflected, r.refracted, r.total(), run.stats.trace_seconds > 0 ? r.total() / run.stats.trace_seconds / 1e6 : 0.0);
  if (cache) fmt::print("{}", cache_summary(*cache, r, o.cache));
  fmt::print("wrote      {} ({:.3f} s{})\n", run.output, world.distributed() ? run.gather_s : run.write_s,
             world.distributed() ? ", gathering the bands" : "");
}

}  // namespace

int run_render(const RenderCommandOptions& o, const cluster::World& world) {
  bool rendering = false;  // past setup: an error now stops every rank (World::fail)
  try {
    // Everything the user typed is checked before the scene is read.
    const Encoding encoding = parse_encoding(o.encoding, o.scene);
    const AovSet aovs = o.aovs.empty() ? AovSet{} : parse_aovs(o.aovs);
    const std::optional<TraceStyle> style = parse_style(o.style);
    const FrameCameraDesc choice = camera_choice_of(o);
    std::unique_ptr<tbb::global_control> thread_cap;
    if (o.threads > 0)
      thread_cap = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, o.threads);

    RenderRun run;
    const auto t_parse = Clock::now();
    const SceneDesc desc = read_scene_file(o.scene);
    run.parse_s = seconds_since(t_parse);
    if (!o.quiet) print_scene_warnings(desc);

    const FrameCamera camera = make_frame_camera(choice, desc.viewpoint, o.scene);
    if ((camera.panel || camera.glass) && (aovs.albedo || aovs.depth || aovs.normal || aovs.id))
      throw std::invalid_argument("--aov: not written for native panel images yet (colour only)");
    if (!camera.array && cache_enabled(o.cache))
      throw std::invalid_argument("--cache on: goes with the integral camera (its cells are sized in lens pitches)");
    const int width = camera.width(), height = camera.height();
    // Under mpirun: bands of whole lens rows of an EIA, else rows of 32 (the
    // line renderers' tile); the image never depends on them.
    const std::vector<RowBand> bands =
        world.distributed() ? row_bands(height, camera.array ? camera.array->desc().pixels_per_lens : 32, world.size())
                            : std::vector<RowBand>{};
    refuse_if_too_large(camera, aovs, world, bands);

    const auto t_build = Clock::now();
    RenderScene scene(desc);
    if (o.max_depth != 0) scene.set_max_depth(o.max_depth);
    // Mesh textures take the MIP level of what one pixel sees.
    if (const auto angle = camera.pixel_angle()) scene.set_pixel_footprint(0, *angle);
    const std::unique_ptr<ShadowCache> cache = camera.array ? make_cache(scene, camera.array->desc().pitch, o.cache) : nullptr;
    scene.set_shadow_cache(cache.get());
    run.build_s = seconds_since(t_build);

    if (!world.agree(true, "")) return 1;
    rendering = true;
    const bool tty = !o.quiet && world.rank() == 0 && ::isatty(STDERR_FILENO);
    std::mutex progress_mutex;
    int shown = -1;
    RenderOptions ropt;
    ropt.spp = o.spp;
    ropt.threads = o.threads;
    ropt.aovs = aovs;
    ropt.style = style ? *style : camera.array ? preferred_style(camera.array->desc()) : TraceStyle::packet;
    run.style = ropt.style;
    if (tty)
      ropt.progress = [&](double f) {
        std::unique_lock lock(progress_mutex, std::try_to_lock);
        const int pct = static_cast<int>(f * 100);
        if (!lock.owns_lock() || pct == shown) return;
        shown = pct;
        std::fprintf(stderr, "\rtracing %3d%%", pct);
        std::fflush(stderr);
      };
    // The whole image, or one band of its rows.
    auto render_rows = [&](std::optional<std::array<int, 2>> rows, RenderStats& st) {
      RenderOptions ro = ropt;
      ro.rows = rows;
      return render_through(scene, camera, ro, st);
    };
    // A quilt's name tells Looking Glass tools its layout.
    run.output = camera.quilt ? quilt_file_name(o.output, camera.quilt->desc()) : o.output;
    if (world.distributed()) {
      // Bands of rows dealt round robin (cluster/row_bands.hpp); each rank
      // traces its own, rank 0 writes them to the files in order as they
      // arrive (the gather time includes those writes).
      const auto t_trace = Clock::now();
      std::vector<FrameBuffers> mine;
      RenderStats band_stats;
      for (const RowBand& b : bands) {
        if (b.rank != world.rank()) continue;
        mine.push_back(render_rows(std::array<int, 2>{b.y0, b.y1}, band_stats));
        run.stats.rays += band_stats.rays;
      }
      const auto t_gather = Clock::now();
      std::optional<FrameFiles> files;
      if (world.rank() == 0) files.emplace(run.output, width, height, aovs, encoding);
      cluster::stream_bands(world, bands, mine, width, aovs, [&](const RowBand&, const FrameBuffers& b) { files->write(b); },
                            run.band_bytes);
      if (files) files->finish();
      run.gather_s = seconds_since(t_gather);
      run.stats.trace_seconds = seconds_since(t_trace);
      RayCounts& r = run.stats.rays;
      for (uint64_t* n : {&r.eye, &r.shadow, &r.reflected, &r.refracted, &r.shadow_cached, &r.cache_samples})
        *n = static_cast<uint64_t>(world.sum(static_cast<int64_t>(*n)));
      run.band_bytes = world.sum(run.band_bytes);
      if (world.rank() != 0) return 0;
      if (tty) std::fprintf(stderr, "\r             \r");
    } else {
      const FrameBuffers fb = render_rows(std::nullopt, run.stats);
      if (tty) std::fprintf(stderr, "\r             \r");
      const auto t_write = Clock::now();
      FrameFiles files(run.output, width, height, aovs, encoding);
      files.write(fb);
      files.finish();
      run.write_s = seconds_since(t_write);
    }
    if (!o.quiet) print_summary(o, desc, scene, choice, camera, cache.get(), run, world);
    return 0;
  } catch (const ParseError& e) {
    return world.fail(e.what(), rendering);
  } catch (const std::exception& e) {
    return world.fail(fmt::format("holoray: error: {}", e.what()), rendering);
  }
}

}  // namespace holoray::cli
