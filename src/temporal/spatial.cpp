#include "temporal/spatial.hpp"

#include <fmt/format.h>

#include <algorithm>
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

  // The frame is its own keyframe: same camera, same time, no motion. Its
  // points go only to the lenses around their own, where the untraced
  // lenses are; the traced pixels are final and receive nothing.
  const int W = camera.width(), H = camera.height();
  std::vector<uint8_t> traced(static_cast<size_t>(W) * H);
  for (int j = 0; j < H; ++j)
    for (int i = 0; i < W; ++i) traced[static_cast<size_t>(j) * W + i] = traced_at_stride(camera, options.stride, i, j);
  const PointImage key{0, camera, std::move(sparse.primary), std::move(sparse.colour), {}, {}};
  ReprojectOptions rp;
  rp.reuse = options.reuse;
  rp.reach = Reach::lenses;
  // Every untraced lens has a traced one within stride - 1 lenses (hex
  // blocks only approximate lenses: one more).
  rp.lens_radius = options.stride - 1 + (camera.desc().grid == Grid::hex ? 1 : 0);
  rp.given = &traced;
  rp.threads = options.threads;
  out.frame = reproject(scene, camera, 0, &key, nullptr, rp);
  for (int j = 0; j < H; ++j)
    for (int i = 0; i < W; ++i) {
      const size_t p = static_cast<size_t>(j) * W + i;
      if (!traced[p]) continue;
      ++out.sparse_pixels;
      std::copy_n(key.colour.at(i, j), 3, out.frame.colour.at(i, j));
      out.frame.status[p] = PixelStatus::traced;
      const PrimaryHit& h = key.hits[p];
      out.frame.object[p] = h.status == PrimaryHit::kHit ? scene.object_of(h.group, static_cast<PrimKind>(h.kind), h.prim) : -1;
    }
  fill_missed(scene, camera, options.fill, options.threads, out.frame);
  return out;
}

}  // namespace holoray
