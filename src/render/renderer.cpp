#include "render/renderer.hpp"

#include <fmt/format.h>
#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "render/shading.hpp"

namespace holoray {

namespace {

// Per-pixel, per-sample jitter: a hashed Cranley-Patterson rotation of the R2
// sequence. Deterministic in (pixel, sample), so any schedule gives the same image.
uint32_t hash32(uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352dU;
  x ^= x >> 15;
  x *= 0x846ca68bU;
  x ^= x >> 16;
  return x;
}

void sample_offset(int i, int j, int k, double& u, double& v) {
  if (k == 0) {
    u = v = 0.5;
    return;
  }
  const uint32_t h = hash32(static_cast<uint32_t>(i) * 73856093U ^ hash32(static_cast<uint32_t>(j) * 19349663U));
  const double ru = (h & 0xffff) / 65536.0, rv = (h >> 16) / 65536.0;
  u = std::fmod(ru + k * 0.7548776662466927, 1.0);
  v = std::fmod(rv + k * 0.5698402909980532, 1.0);
}

}  // namespace

uint64_t frame_bytes(const LensArray& camera, const AovSet& aovs) {
  const uint64_t channels = 3 + (aovs.albedo ? 3 : 0) + (aovs.depth ? 1 : 0) + (aovs.normal ? 3 : 0) + (aovs.id ? 1 : 0);
  return static_cast<uint64_t>(camera.pixel_count()) * channels * sizeof(float);
}

std::optional<PrimaryRay> primary_ray(const LensArray& camera, const Bounds3& bounds, double margin, int i, int j,
                                      double u, double v) {
  if (bounds.empty()) return std::nullopt;
  const PixelLine line = camera.line(i, j, u, v);
  Bounds3 b = bounds;
  b.lo -= Vec3{margin, margin, margin};
  b.hi += Vec3{margin, margin, margin};
  double t0, t1;
  if (!intersect_line_box(line.origin, line.dir, b, t0, t1)) return std::nullopt;
  if (camera.desc().mode == RecordingMode::orthoscopic) {
    const double start = t1 + margin;
    return PrimaryRay{Ray{line.origin + line.dir * start, -line.dir, 0, start - t0 + margin}, start, -1};
  }
  if (t1 <= 0) return std::nullopt;
  return PrimaryRay{Ray{line.origin, line.dir, std::fmax(0.0, t0 - margin), t1 + margin}, 0, 1};
}

FrameBuffers render_frame(const RenderScene& scene, const LensArray& camera, const RenderOptions& opt,
                          RenderStats& stats, uint64_t memory_limit_bytes) {
  if (opt.spp < 1) throw std::invalid_argument(fmt::format("samples per pixel must be at least 1, got {}", opt.spp));
  if (opt.threads < 0) throw std::invalid_argument(fmt::format("threads must be 0 (all) or more, got {}", opt.threads));
  const uint64_t need = frame_bytes(camera, opt.aovs);
  if (memory_limit_bytes && need > memory_limit_bytes)
    throw std::length_error(fmt::format("a {}x{} image needs {:.1f} MiB of buffers, over the limit of {:.1f} MiB",
                                        camera.width(), camera.height(), need / 1048576.0, memory_limit_bytes / 1048576.0));

  const int W = camera.width(), H = camera.height();
  FrameBuffers fb;
  fb.colour = ImageBuffer(W, H, 3);
  if (opt.aovs.albedo) fb.albedo = ImageBuffer(W, H, 3);
  if (opt.aovs.depth) fb.depth = ImageBuffer(W, H, 1, NAN);
  if (opt.aovs.normal) fb.normal = ImageBuffer(W, H, 3);
  if (opt.aovs.id) fb.id = ImageBuffer(W, H, 1, -1.0f);

  // Tiles of whole elemental images, about 4096 pixels each.
  const int P = camera.desc().pixels_per_lens;
  const int lenses_per_tile = std::max(1, static_cast<int>(std::lround(64.0 / P)));
  const int tile_w = P * lenses_per_tile, tile_h = P * lenses_per_tile;
  const int tiles_x = (W + tile_w - 1) / tile_w, tiles_y = (H + tile_h - 1) / tile_h;
  const int tiles = tiles_x * tiles_y;
  std::vector<RayCounts> tile_counts(static_cast<size_t>(tiles));
  std::atomic<int> tiles_done{0};
  const double margin = scene.epsilon();
  const Bounds3 bounds = scene.bounds();
  const double inv_spp = 1.0 / opt.spp;

  auto render_tile = [&](int tile) {
    RayCounts counts;
    const int x0 = (tile % tiles_x) * tile_w, y0 = (tile / tiles_x) * tile_h;
    const int x1 = std::min(W, x0 + tile_w), y1 = std::min(H, y0 + tile_h);
    for (int j = y0; j < y1; ++j) {
      for (int i = x0; i < x1; ++i) {
        Vec3 sum;
        for (int k = 0; k < opt.spp; ++k) {
          double u, v;
          sample_offset(i, j, k, u, v);
          Vec3 c = scene.background();
          const auto pr = primary_ray(camera, bounds, margin, i, j, u, v);
          Hit hit;
          if (pr) {
            ++counts.eye;
            if (scene.accel().intersect(pr->ray, hit, RayCoherence::coherent)) {
              const SurfacePoint sp = scene.surface(pr->ray, hit);
              c = shade(scene, pr->ray, sp, 1, counts);
              if (k == 0) {
                if (opt.aovs.albedo) {
                  float* a = fb.albedo.at(i, j);
                  a[0] = static_cast<float>(sp.material->colour.x);
                  a[1] = static_cast<float>(sp.material->colour.y);
                  a[2] = static_cast<float>(sp.material->colour.z);
                }
                if (opt.aovs.depth) *fb.depth.at(i, j) = static_cast<float>(pr->t_offset + pr->t_sign * hit.t);
                if (opt.aovs.normal) {
                  const Vec3 n = dot(sp.ns, pr->ray.dir) <= 0 ? sp.ns : -sp.ns;
                  float* o = fb.normal.at(i, j);
                  o[0] = static_cast<float>(n.x);
                  o[1] = static_cast<float>(n.y);
                  o[2] = static_cast<float>(n.z);
                }
                if (opt.aovs.id) *fb.id.at(i, j) = static_cast<float>(sp.object);
              }
            }
          }
          sum += c;
        }
        float* o = fb.colour.at(i, j);
        o[0] = static_cast<float>(sum.x * inv_spp);
        o[1] = static_cast<float>(sum.y * inv_spp);
        o[2] = static_cast<float>(sum.z * inv_spp);
      }
    }
    tile_counts[static_cast<size_t>(tile)] = counts;
    const int done = ++tiles_done;
    if (opt.progress) opt.progress(static_cast<double>(done) / tiles);
  };

  const auto start = std::chrono::steady_clock::now();
  auto run = [&] {
    tbb::parallel_for(tbb::blocked_range<int>(0, tiles, 1), [&](const tbb::blocked_range<int>& r) {
      for (int t = r.begin(); t != r.end(); ++t) render_tile(t);
    });
  };
  if (opt.threads > 0) {
    tbb::task_arena arena(opt.threads);
    arena.execute(run);
  } else {
    run();
  }
  stats.trace_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  stats.rays = {};
  for (const RayCounts& c : tile_counts) stats.rays += c;
  return fb;
}

}  // namespace holoray
