#include "temporal/spatial.hpp"

#include <fmt/format.h>

#include <stdexcept>
#include <utility>

#include "render/renderer.hpp"
#include "temporal/point_image.hpp"

namespace holoray {

SpatialFrame render_spatial(const RenderScene& scene, const LensArray& camera, const SpatialOptions& options) {
  if (options.stride < 2)
    throw std::invalid_argument(fmt::format("the spatial-reuse stride must be at least 2, got {}", options.stride));
  SpatialFrame out;
  RenderOptions ro;
  ro.threads = options.threads;
  ro.primary_hits = true;
  ro.lens_stride = options.stride;
  RenderStats stats;
  FrameBuffers sparse = render_frame(scene, camera, ro, stats);
  out.sparse_rays = stats.rays;
  out.sparse_seconds = stats.trace_seconds;

  // The frame is its own keyframe: same camera, same time, no motion.
  const PointImage key{0, camera, std::move(sparse.primary), std::move(sparse.colour)};
  ReprojectOptions rp;
  rp.reuse = options.reuse;
  rp.reach = Reach::all;  // a point must reach the lenses between the traced ones
  rp.threads = options.threads;
  out.frame = reproject(scene, camera, 0, &key, nullptr, rp);
  fill_missed(scene, camera, options.fill, options.threads, out.frame);
  return out;
}

}  // namespace holoray
