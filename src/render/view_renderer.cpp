#include "render/view_renderer.hpp"

#include "render/line_renderer.hpp"
#include "render/view_sharing.hpp"

namespace holoray {

FrameBuffers render_view(const RenderContext& scene, const PinholeCamera& camera, const RenderOptions& opt,
                         RenderStats& stats) {
  const PinholeDesc& d = camera.desc();
  if (d.clip_near == 0 && d.clip_far == INFINITY) return detail::render_lines(scene, camera, opt, stats, detail::eye_ray);
  // The planes are perpendicular to the axis: a ray at cosine c to it
  // meets them at clip / c.
  const Vec3 axis = camera.axis();
  return detail::render_lines(scene, camera, opt, stats, [&](const PixelLine& line, PrimaryRay& out) {
    const double c = dot(line.dir, axis);
    out = PrimaryRay{Ray{line.origin, line.dir, d.clip_near / c, d.clip_far / c}, 0, 1};
    return c > 0;
  });
}

FrameBuffers render_quilt(const RenderContext& scene, const QuiltCamera& camera, const RenderOptions& opt,
                          RenderStats& stats) {
  if (opt.share_views > 0) return render_quilt_shared(scene, camera, opt, stats);
  return detail::render_lines(scene, camera, opt, stats, detail::eye_ray);
}

}  // namespace holoray
