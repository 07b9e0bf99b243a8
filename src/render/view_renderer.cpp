#include "render/view_renderer.hpp"

#include "render/line_renderer.hpp"

namespace holoray {

namespace {
// A pinhole's primary ray starts at the eye (NFF's hither is not applied).
bool eye_ray(const PixelLine& line, PrimaryRay& out) {
  out = PrimaryRay{Ray{line.origin, line.dir, 0, INFINITY}, 0, 1};
  return true;
}
}  // namespace

FrameBuffers render_view(const RenderScene& scene, const PinholeCamera& camera, const RenderOptions& opt,
                         RenderStats& stats) {
  return detail::render_lines(scene, camera, opt, stats, eye_ray);
}

FrameBuffers render_quilt(const RenderScene& scene, const QuiltCamera& camera, const RenderOptions& opt,
                          RenderStats& stats) {
  return detail::render_lines(scene, camera, opt, stats, eye_ray);
}

}  // namespace holoray
