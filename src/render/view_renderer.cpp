#include "render/view_renderer.hpp"

#include "render/line_renderer.hpp"

namespace holoray {

FrameBuffers render_view(const RenderScene& scene, const PinholeCamera& camera, const RenderOptions& opt,
                         RenderStats& stats) {
  return detail::render_lines(scene, camera, opt, stats, detail::eye_ray);
}

FrameBuffers render_quilt(const RenderScene& scene, const QuiltCamera& camera, const RenderOptions& opt,
                          RenderStats& stats) {
  return detail::render_lines(scene, camera, opt, stats, detail::eye_ray);
}

}  // namespace holoray
