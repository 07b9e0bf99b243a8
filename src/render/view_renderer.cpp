#include "render/view_renderer.hpp"

#include "render/line_renderer.hpp"

namespace holoray {

FrameBuffers render_view(const RenderScene& scene, const PinholeCamera& camera, const RenderOptions& opt,
                         RenderStats& stats) {
  return detail::render_lines(scene, camera, opt, stats, [](const PixelLine& line, PrimaryRay& out) {
    out = PrimaryRay{Ray{line.origin, line.dir, 0, INFINITY}, 0, 1};
    return true;
  });
}

}  // namespace holoray
