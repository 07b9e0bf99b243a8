// holoray/api (internal): what a Renderer holds once built, for the front
// ends inside the library that render it in ways the public API does not
// offer (live/: the camera placed again for each view, frames shown in a
// window).
#pragma once

#include <memory>
#include <optional>

#include "api/gpu_executor.hpp"
#include "api/internal.hpp"
#include "api/world_state.hpp"
#include "holoray/render.hpp"
#include "render/frame_camera.hpp"
#include "render/render_context.hpp"
#include "render/shadow_cache.hpp"

namespace holoray::api {

struct RendererState {
  std::shared_ptr<const WorldState> world;  // the scene, built, and its light
  Camera public_camera;
  FrameCameraDesc choice;
  std::optional<FrameCamera> placed;  // set once the constructor has placed it
  const FrameCamera& camera() const { return *placed; }
  RenderSettings settings;  // the world's, with this renderer's cache and footprint
  std::unique_ptr<ShadowCache> cache;
  RenderOptions options;
  TraceStyle style = TraceStyle::packet;
  RenderStats build;
  std::unique_ptr<GpuExecutor> gpu;  // set for `device` gpu
};

/// What Renderer(world, camera, options) checks before it builds anything:
/// the options (their light taken from the world), the camera placed on the
/// scene's viewpoint, its image against this machine's memory. Throws as
/// that constructor does. For live, which places the camera itself for
/// each view.
void check_camera(const World& world, const Camera& camera, const RenderOptions& options);

namespace detail {

/// The state behind a Renderer (internal).
struct RendererAccess {
  static RendererState& state(const Renderer& renderer);
};

}  // namespace detail

}  // namespace holoray::api
