#include "temporal/reproject.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "render/renderer.hpp"
#include "render/shading.hpp"
#include "render/tiles.hpp"
#include "temporal/lens_reach.hpp"

namespace holoray {

namespace {

// Tuning of the z-buffer, in pixel footprints (the width one pixel covers at
// the point's depth, s*|t|/g): see reproject.hpp.
constexpr double kCentrePenalty = 2.0;
constexpr double kSameSurface = 4.0;
constexpr double kLeakStep = 4.0;
// Leak pass marks: a gap (nearer on two opposite sides) or the far side of a step.
constexpr uint8_t kLeak = 1, kBehindStep = 2;

// Floats as unsigned integers in the same order, so one integer max is a float max.
uint32_t orderable(float f) {
  const auto b = std::bit_cast<uint32_t>(f);
  return (b & 0x80000000u) ? ~b : (b | 0x80000000u);
}
float from_orderable(uint32_t o) { return std::bit_cast<float>((o & 0x80000000u) ? (o & 0x7fffffffu) : ~o); }

using ZBuffer = std::vector<std::atomic<uint64_t>>;

void atomic_max(std::atomic<uint64_t>& slot, uint64_t key) {
  uint64_t cur = slot.load(std::memory_order_relaxed);
  while (key > cur && !slot.compare_exchange_weak(cur, key, std::memory_order_relaxed)) {
  }
}

struct Candidate {
  bool valid = false;
  float depth = 0;  // toward the viewer: t orthoscopic, -t pseudoscopic (less the centre penalty)
  uint32_t src = 0;
};

Candidate decode(uint64_t key) {
  if (key == 0) return {};
  return {true, from_orderable(static_cast<uint32_t>(key >> 32)), static_cast<uint32_t>(key & 0xffffffffu) - 1};
}

class Splatter {
 public:
  Splatter(const RenderContext& scene, const LensArray& camera, const PointImage& key, const ReprojectOptions& opt)
      : scene_(scene), cam_(camera), key_(key), reach_(opt.reach),
        ortho_(camera.desc().mode == RecordingMode::orthoscopic),
        footprint_(camera.pixel_pitch() / camera.desc().gap) {
    // Keyframe array frame -> this frame's array frame, for directions: one
    // 3x3 product per point instead of two frame changes.
    const Frame& a = key.camera.desc().frame;
    const Frame& b = camera.desc().frame;
    const Vec3 from[3] = {a.x, a.y, a.z}, to[3] = {b.x, b.y, b.z};
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) key_to_local_[r][c] = dot(to[r], from[c]);
  }

  void run(ZBuffer& z, int threads) const {
    const LensArray& kc = key_.camera;
    const int W = kc.width(), H = kc.height();
    constexpr int kRows = 8;
    parallel_for_n((H + kRows - 1) / kRows, threads, [&](int block) {
      std::vector<PanelHit> landings;
      for (int j = block * kRows; j < std::min(H, (block + 1) * kRows); ++j)
        for (int i = 0; i < W; ++i) splat_point(i, j, landings, z);
    });
  }

  double footprint(double t) const { return footprint_ * std::fabs(t); }

 private:
  void splat_point(int i, int j, std::vector<PanelHit>& landings, ZBuffer& z) const {
    const LensArray& kc = key_.camera;
    const size_t idx = static_cast<size_t>(j) * kc.width() + i;
    const PrimaryHit& h = key_.hits[idx];
    // A deformed mesh's point has no transform to follow: left missed, traced.
    if (h.status != PrimaryHit::kHit || !key_.same_pose(scene_.accel(), h.group)) return;
    const Vec3 p_object{h.p_object[0], h.p_object[1], h.p_object[2]};
    const Affine& xf = scene_.accel().transform(h.group);
    const Vec3 p_world = xf.is_identity() ? p_object : xf.point(p_object);
    landings.clear();
    if (reach_ == Reach::all) {
      cam_.project(p_world, landings);
    } else {
      // The lens that sees the moved point along the direction the keyframe
      // pixel saw it: there it lands at the same place in the elemental
      // image, whether the camera or the object moved.
      const Vec3 x = cam_.desc().frame.to_local_point(p_world);
      const Vec3 d = kc.line_local(i, j).dir;
      const auto& m = key_to_local_;
      const Vec3 dir{m[0][0] * d.x + m[0][1] * d.y + m[0][2] * d.z, m[1][0] * d.x + m[1][1] * d.y + m[1][2] * d.z,
                     m[2][0] * d.x + m[2][1] * d.y + m[2][2] * d.z};
      PanelHit ph;
      if (cam_.project_along(x, dir, ph)) landings.push_back(ph);
    }
    const int W = cam_.width();
    for (const PanelHit& l : landings) {
      const double d = ortho_ ? l.t : -l.t;
      const double r = std::sqrt((l.u - 0.5) * (l.u - 0.5) + (l.v - 0.5) * (l.v - 0.5));
      const auto score = static_cast<float>(d - kCentrePenalty * r * footprint(l.t));
      const uint64_t k = (uint64_t{orderable(score)} << 32) | (static_cast<uint64_t>(idx) + 1);
      atomic_max(z[static_cast<size_t>(l.j) * W + l.i], k);
    }
  }

  const RenderContext& scene_;
  const LensArray& cam_;
  const PointImage& key_;
  Reach reach_;
  bool ortho_;
  double footprint_;
  double key_to_local_[3][3];
};

using Clock = std::chrono::steady_clock;
double lap(Clock::time_point& t) {
  const auto now = Clock::now();
  const double s = std::chrono::duration<double>(now - t).count();
  t = now;
  return s;
}

void check_key(const RenderContext& scene, const PointImage* k) {
  if (k && k->hits.size() != static_cast<size_t>(k->camera.pixel_count()))
    throw std::invalid_argument(fmt::format("the point image of frame {} has {} records for {} pixels", k->frame,
                                            k->hits.size(), k->camera.pixel_count()));
  if (k && (k->pose.size() != scene.accel().group_count() || k->bounds.size() != scene.accel().group_count()))
    throw std::invalid_argument(fmt::format("the point image of frame {} has {} poses for {} scene groups", k->frame,
                                            k->pose.size(), scene.accel().group_count()));
}

}  // namespace

size_t ReprojectedFrame::count(PixelStatus s) const { return static_cast<size_t>(std::count(status.begin(), status.end(), s)); }

ReprojectedFrame reproject(const RenderContext& scene, const LensArray& camera, int frame, const PointImage* prev,
                           const PointImage* next, const ReprojectOptions& opt) {
  if (!prev && !next) throw std::invalid_argument("reprojection needs at least one keyframe");
  check_key(scene, prev);
  check_key(scene, next);
  const int W = camera.width(), H = camera.height();
  const size_t n = static_cast<size_t>(W) * H;
  const PointImage* keys[2] = {prev, next};
  double w_next = 0;
  if (prev && next && next->frame != prev->frame) w_next = double(frame - prev->frame) / double(next->frame - prev->frame);
  else if (!prev) w_next = 1;

  auto clock = Clock::now();
  // 1-2. Splat each keyframe into its own z-buffer.
  ZBuffer z[2];
  for (int k = 0; k < 2; ++k) {
    if (!keys[k]) continue;
    z[k] = ZBuffer(n);
    Splatter(scene, camera, *keys[k], opt).run(z[k], opt.threads);
  }
  const double splat_seconds = lap(clock);
  const double footprint = camera.pixel_pitch() / camera.desc().gap;
  const double tiny = 1e-7 * std::fmax(1.0, length(scene.bounds().diagonal()));

  ReprojectedFrame out;
  out.seconds.splat = splat_seconds;
  out.colour = ImageBuffer(W, H, 3);
  out.status.assign(n, PixelStatus::missed);
  out.received.assign(n, 0);
  out.object.assign(n, -1);
  std::vector<float> depth(n, 0);
  struct Winner {
    int8_t key = -1;
    uint32_t src = 0;
  };
  std::vector<Winner> winner(n), runner_up(n);
  const Vec3 bg = scene.background();

  // 3. Merge the keyframes.
  const ElementalTiles tiles(camera);
  for_each_tile(tiles, opt.threads, [&](int tile) {
    const TileRect r = tiles.rect(tile);
    for (int j = r.y0; j < r.y1; ++j)
      for (int i = r.x0; i < r.x1; ++i) {
        const size_t p = static_cast<size_t>(j) * W + i;
        Candidate c[2];
        for (int k = 0; k < 2; ++k)
          if (keys[k]) c[k] = decode(z[k][p].load(std::memory_order_relaxed));
        float* o = out.colour.at(i, j);
        o[0] = static_cast<float>(bg.x), o[1] = static_cast<float>(bg.y), o[2] = static_cast<float>(bg.z);
        if (!c[0].valid && !c[1].valid) continue;
        out.received[p] = 1;
        const int best = !c[0].valid ? 1 : !c[1].valid ? 0 : (c[1].depth > c[0].depth ? 1 : 0);
        const float* cb = keys[best]->colour.at(c[best].src % keys[best]->camera.width(), c[best].src / keys[best]->camera.width());
        Vec3 colour{cb[0], cb[1], cb[2]};
        if (c[0].valid && c[1].valid) {
          const PrimaryHit& a = prev->hits[c[0].src];
          const PrimaryHit& b = next->hits[c[1].src];
          const bool same_object = scene.object_of(a.group, static_cast<PrimKind>(a.kind), a.prim) ==
                                   scene.object_of(b.group, static_cast<PrimKind>(b.kind), b.prim);
          const double tol = kSameSurface * footprint * std::fabs(c[best].depth) + tiny;
          if (same_object && std::fabs(c[0].depth - c[1].depth) <= tol) {
            const float* ca = prev->colour.at(c[0].src % prev->camera.width(), c[0].src / prev->camera.width());
            const float* cn = next->colour.at(c[1].src % next->camera.width(), c[1].src / next->camera.width());
            colour = Vec3{ca[0], ca[1], ca[2]} * (1 - w_next) + Vec3{cn[0], cn[1], cn[2]} * w_next;
          }
        }
        o[0] = static_cast<float>(colour.x), o[1] = static_cast<float>(colour.y), o[2] = static_cast<float>(colour.z);
        depth[p] = c[best].depth;
        winner[p] = {static_cast<int8_t>(best), c[best].src};
        if (c[0].valid && c[1].valid) runner_up[p] = {static_cast<int8_t>(1 - best), c[1 - best].src};
        const PrimaryHit& wh = keys[best]->hits[c[best].src];
        out.object[p] = scene.object_of(wh.group, static_cast<PrimKind>(wh.kind), wh.prim);
        out.status[p] = PixelStatus::reprojected;
      }
  });

  // A mesh that deformed since a keyframe has no points to splat where it
  // is now (splat_point leaves them out), so nothing there would hide what
  // it now covers: every elemental image that can see it, where it is or
  // where a keyframe saw it, is traced (lens_reach.hpp).
  std::vector<BoundingSphere> deformed;
  for (const PointImage* key : keys)
    for (uint32_t g = 0; key && g < scene.accel().group_count(); ++g)
      if (!key->same_pose(scene.accel(), g))
        for (const Bounds3& b : {scene.accel().group_bounds(g, scene.accel().transform(g)), key->bounds[g]})
          if (!b.empty()) deformed.push_back({b.centre(), 0.5 * length(b.diagonal())});
  if (!deformed.empty()) {
    const double half_angle = lens_half_angle(camera.desc());
    for_each_tile(tiles, opt.threads, [&](int tile) {
      const TileRect r = tiles.rect(tile);
      for (int j = r.y0; j < r.y1; ++j)
        for (int i = r.x0; i < r.x1; ++i) {
          const size_t p = static_cast<size_t>(j) * W + i;
          if (out.status[p] == PixelStatus::reprojected && lens_reaches(camera, camera.lens_of_pixel(i, j), deformed, half_angle))
            out.status[p] = PixelStatus::missed;
        }
    });
  }
  out.seconds.merge = lap(clock);

  // 4. Leaks: a point seen through a gap between a nearer surface's points
  // has nearer neighbours on two opposite sides in its elemental image.
  std::vector<uint8_t> leak(n, 0);
  if (opt.detect_leaks) {
    for_each_tile(tiles, opt.threads, [&](int tile) {
      const TileRect r = tiles.rect(tile);
      static constexpr int kPairs[4][2][2] = {{{-1, 0}, {1, 0}}, {{0, -1}, {0, 1}}, {{-1, -1}, {1, 1}}, {{-1, 1}, {1, -1}}};
      for (int j = r.y0; j < r.y1; ++j)
        for (int i = r.x0; i < r.x1; ++i) {
          const size_t p = static_cast<size_t>(j) * W + i;
          if (out.status[p] != PixelStatus::reprojected) continue;
          const LensIndex lens = camera.lens_of_pixel(i, j);
          const double tol = kLeakStep * footprint * std::fabs(depth[p]) + tiny;
          auto nearer = [&](int di, int dj) {
            const int ni = i + di, nj = j + dj;
            if (ni < 0 || nj < 0 || ni >= W || nj >= H) return false;
            const size_t q = static_cast<size_t>(nj) * W + ni;
            return out.status[q] == PixelStatus::reprojected && depth[q] - depth[p] > tol &&
                   camera.lens_of_pixel(ni, nj) == lens;
          };
          // Up to two pixels out on each side: gaps can be two pixels wide.
          auto side = [&](int di, int dj) { return nearer(di, dj) || nearer(2 * di, 2 * dj); };
          for (const auto& pair : kPairs) {
            const bool a = side(pair[0][0], pair[0][1]), b = side(pair[1][0], pair[1][1]);
            if (a && b) {
              leak[p] = kLeak;
              break;
            }
            if (a || b) leak[p] = kBehindStep;
          }
        }
    });
  }
  out.seconds.leaks = lap(clock);

  // 5. Local visibility: the pixel's own centre ray against the primitives
  // that landed here and around it (its winner, the other keyframe's
  // candidate, the winners of its 8 neighbours in the same elemental image),
  // each alone and exactly; the nearest hit wins. This resolves silhouettes
  // and surfaces that cross without a BVH traversal. No hit: missed.
  std::vector<RayCounts> tile_rays(static_cast<size_t>(tiles.count()));
  std::vector<double> depth_line(n, 0);  // line t of each checked hit
  const bool ortho = camera.desc().mode == RecordingMode::orthoscopic;
  const double gap = camera.desc().gap;
  for_each_tile(tiles, opt.threads, [&](int tile) {
    const TileRect r = tiles.rect(tile);
    RayCounts counts;
    Winner cands[10];
    for (int j = r.y0; j < r.y1; ++j)
      for (int i = r.x0; i < r.x1; ++i) {
        const size_t p = static_cast<size_t>(j) * W + i;
        if (out.status[p] != PixelStatus::reprojected) continue;
        if (leak[p] == kLeak) {
          out.status[p] = PixelStatus::leak;
          continue;
        }
        int nc = 0;
        auto add = [&](const Winner& w) {
          if (w.key < 0) return;
          const PrimaryHit& h = keys[w.key]->hits[w.src];
          for (int k = 0; k < nc; ++k) {
            const PrimaryHit& o = keys[cands[k].key]->hits[cands[k].src];
            if (o.prim == h.prim && o.group == h.group && o.kind == h.kind) return;
          }
          cands[nc++] = w;
        };
        add(winner[p]);
        add(runner_up[p]);
        const LensIndex lens = camera.lens_of_pixel(i, j);
        for (int dj = -1; dj <= 1 && opt.local_visibility; ++dj)
          for (int di = -1; di <= 1; ++di) {
            const int ni = i + di, nj = j + dj;
            if ((di == 0 && dj == 0) || ni < 0 || nj < 0 || ni >= W || nj >= H) continue;
            const size_t q = static_cast<size_t>(nj) * W + ni;
            if (winner[q].key >= 0 && leak[q] != kLeak && camera.lens_of_pixel(ni, nj) == lens) add(winner[q]);
          }
        const auto pr = primary_ray(camera, scene.bounds(), scene.epsilon(), i, j);
        Hit best, hit;
        int chosen = -1;
        for (int k = 0; pr && k < nc; ++k) {
          const PrimaryHit& h = keys[cands[k].key]->hits[cands[k].src];
          if (scene.accel().intersect_primitive(pr->ray, h.group, static_cast<PrimKind>(h.kind), h.prim, hit) &&
              hit.t < best.t) {
            best = hit;
            chosen = k;
          }
        }
        if (chosen < 0) {
          out.status[p] = PixelStatus::rejected;
          continue;
        }
        // The slab |t| < g about the array is seen by at most one lens per
        // point (cones narrower than the pitch), so keyframes sample it with
        // gaps: a surface there may have left no point. One short occlusion
        // ray across the slab, in front of the hit, settles it.
        // Behind a depth step, the nearer surface may cover the pixel centre
        // with none of its primitives nearby: check the whole way to the hit.
        if (leak[p] == kBehindStep) {
          Ray front = pr->ray;
          front.tfar = best.t - scene.epsilon();
          if (front.tfar > front.tnear && scene.accel().occluded(front)) {
            out.status[p] = PixelStatus::leak;
            continue;
          }
        } else if (opt.check_near_slab) {
          const double t_line = pr->t_offset + pr->t_sign * best.t;
          const double eps = scene.epsilon();
          Ray slab = pr->ray;
          if (ortho) {
            slab.tnear = std::fmax(pr->ray.tnear, pr->t_offset - gap);
            slab.tfar = pr->t_offset - std::fmax(t_line, -gap) - eps;
          } else {
            slab.tfar = std::fmin(best.t, gap) - eps;
          }
          if (slab.tfar > slab.tnear && scene.accel().occluded(slab)) {
            out.status[p] = PixelStatus::rejected;
            continue;
          }
        }
        float* o = out.colour.at(i, j);
        if (opt.reuse == Reuse::geometry) {
          const Vec3 c = shade(scene, pr->ray, scene.surface(pr->ray, best), 1, counts);
          o[0] = static_cast<float>(c.x), o[1] = static_cast<float>(c.y), o[2] = static_cast<float>(c.z);
        } else if (chosen > 0) {
          const PointImage& key = *keys[cands[chosen].key];
          const float* c = key.colour.at(cands[chosen].src % key.camera.width(), cands[chosen].src / key.camera.width());
          o[0] = c[0], o[1] = c[1], o[2] = c[2];
        }
        out.object[p] = scene.object_of(best.group, best.kind, best.prim);
        depth_line[p] = pr->t_offset + pr->t_sign * best.t;
      }
    tile_rays[static_cast<size_t>(tile)] = counts;
  });
  for (const RayCounts& c : tile_rays) out.rays += c;

  // 6. Grow the occluded regions: a pixel found hidden behind a silhouette
  // makes its neighbours in the same elemental image suspect too (a nearer
  // surface that grew since the keyframe covers a patch, not a pixel). Each
  // suspect gets the same occlusion ray; the flood stops where none is hidden.
  if (opt.detect_leaks) {
    for_each_tile(tiles, opt.threads, [&](int tile) {
      const TileRect r = tiles.rect(tile);
      std::vector<size_t> queue;
      for (int j = r.y0; j < r.y1; ++j)
        for (int i = r.x0; i < r.x1; ++i)
          if (out.status[static_cast<size_t>(j) * W + i] == PixelStatus::leak) queue.push_back(static_cast<size_t>(j) * W + i);
      std::vector<uint8_t> tested(static_cast<size_t>(r.x1 - r.x0) * (r.y1 - r.y0), 0);
      while (!queue.empty()) {
        const size_t p = queue.back();
        queue.pop_back();
        const int i = static_cast<int>(p % W), j = static_cast<int>(p / W);
        const LensIndex lens = camera.lens_of_pixel(i, j);
        for (int dj = -1; dj <= 1; ++dj)
          for (int di = -1; di <= 1; ++di) {
            const int ni = i + di, nj = j + dj;
            if (ni < r.x0 || nj < r.y0 || ni >= r.x1 || nj >= r.y1) continue;
            const size_t q = static_cast<size_t>(nj) * W + ni;
            uint8_t& seen = tested[static_cast<size_t>(nj - r.y0) * (r.x1 - r.x0) + (ni - r.x0)];
            if (seen || out.status[q] != PixelStatus::reprojected || !(camera.lens_of_pixel(ni, nj) == lens)) continue;
            seen = 1;
            const auto pr = primary_ray(camera, scene.bounds(), scene.epsilon(), ni, nj);
            if (!pr) continue;
            // The shown surface's line t, back to this ray's parameter.
            Ray front = pr->ray;
            front.tfar = (depth_line[q] - pr->t_offset) / pr->t_sign - scene.epsilon();
            if (front.tfar > front.tnear && scene.accel().occluded(front)) {
              out.status[q] = PixelStatus::leak;
              queue.push_back(q);
            }
          }
      }
    });
  }
  out.seconds.check = lap(clock);
  return out;
}

}  // namespace holoray
