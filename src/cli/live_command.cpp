#include "cli/live_command.hpp"

#include "cli/light_options.hpp"

#include <fmt/format.h>

#include "cli/devices_command.hpp"
#include "cli/error_words.hpp"
#include "cli/interrupt.hpp"
#include "cli/light_options.hpp"
#include "cli/option_parsing.hpp"
#include "cli/scene_warnings.hpp"
#include "cli/validators.hpp"
#include "holoray/holoray.hpp"

namespace holoray::cli {

CLI::App* add_live_command(CLI::App& app, LiveCommandOptions& o) {
  RenderCommandOptions& r = o.camera;
  r.device = "gpu";
  CLI::App* cmd = app.add_subcommand(
      "live", "Show the scene in a window, rendered on the GPU path as fast as the device renders it: the EIA (or its centre "
              "sub-aperture view), a pinhole view, or a display's or Looking Glass's panel image full screen; the mouse and "
              "keys move the view, the array's plane and the lenses");
  CLI::Option* scene = cmd->add_option("scene", r.scene, "Scene file: NFF (.nff), Tachyon (.dat), or a mesh through assimp (.obj, .ply, .stl, .gltf, .glb, .3ds, .dae, .ac)")
      ->check(existing_file());
  CLI::Option* shot = cmd->add_option("--shot", o.shot, "An animated shot (TOML, docs/shot-format.md) instead of a scene: Space plays it in real time, PageDown and PageUp step a frame; its [array] is the camera unless --camera pinhole, --display or --looking-glass is given")
      ->check(existing_file())
      ->excludes(scene);
  cmd->add_flag("--play", o.play, "With --shot: play it from the start")->needs(shot);
  const auto [display, lg] = add_camera_options(*cmd, r.view, "the image");
  for (CLI::Option* a : add_lens_array_options(*cmd, r)) display->excludes(a), lg->excludes(a), shot->excludes(a);
  add_focus_distance_option(*cmd, r);
  add_scene_read_options(*cmd, r.camera_name, r.texture_paths);
  add_device_option(*cmd, r.device, "live renders on the GPU path only");
  cmd->add_option("--spp", r.spp, "Samples per pixel (jittered inside the pixel)")->check(in_range(1))->capture_default_str();
  cmd->add_option("--max-depth", r.max_depth, "Ray-tree depth limit, eye ray = 1 (default: the scene's Tachyon raydepth, else 5, the SPD's)")
      ->check(in_range(1, api::kMaxDepth));
  add_light_options(*cmd, r.light, true);
  cmd->get_option("--lights")->excludes(shot);
  cmd->add_option("--max-spp", o.max_spp, "With --integrator path: while the view stands still, each frame adds --spp samples to the last, up to this many per pixel (0: every frame its --spp alone)")
      ->check(in_range(0))
      ->capture_default_str();
  cmd->add_option("--encoding", r.encoding, "8-bit encoding shown and written: linear, srgb, or auto (srgb for a mesh scene, linear for NFF and Tachyon), as render's PNGs")
      ->check(one_of({"auto", "linear", "srgb"}))
      ->capture_default_str();
  cmd->add_flag("--simulate", o.simulate, "With --display: show what an eye sees through the display (as holoray simulate) from where the pointer is over the panel; the wheel moves the eye nearer or farther (600 mm at first)")
      ->needs(display);
  cmd->add_option("--monitor", o.monitor, "The monitor to open on, by index (0, 1, ...) or name; a display's panel is one of them (default: the primary)");
  CLI::Option* full = cmd->add_flag("--fullscreen", o.fullscreen, "Full screen on the monitor, at its mode (the default for a display or Looking Glass)");
  cmd->add_flag("--windowed", o.windowed, "In a window the image's size (the default for a lens array or a pinhole view)")->excludes(full);
  CLI::Option* exit_after =
      cmd->add_option("--exit-after", o.exit_after, "Close after N frames shown (0: when the window is closed)")->check(in_range(0))->capture_default_str();
  cmd->add_flag("--offscreen", o.offscreen, "No window: each frame traced, packed and copied on the device as it would be shown, and not presented (no vsync); input from --events; for a machine without a display, and to measure the frame rate there (docs/guide/live.md)")
      ->needs(exit_after)
      ->excludes(full);
  cmd->add_option("--screenshot", o.screenshot, "When the window closes, write the last frame shown: .png as shown (8-bit), .exr its colour in float")
      ->check(output_image());
  cmd->add_option("--events", o.events, "Replay input from FILE: lines 'FRAME orbit|pan DX DY', 'FRAME pointer X Y', 'FRAME wheel CLICKS', 'FRAME key NAME' (docs/guide/live.md)")
      ->check(existing_file());
  cmd->add_option("--record", o.record, "Write every frame shown to DIR as frame_NNNN.png (frames numbered from 0, as animate names them)");
  cmd->add_flag("-q,--quiet", r.quiet, "Print nothing but errors");
  lay_out_help(*cmd,
               {{"Scene", {"--shot", "--play", "--camera-name", "--texture-path"}},
                {"Window", {"--simulate", "--monitor", "--fullscreen", "--windowed", "--offscreen", "--exit-after", "--screenshot", "--events", "--record",
                            "--encoding", "--quiet"}},
                {"Camera", {"--camera", "--resolution", "--display", "--looking-glass", "--views", "--focus-distance"}},
                {"Lens array", {"--grid", "--lenses", "--pixels-per-lens", "--rows", "--fov-lens", "--gap", "--pitch", "--mode",
                                "--view-distance"}},
                {"Tracing", {"--device", "--spp", "--max-spp", "--max-depth"}},
                {"Light", light_option_names(true)}},
               {"holoray live examples/primitives.nff --lenses 64x64 --pixels-per-lens 12",
                "holoray live --shot examples/shots/sliding_primitives.toml --play",
                "holoray live examples/primitives.nff --display examples/displays/lenticular_4k.toml --monitor 1"},
               "docs/guide/live.md");
  cmd->footer(cmd->get_footer() +
              "\nKeys: drag orbits, shift-drag (or the right button) pans, the wheel dollies; Up/Down move the array's "
              "plane farther/nearer, Left/Right narrow/widen the lenses' field of view, A cycles colour and the AOVs, V "
              "toggles the EIA and its centre sub-aperture view, S writes a PNG (shift+S an EXR), Space plays or pauses a shot, "
              "PageDown and PageUp step it, Home resets the view, Escape or Q quits. With --simulate the pointer places the eye "
              "over the panel and the wheel its distance.");
  return cmd;
}

int run_live(const LiveCommandOptions& o) {
  try {
    const RenderCommandOptions& r = o.camera;
    if (r.scene.empty() == o.shot.empty()) {  // a usage error: CLI11 made the two exclusive, not one required
      std::fprintf(stderr, "holoray: error: live: give a scene file, or a shot with --shot FILE\n");
      return 2;
    }
    const api::Camera camera = camera_of(r);
    const CameraOptions& v = r.view;
    api::RenderOptions options;
    options.spp = r.spp;
    options.max_depth = r.max_depth;
    options.device = r.device;
    const LightChoice light = light_choice(r.light);
    options.integrator = light.integrator;
    options.environment = light.environment;
    options.blender_principled = light.blender_principled;
    const StopOnSignal interrupt;
    api::LiveOptions live;
    live.monitor = o.monitor;
    if (o.fullscreen) live.fullscreen = true;
    if (o.windowed) live.fullscreen = false;
    live.exit_after = o.exit_after;
    live.offscreen = o.offscreen;
    live.screenshot = o.screenshot;
    live.events = o.events;
    live.record = o.record;
    if (r.encoding != "auto") live.encoding = parse_encoding(r.encoding);
    live.play = o.play;
    live.simulate = o.simulate;
    live.max_spp = o.max_spp;
    if (!r.quiet) live.print = [](const std::string& line) { fmt::print("{}\n", line); };
    live.stop = [&] { return interrupt.requested(); };
    api::LiveResult result;
    if (!o.shot.empty()) {
      // The shot's [array] is its camera unless another kind was asked for (as animate).
      const bool other = v.camera == "pinhole" || !v.display.empty() || !v.looking_glass.empty();
      result = api::run_live_shot(o.shot, other ? std::optional(camera) : std::nullopt, options, live);
    } else {
      api::Scene scene = api::Scene::load(r.scene, {r.camera_name, r.texture_paths});
      if (!r.light.lights.empty()) scene.add_lights(r.light.lights);
      if (!r.quiet) print_scene_warnings(scene.warnings(), scene.warning_count(), r.scene);
      result = api::run_live(scene, camera, options, live);
    }
    if (!r.quiet) {
      fmt::print("view       {}\n", result.view);
      if (!o.shot.empty()) fmt::print("shot       frame {}\n", result.shot_frame);
      if (o.simulate) fmt::print("simulate   eye {} mm, {} px wide\n", result.eye_mm, result.simulated_width);
      fmt::print("frames     {} shown in {:.3f} s{}\n", result.frames, result.seconds,
                 result.frames > 1 ? fmt::format(" ({:.3g} fps)", (result.frames - 1) / std::max(1e-9, result.seconds)) : "");
      if (result.frames > 0) {
        const double ms = 1e3 / result.frames;
        fmt::print("a frame    layout {:.3f} ms, trace {:.3f} ms, show {:.3f} ms (means)\n", result.layout_seconds * ms,
                   result.trace_seconds * ms, result.show_seconds * ms);
      }
    }
    return interrupt.requested() ? interrupt.exit_status() : 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", error_report(e).c_str());
    return 1;
  }
}

}  // namespace holoray::cli
