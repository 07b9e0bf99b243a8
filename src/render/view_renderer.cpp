#include "render/view_renderer.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <stdexcept>
#include <vector>

#include "render/tiles.hpp"

namespace holoray {

namespace {

constexpr int kTile = 32;   // pixels across a tile
constexpr int kBlock = 4;   // pixels across a packet: 4 x 4 = kPacketSize rays
static_assert(kBlock * kBlock == kPacketSize);

}  // namespace

FrameBuffers render_view(const RenderScene& scene, const PinholeCamera& camera, const RenderOptions& opt,
                         RenderStats& stats) {
  if (opt.spp < 1) throw std::invalid_argument(fmt::format("samples per pixel must be at least 1, got {}", opt.spp));
  if (opt.threads < 0) throw std::invalid_argument(fmt::format("threads must be 0 (all) or more, got {}", opt.threads));
  const int W = camera.width(), H = camera.height();
  FrameBuffers fb = allocate_frame(W, H, opt.aovs);
  const int tiles_x = (W + kTile - 1) / kTile, tiles_y = (H + kTile - 1) / kTile;
  const int tiles = tiles_x * tiles_y;
  std::vector<RayCounts> tile_counts(static_cast<size_t>(tiles));
  std::atomic<int> tiles_done{0};
  const Vec3 background = scene.background();
  const auto start = std::chrono::steady_clock::now();
  parallel_for_n(tiles, opt.threads, [&](int tile) {
    RayCounts counts;
    EyePacket eye;
    const int x0 = tile % tiles_x * kTile, y0 = tile / tiles_x * kTile;
    for (int by = y0; by < std::min(y0 + kTile, H); by += kBlock)
      for (int bx = x0; bx < std::min(x0 + kTile, W); bx += kBlock) {
        int pi[kPacketSize], pj[kPacketSize], n = 0;
        for (int j = by; j < std::min(by + kBlock, H); ++j)
          for (int i = bx; i < std::min(bx + kBlock, W); ++i) pi[n] = i, pj[n] = j, ++n;
        Vec3 sum[kPacketSize];
        bool first_hit[kPacketSize] = {};
        SurfacePoint first_surface[kPacketSize];
        double first_t[kPacketSize] = {};
        Vec3 toward[kPacketSize];  // sample 0's ray reversed: normals face the eye
        for (int k = 0; k < opt.spp; ++k) {
          bool ok[kPacketSize];
          for (int l = 0; l < n; ++l) {
            double u, v;
            sample_offset(pi[l], pj[l], k, u, v);
            const PixelLine line = camera.line(pi[l], pj[l], u, v);
            eye.primary[l] = PrimaryRay{Ray{line.origin, line.dir, 0, INFINITY}, 0, 1};
            ok[l] = true;
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
        for (int l = 0; l < n; ++l)
          store_pixel(fb, opt.aovs, pi[l], pj[l], sum[l] * (1.0 / opt.spp), first_hit[l] ? &first_surface[l] : nullptr,
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

}  // namespace holoray
