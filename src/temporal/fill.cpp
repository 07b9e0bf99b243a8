#include "temporal/fill.hpp"

#include <algorithm>
#include <chrono>
#include <vector>

#include "render/renderer.hpp"
#include "render/tiles.hpp"

namespace holoray {

namespace {

bool is_hole(PixelStatus s) { return static_cast<int8_t>(s) < 0; }

void trace_holes(const RenderContext& scene, const LensArray& camera, int threads, ReprojectedFrame& frame) {
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

// A hole whose line cannot meet the scene's bounds shows the background:
// set exactly, at the cost of a box test and no ray (the same test the
// tracer makes first), so interpolation never paints a surface over it.
void settle_background(const RenderContext& scene, const LensArray& camera, ReprojectedFrame& frame) {
  const int W = camera.width();
  const Vec3 bg = scene.background();
  for (size_t p = 0; p < frame.status.size(); ++p) {
    if (!is_hole(frame.status[p])) continue;
    const int i = static_cast<int>(p % W), j = static_cast<int>(p / W);
    if (primary_ray(camera, scene.bounds(), scene.epsilon(), i, j)) continue;
    float* o = frame.colour.at(i, j);
    o[0] = static_cast<float>(bg.x), o[1] = static_cast<float>(bg.y), o[2] = static_cast<float>(bg.z);
    frame.status[p] = PixelStatus::traced;
    frame.object[p] = -1;
  }
}

// Interpolation from valid neighbours in the same elemental image, one ring
// of growth at a time: every hole with a valid 8-neighbour on a surface takes
// the mean of the neighbours on the surface most of them show (the object id),
// so a surface's colour never bleeds onto another or onto the background;
// holes next to background only are traced. A ring reads the state before
// it only (its results are applied after), so the result does not depend on
// the order or the thread count. Only the holes are visited, so a ring costs
// what it fills, not the frame.
void interpolate_holes(const LensArray& camera, int threads, ReprojectedFrame& frame) {
  const int W = camera.width(), H = camera.height();
  std::vector<size_t> holes;
  for (size_t p = 0; p < frame.status.size(); ++p)
    if (is_hole(frame.status[p])) holes.push_back(p);
  struct Filled {
    bool ok = false;
    int32_t object = -1;
    float c[3] = {0, 0, 0};
  };
  std::vector<Filled> result;
  constexpr size_t kChunk = 4096;
  // A hole wider than the elemental image cannot be bridged from inside it.
  for (int ring = 0; ring < camera.desc().pixels_per_lens && !holes.empty(); ++ring) {
    result.assign(holes.size(), Filled{});
    parallel_for_n(static_cast<int>((holes.size() + kChunk - 1) / kChunk), threads, [&](int chunk) {
      const size_t end = std::min(holes.size(), (chunk + 1) * kChunk);
      for (size_t h = chunk * kChunk; h < end; ++h) {
        const int i = static_cast<int>(holes[h] % W), j = static_cast<int>(holes[h] / W);
        const LensIndex lens = camera.lens_of_pixel(i, j);
        size_t near[8];
        int count = 0;
        for (int dj = -1; dj <= 1; ++dj)
          for (int di = -1; di <= 1; ++di) {
            const int ni = i + di, nj = j + dj;
            if ((di == 0 && dj == 0) || ni < 0 || nj < 0 || ni >= W || nj >= H) continue;
            const size_t q = static_cast<size_t>(nj) * W + ni;
            if (is_hole(frame.status[q]) || frame.object[q] < 0 || !(camera.lens_of_pixel(ni, nj) == lens)) continue;
            near[count++] = q;
          }
        // The object most neighbours show (ties: the smallest id, for determinism).
        int32_t object = -1;
        int best = 0;
        for (int a = 0; a < count; ++a) {
          int votes = 0;
          for (int b = 0; b < count; ++b) votes += frame.object[near[b]] == frame.object[near[a]];
          if (votes > best || (votes == best && frame.object[near[a]] < object)) best = votes, object = frame.object[near[a]];
        }
        if (best == 0) continue;
        float sum[3] = {0, 0, 0};
        for (int a = 0; a < count; ++a) {
          if (frame.object[near[a]] != object) continue;
          const float* c = frame.colour.data.data() + 3 * near[a];
          sum[0] += c[0], sum[1] += c[1], sum[2] += c[2];
        }
        result[h].ok = true;
        result[h].object = object;
        for (int k = 0; k < 3; ++k) result[h].c[k] = sum[k] / static_cast<float>(best);
      }
    });
    size_t kept = 0;
    for (size_t h = 0; h < holes.size(); ++h) {
      const size_t p = holes[h];
      if (!result[h].ok) {
        holes[kept++] = p;
        continue;
      }
      float* o = frame.colour.at(static_cast<int>(p % W), static_cast<int>(p / W));
      o[0] = result[h].c[0], o[1] = result[h].c[1], o[2] = result[h].c[2];
      frame.status[p] = PixelStatus::interpolated;
      frame.object[p] = result[h].object;
    }
    if (kept == holes.size()) break;
    holes.resize(kept);
  }
}

}  // namespace

void fill_missed(const RenderContext& scene, const LensArray& camera, Fill fill, int threads, ReprojectedFrame& frame) {
  scene.accel().build();  // before the clock, on all cores (AccelScene::build)
  const auto start = std::chrono::steady_clock::now();
  if (fill == Fill::interpolate) {
    settle_background(scene, camera, frame);
    interpolate_holes(camera, threads, frame);
  }
  trace_holes(scene, camera, threads, frame);
  frame.seconds.fill = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace holoray
