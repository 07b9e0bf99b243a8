#include "render/view_sharing.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "render/line_renderer.hpp"
#include "render/path_tracer.hpp"
#include "util/parallel.hpp"

namespace holoray {

namespace {

constexpr float kMinNormalCos = 0.8f;  // 37 degrees

// What a pixel's centre ray met: the z-buffer the other views' samples are
// tested against. t infinite: nothing.
struct Centre {
  float t = INFINITY;
  float p[3] = {0, 0, 0};  ///< the point (world)
  float n[3] = {0, 0, 0};  ///< unit geometric normal, toward the eye
};

// The samples a pixel took from its neighbours.
struct Taken {
  float sum[3] = {0, 0, 0};
  uint32_t count = 0;
};

// A pixel's own samples.
struct Own {
  float shared[3] = {0, 0, 0};  ///< the sum of those on the centre's surface
  float others[3] = {0, 0, 0};
  uint32_t shared_count = 0;
};

void take(Taken& t, const Vec3& c) {
  t.sum[0] += static_cast<float>(c.x), t.sum[1] += static_cast<float>(c.y), t.sum[2] += static_cast<float>(c.z);
  ++t.count;
}

// The first pass: each quilt pixel's centre ray.
std::vector<Centre> centres(const RenderContext& scene, const QuiltCamera& camera, int threads, RayCounts& counts) {
  const int W = camera.width(), H = camera.height();
  std::vector<Centre> out(static_cast<size_t>(W) * H);
  parallel_for_n(H, threads, [&](int j) {
    for (int i = 0; i < W; ++i) {
      const PixelLine line = camera.line(i, j);
      const Ray ray{line.origin, line.dir, 0, INFINITY};
      Hit hit;
      if (!scene.accel().intersect(ray, hit, RayCoherence::coherent)) continue;
      const SurfacePoint sp = scene.surface(ray, hit);
      Vec3 n = normalize(sp.ng);
      if (dot(n, line.dir) > 0) n = -n;
      const Vec3& p = sp.position;
      out[static_cast<size_t>(j) * W + i] =
          Centre{static_cast<float>(hit.t),
                 {static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z)},
                 {static_cast<float>(n.x), static_cast<float>(n.y), static_cast<float>(n.z)}};
    }
  });
  counts.eye += static_cast<uint64_t>(W) * H;
  return out;
}

// Whether x, with unit geometric normal n_x, lies on the surface the
// centre ray of `c` met in `view`: within one pixel's footprint of its
// tangent plane, its normal within 37 degrees (the z-buffer test).
bool on_centre_surface(const PinholeCamera& view, const Centre& c, const Vec3& x, const Vec3& n_x, double epsilon) {
  if (!std::isfinite(c.t)) return false;
  const Vec3 n{c.n[0], c.n[1], c.n[2]};
  const double footprint = view.pixel_size() * (view.desc().ortho_height > 0 ? 1.0 : c.t);
  if (std::fabs(dot(x - Vec3{c.p[0], c.p[1], c.p[2]}, n)) > footprint + 4 * epsilon) return false;
  return std::fabs(dot(n_x, n)) >= kMinNormalCos;
}

// Where view u sees x (unit normal n), taken from row `row` of another
// view: its quilt pixel index and the direction from its eye, or false
// (outside it, off the surface its pixel's centre meets, or on another
// row, which only rounding can give).
bool seen_by(const QuiltCamera& camera, const std::vector<Centre>& centre, int u, int row, const Vec3& x, const Vec3& n,
             double epsilon, size_t& index, Vec3& dir) {
  const PinholeCamera& view = camera.view(u);
  PanelHit h;
  if (!view.project(x, h) || h.j != row) return false;
  index = static_cast<size_t>(camera.quilt_y(u, h.j)) * camera.width() + camera.quilt_x(u, h.i);
  if (!on_centre_surface(view, centre[index], x, n, epsilon)) return false;
  // The eye's ray through x: from the eye, or along the axis when orthographic.
  dir = view.desc().ortho_height > 0 ? view.axis() : normalize(x - view.frame().origin);
  return true;
}

}  // namespace

uint64_t shared_views_bytes(int64_t pixels) {
  return static_cast<uint64_t>(pixels) * (sizeof(Centre) + sizeof(Taken) + sizeof(Own));
}

FrameBuffers render_quilt_shared(const RenderContext& scene, const QuiltCamera& camera, const RenderOptions& opt,
                                 RenderStats& stats) {
  if (scene.settings().integrator != Integrator::path)
    throw std::invalid_argument("sharing samples between a quilt's views needs the path integrator");
  if (opt.share_views < 1 || opt.share_views > kMaxSharedViews)
    throw std::invalid_argument(fmt::format("views shared: expected 1 to {} on each side, got {}", kMaxSharedViews, opt.share_views));
  if (opt.rows) throw std::invalid_argument("sharing samples between a quilt's views takes the whole quilt, not a band of rows");
  if (opt.spp < 1) throw std::invalid_argument(fmt::format("samples per pixel must be at least 1, got {}", opt.spp));
  const int W = camera.width(), H = camera.height(), views = camera.desc().columns * camera.desc().rows;
  const auto start = std::chrono::steady_clock::now();
  RayCounts first_pass;
  const double epsilon = scene.epsilon();
  const std::vector<Centre> centre = centres(scene, camera, opt.threads, first_pass);
  FrameBuffers fb = allocate_frame(W, H, opt.aovs);
  std::vector<Taken> taken(static_cast<size_t>(W) * H);
  std::vector<Own> own(static_cast<size_t>(W) * H);
  // A point is seen on the same row of every view (they differ by a move
  // along the image's right vector: quilt_camera.hpp), so one task traces
  // one row of every view and every sample it shares stays in that row: no
  // two tasks write one pixel, and each pixel's sums are added in one order,
  // the same for any thread count.
  const int view_width = camera.desc().view_width, view_height = camera.desc().view_height;
  std::vector<RayCounts> row_counts(static_cast<size_t>(view_height));
  std::atomic<int> rows_done{0};
  parallel_for_n(view_height, opt.threads, [&](int row) {
    RayCounts counts;
    FirstVertexRecord rec;
    for (int v = 0; v < views; ++v)
      for (int column = 0; column < view_width; ++column) {
        const int i = camera.quilt_x(v, column), j = camera.quilt_y(v, row);
        const size_t p = static_cast<size_t>(j) * W + i;
        Vec3 shared, others;
        uint32_t shared_count = 0;
        PathFirstHit first;
        const auto eye_ray = [&](double pu, double pv, PrimaryRay& pr, Vec3& escape) {
          const PixelLine line = camera.line(i, j, pu, pv);
          escape = line.dir;
          return detail::eye_ray(line, pr);  // as the unshared quilt's (render_quilt)
        };
        path_pixel_samples(scene, i, j, opt.spp, counts, eye_ray, first, &rec, [&](const Vec3& c) {
          // Pooled with what the neighbours give only where they could give
          // it: on the surface this pixel's centre meets.
          const Vec3 x = rec.surface.position, n = rec.shareable ? normalize(rec.surface.ng) : Vec3{};
          if (!rec.shareable || !on_centre_surface(camera.view(v), centre[p], x, n, epsilon)) {
            others += c;
            return;
          }
          shared += c, ++shared_count;
          for (int w = std::max(0, v - opt.share_views); w <= std::min(views - 1, v + opt.share_views); ++w) {
            size_t index;
            Vec3 dir, seen;
            if (w == v || !seen_by(camera, centre, w, row, x, n, epsilon, index, dir)) continue;
            if (path_radiance_toward(scene, rec, dir, seen)) take(taken[index], seen);
          }
        });
        Own& o = own[p];
        o = Own{{static_cast<float>(shared.x), static_cast<float>(shared.y), static_cast<float>(shared.z)},
                {static_cast<float>(others.x), static_cast<float>(others.y), static_cast<float>(others.z)},
                shared_count};
        store_pixel(fb, opt.aovs, i, j, Vec3{}, first.found ? &first.surface : nullptr, first.hit.t, -first.primary.ray.dir);
      }
    row_counts[static_cast<size_t>(row)] = counts;
    const int done = ++rows_done;
    if (opt.progress) opt.progress(static_cast<double>(done) / view_height);
  });
  // Every sample is in: each pixel's colour (the header's formula).
  parallel_for_n(H, opt.threads, [&](int j) {
    for (int i = 0; i < W; ++i) {
      const size_t p = static_cast<size_t>(j) * W + i;
      const Own& o = own[p];
      const Taken& t = taken[p];
      float* out = fb.colour.at(i, j);
      for (int c = 0; c < 3; ++c) {
        double value = o.others[c] / opt.spp;
        if (o.shared_count > 0)
          value += (static_cast<double>(o.shared_count) / opt.spp) * (o.shared[c] + t.sum[c]) / (o.shared_count + t.count);
        out[c] = static_cast<float>(value);
      }
    }
  });
  stats.trace_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  stats.rays = first_pass;
  for (const RayCounts& c : row_counts) stats.rays += c;
  return fb;
}

}  // namespace holoray
