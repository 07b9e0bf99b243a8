#include "temporal/fill.hpp"

#include <atomic>
#include <chrono>
#include <vector>

#include "render/renderer.hpp"
#include "render/tiles.hpp"

namespace holoray {

namespace {

bool is_hole(PixelStatus s) { return static_cast<int8_t>(s) < 0; }

void trace_holes(const RenderScene& scene, const LensArray& camera, int threads, ReprojectedFrame& frame) {
  const ElementalTiles tiles(camera);
  const int W = camera.width();
  std::vector<RayCounts> tile_rays(static_cast<size_t>(tiles.count()));
  for_each_tile(tiles, threads, [&](int tile) {
    const TileRect r = tiles.rect(tile);
    RayCounts counts;
    for (int j = r.y0; j < r.y1; ++j)
      for (int i = r.x0; i < r.x1; ++i) {
        const size_t p = static_cast<size_t>(j) * W + i;
        if (!is_hole(frame.status[p])) continue;
        PrimaryHit hit;
        SurfacePoint sp;
        const Vec3 c = render_pixel(scene, camera, i, j, 1, counts, &hit, &sp);
        frame.object[p] = hit.status == PrimaryHit::kHit ? sp.object : -1;
        float* o = frame.colour.at(i, j);
        o[0] = static_cast<float>(c.x), o[1] = static_cast<float>(c.y), o[2] = static_cast<float>(c.z);
        frame.status[p] = PixelStatus::traced;
      }
    tile_rays[static_cast<size_t>(tile)] = counts;
  });
  for (const RayCounts& c : tile_rays) frame.rays += c;
}

// One ring of growth: every hole with a valid 8-neighbour in its own
// elemental image takes their mean. Reads the previous state only, so the
// result does not depend on the order.
bool interpolate_ring(const LensArray& camera, int threads, ReprojectedFrame& frame) {
  const int W = camera.width(), H = camera.height();
  const std::vector<PixelStatus> before = frame.status;
  const ImageBuffer colour_before = frame.colour;
  const ElementalTiles tiles(camera);
  std::atomic<bool> grew{false};
  for_each_tile(tiles, threads, [&](int tile) {
    const TileRect r = tiles.rect(tile);
    for (int j = r.y0; j < r.y1; ++j)
      for (int i = r.x0; i < r.x1; ++i) {
        const size_t p = static_cast<size_t>(j) * W + i;
        if (!is_hole(before[p])) continue;
        const LensIndex lens = camera.lens_of_pixel(i, j);
        Vec3 sum;
        int n = 0;
        for (int dj = -1; dj <= 1; ++dj)
          for (int di = -1; di <= 1; ++di) {
            const int ni = i + di, nj = j + dj;
            if ((di == 0 && dj == 0) || ni < 0 || nj < 0 || ni >= W || nj >= H) continue;
            const size_t q = static_cast<size_t>(nj) * W + ni;
            if (is_hole(before[q]) || !(camera.lens_of_pixel(ni, nj) == lens)) continue;
            const float* c = colour_before.at(ni, nj);
            sum += Vec3{c[0], c[1], c[2]};
            ++n;
          }
        if (n == 0) continue;
        sum = sum * (1.0 / n);
        float* o = frame.colour.at(i, j);
        o[0] = static_cast<float>(sum.x), o[1] = static_cast<float>(sum.y), o[2] = static_cast<float>(sum.z);
        frame.status[p] = PixelStatus::interpolated;
        frame.object[p] = -1;
        grew = true;
      }
  });
  return grew;
}

}  // namespace

void fill_missed(const RenderScene& scene, const LensArray& camera, Fill fill, int threads, ReprojectedFrame& frame) {
  const auto start = std::chrono::steady_clock::now();
  if (fill == Fill::interpolate) {
    // A hole wider than the elemental image cannot be bridged from inside it.
    for (int ring = 0; ring < camera.desc().pixels_per_lens; ++ring)
      if (!interpolate_ring(camera, threads, frame)) break;
  }
  trace_holes(scene, camera, threads, frame);
  frame.seconds.fill = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace holoray
