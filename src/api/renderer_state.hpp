// holoray/api (internal): what a Renderer holds once built, for the front
// ends inside the library that render it in ways the public API does not
// offer (live/: the camera placed again for each view, frames shown in a
// window).
#pragma once

#include <memory>
#include <optional>

#include "api/gpu_executor.hpp"
#include "api/internal.hpp"
#include "holoray/render.hpp"
#include "render/emitters.hpp"
#include "render/environment.hpp"
#include "render/frame_camera.hpp"
#include "render/render_context.hpp"
#include "render/shadow_cache.hpp"

namespace holoray::api {

struct RendererState {
  std::shared_ptr<const SceneData> scene;
  Camera public_camera;
  FrameCameraDesc choice;
  std::optional<FrameCamera> placed;  // set once the constructor has placed it
  const FrameCamera& camera() const { return *placed; }
  std::unique_ptr<RenderScene> render_scene;
  RenderSettings settings;  // this renderer's depth, cache, footprint and background
  std::unique_ptr<EnvironmentMap> environment;  // the path integrator's (settings.environment)
  std::unique_ptr<EmissiveTriangles> emitters;  // the path integrator's (settings.emitters)
  std::unique_ptr<ShadowCache> cache;
  RenderOptions options;
  TraceStyle style = TraceStyle::packet;
  RenderStats build;
  std::unique_ptr<GpuExecutor> gpu;  // set for `device` gpu
};

namespace detail {

/// The state behind a Renderer (internal).
struct RendererAccess {
  static RendererState& state(const Renderer& renderer);
};

}  // namespace detail

}  // namespace holoray::api
