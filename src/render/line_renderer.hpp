// holoray/render (internal): the tile loop shared by the renderers of
// cameras that give one line per pixel and nothing more (the pinhole view,
// the display camera): 4 x 4 pixel packets of 16 rays in 32 x 32 pixel
// tiles, spp samples per pixel (sample_offset), AOVs stored from sample 0.
// `make_ray(line, out)` turns a pixel's line into its primary ray and says
// whether it meets the scene. The result does not depend on the thread count.
#pragma once

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <stdexcept>
#include <vector>

#include "render/path_tracer.hpp"
#include "render/renderer.hpp"
#include "render/tiles.hpp"

namespace holoray::detail {

inline constexpr int kLineTile = 32;   // pixels across a tile
inline constexpr int kLineBlock = 4;   // pixels across a packet: 4 x 4 = kPacketSize rays
static_assert(kLineBlock * kLineBlock == kPacketSize);

/// A pinhole's primary ray: from the eye, unclipped (NFF's hither is not applied).
inline bool eye_ray(const PixelLine& line, PrimaryRay& out) {
  out = PrimaryRay{Ray{line.origin, line.dir, 0, INFINITY}, 0, 1};
  return true;
}

template <class Cam, class MakeRay>
FrameBuffers render_lines(const RenderContext& scene, const Cam& camera, const RenderOptions& opt, RenderStats& stats,
                          MakeRay make_ray) {
  if (opt.spp < 1) throw std::invalid_argument(fmt::format("samples per pixel must be at least 1, got {}", opt.spp));
  if (opt.threads < 0) throw std::invalid_argument(fmt::format("threads must be 0 (all) or more, got {}", opt.threads));
  // Rows [top, H) of the image, or RenderOptions::rows: row 0 of the
  // buffers is image row `top`.
  const int W = camera.width(), top = opt.rows ? (*opt.rows)[0] : 0, H = opt.rows ? (*opt.rows)[1] : camera.height();
  if (top < 0 || H > camera.height() || top >= H)
    throw std::invalid_argument(fmt::format("rows {} to {} are not a band of the {} rows of the image", top, H, camera.height()));
  FrameBuffers fb = allocate_frame(W, H - top, opt.aovs);
  const int tiles_x = (W + kLineTile - 1) / kLineTile, tiles_y = (H - top + kLineTile - 1) / kLineTile;
  const int tiles = tiles_x * tiles_y;
  std::vector<RayCounts> tile_counts(static_cast<size_t>(tiles));
  std::atomic<int> tiles_done{0};
  const Vec3 background = scene.background();
  const auto start = std::chrono::steady_clock::now();
  parallel_for_n(tiles, opt.threads, [&](int tile) {
    RayCounts counts;
    EyePacket eye;
    const int x0 = tile % tiles_x * kLineTile, y0 = top + tile / tiles_x * kLineTile;
    for (int by = y0; by < std::min(y0 + kLineTile, H); by += kLineBlock)
      for (int bx = x0; bx < std::min(x0 + kLineTile, W); bx += kLineBlock) {
        int pi[kPacketSize], pj[kPacketSize], n = 0;
        for (int j = by; j < std::min(by + kLineBlock, H); ++j)
          for (int i = bx; i < std::min(bx + kLineBlock, W); ++i) pi[n] = i, pj[n] = j, ++n;
        Vec3 sum[kPacketSize];
        bool first_hit[kPacketSize] = {};
        SurfacePoint first_surface[kPacketSize];
        double first_t[kPacketSize] = {};
        Vec3 toward[kPacketSize];  // sample 0's ray reversed: normals face the eye
        if (scene.settings().integrator == Integrator::path) {
          // Single rays, placed by the pixel's sampler (path_pixel_sum).
          for (int l = 0; l < n; ++l) {
            PathFirstHit first;
            sum[l] = path_pixel_sum(scene, pi[l], pj[l], opt.spp, counts, [&](double u, double v, PrimaryRay& pr, Vec3& escape) {
              const PixelLine line = camera.line(pi[l], pj[l], u, v);
              escape = line.dir;
              return make_ray(line, pr);
            }, first);
            if (!first.found) continue;
            first_hit[l] = true;
            first_surface[l] = first.surface;
            first_t[l] = first.hit.t;
            toward[l] = -first.primary.ray.dir;
          }
        } else {
          for (int k = 0; k < opt.spp; ++k) {
            bool ok[kPacketSize];
            for (int l = 0; l < n; ++l) {
              double u, v;
              sample_offset(pi[l], pj[l], k, u, v);
              ok[l] = make_ray(camera.line(pi[l], pj[l], u, v), eye.primary[l]);
            }
            intersect_eye_packet(scene, ok, n, counts, eye);
            Vec3 c[kPacketSize];
            for (int l = 0; l < kPacketSize; ++l) c[l] = background;
            if (std::any_of(eye.found, eye.found + n, [](bool f) { return f; }))
              shade(scene, eye.rays, eye.found, eye.surface, 1, counts, c);
            for (int l = 0; l < n; ++l) {
              sum[l] += c[l];
              if (k != 0 || !eye.found[l]) continue;
              first_hit[l] = true;
              first_surface[l] = eye.surface[l];
              first_t[l] = eye.hits[l].t;
              toward[l] = -eye.rays.rays[l].dir;
            }
          }
        }
        for (int l = 0; l < n; ++l)
          store_pixel(fb, opt.aovs, pi[l], pj[l] - top, sum[l] * (1.0 / opt.spp), first_hit[l] ? &first_surface[l] : nullptr,
                      first_t[l], toward[l]);
      }
    tile_counts[static_cast<size_t>(tile)] = counts;
    const int done = ++tiles_done;
    if (opt.progress) opt.progress(static_cast<double>(done) / tiles);
  });
  stats.trace_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  stats.rays = {};
  for (const RayCounts& c : tile_counts) stats.rays += c;
  return fb;
}

}  // namespace holoray::detail
