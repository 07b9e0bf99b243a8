// holoray public API: a scene shown live in a window, rendered on the GPU
// path as fast as the device renders it (docs/guide/live.md).
//
//   LiveOptions live;
//   live.exit_after = 100;
//   run_live(scene, LensArray{}, RenderOptions{.device = "gpu"}, live);
#pragma once

#include <functional>
#include <optional>
#include <string>

#include "holoray/camera.hpp"
#include "holoray/export.hpp"
#include "holoray/image.hpp"
#include "holoray/render.hpp"
#include "holoray/scene.hpp"

namespace holoray::api {

struct LiveOptions {
  /// The monitor the window opens on: its index ("0") or name; "" the primary.
  std::string monitor;
  /// Full screen on that monitor at its own mode. Default: a display's or
  /// Looking Glass's panel image full screen (it is one of the machine's
  /// monitors), anything else in a window the image's size.
  std::optional<bool> fullscreen;
  int exit_after = 0;      ///< frames shown, then return; 0: until the window is closed
  /// No window: each frame traced, packed and copied on the device to an
  /// image of the window's size as it would be shown, and not presented
  /// (no vsync), input only from `events`; for a machine without a display
  /// and to measure live's frame rate there (LiveResult). Needs exit_after.
  bool offscreen = false;
  /// Written when the window closes: the last frame shown, .png as shown
  /// (8-bit, `encoding`), .exr its rendered colour in float.
  std::string screenshot;
  std::string events;      ///< input replayed by frame number (live.md, "Scripted runs")
  std::string record;      ///< a folder: every frame shown as frame_NNNN.png (from 0)
  bool play = false;       ///< run_live_shot: the shot plays from the start (else Space plays it)
  /// With a Display camera: show what an eye sees through the display
  /// (simulate_view, preview.hpp) instead of the panel image, the eye where
  /// the pointer is over the panel (display frame, 600 mm away at first;
  /// the wheel brings it nearer or farther).
  bool simulate = false;
  /// The 8-bit encoding shown and written; nullopt: srgb for a mesh
  /// scene, linear for NFF and Tachyon (as `holoray render`).
  std::optional<Encoding> encoding;
  /// Under the path integrator (RenderOptions::integrator): while the view
  /// stands still, each frame adds RenderOptions::spp samples to the one
  /// before (the samples after its own, as a render of more samples draws
  /// them), up to this many per pixel; 0: every frame its spp alone.
  int max_spp = 256;
  /// Lines for the user: the files written, the view at the end.
  std::function<void(const std::string& line)> print;
  /// Asked between frames and at least twice a second while idle: true ends
  /// the run (a signal).
  std::function<bool()> stop;
};

/// What a run showed.
struct LiveResult {
  int frames = 0;        ///< frames shown
  double seconds = 0;    ///< from the first frame shown to the last
  /// Where the frames' time went, seconds summed over every frame shown:
  /// the scene moved to the frame and laid out again on the device (a
  /// shot's, where its objects moved), the trace, and the pack and show
  /// (or copy, offscreen; a simulated eye's view included).
  double layout_seconds = 0, trace_seconds = 0, show_seconds = 0;
  /// The view at the end, as `holoray live` prints it: "eye X,Y,Z at X,Y,Z
  /// up X,Y,Z fov F focus D [lens-fov L]" (17 digits: the same doubles).
  std::string view;
  int shot_frame = 0;    ///< run_live_shot: the shot's frame shown last
  /// simulate: the eye's last place, "X,Y,Z" (mm, display frame, 17
  /// digits), and the width of the view it saw (SimulateOptions::width).
  std::string eye_mm;
  int simulated_width = 0;
};

/// Opens the window and shows `scene` through `camera` (a lens array, a
/// pinhole view, a display or a Looking Glass, placed by the scene's
/// viewpoint) until the window is closed, options.stop says so or
/// exit_after frames were shown. Renders only when something changed.
/// options.device must name the GPU path ("gpu", "gpu:N"). Throws
/// std::runtime_error with the reason when there is no display (neither
/// DISPLAY nor WAYLAND_DISPLAY), no Vulkan device, or no monitor of that
/// name (listing them); std::invalid_argument naming the option for what
/// live does not show (a quilt, an explicit placement, the CPU path).
HOLORAY_API LiveResult run_live(const Scene& scene, const Camera& camera, const RenderOptions& options,
                                const LiveOptions& live);

/// run_live for an animated shot (shot-format.md): its objects move as the
/// shot plays (Space, or live.play), in real time at its fps and looping;
/// PageDown and PageUp step a frame. The camera is the shot's lens array,
/// or `camera` (a pinhole, display or Looking Glass) placed by each frame's
/// viewpoint, as `holoray animate` places it; the controls move the view
/// from the frame's, and Home gives it back to the shot. Throws as
/// run_live, and what reading the shot throws (SceneError).
HOLORAY_API LiveResult run_live_shot(const std::string& shot, const std::optional<Camera>& camera,
                                     const RenderOptions& options, const LiveOptions& live);

}  // namespace holoray::api
