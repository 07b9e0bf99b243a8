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

namespace {

// One frame's reprojection (reproject() below), its steps in order over
// the state they share: the keyframes' z-buffers, the merged candidates per
// pixel and the frame being built.
class Reprojection {
 public:
  Reprojection(const RenderContext& scene, const LensArray& camera, int frame, const PointImage* prev,
               const PointImage* next, const ReprojectOptions& opt)
      : scene_(scene), camera_(camera), opt_(opt), keys_{prev, next}, W_(camera.width()), H_(camera.height()),
        n_(static_cast<size_t>(W_) * H_), tiles_(camera),
        footprint_(camera.pixel_pitch() / camera.desc().gap),
        tiny_(1e-7 * std::fmax(1.0, length(scene.bounds().diagonal()))) {
    if (prev && next && next->frame != prev->frame) w_next_ = double(frame - prev->frame) / double(next->frame - prev->frame);
    else if (!prev) w_next_ = 1;
  }

  /// 1-2. Each keyframe splatted into its own z-buffer.
  void splat() {
    for (int k = 0; k < 2; ++k) {
      if (!keys_[k]) continue;
      z_[k] = ZBuffer(n_);
      Splatter(scene_, camera_, *keys_[k], opt_).run(z_[k], opt_.threads);
    }
  }

  /// 3. The keyframes merged: per pixel the nearer candidate, blended with
  /// the other where both show the same surface.
  void merge() {
    out_.colour = ImageBuffer(W_, H_, 3);
    out_.status.assign(n_, PixelStatus::missed);
    out_.received.assign(n_, 0);
    out_.object.assign(n_, -1);
    depth_.assign(n_, 0);
    winner_.assign(n_, {});
    runner_up_.assign(n_, {});
    const Vec3 bg = scene_.background();
    const PointImage* prev = keys_[0];
    const PointImage* next = keys_[1];
    for_each_pixel([&](int i, int j, size_t p) {
      Candidate c[2];
      for (int k = 0; k < 2; ++k)
        if (keys_[k]) c[k] = decode(z_[k][p].load(std::memory_order_relaxed));
      float* o = out_.colour.at(i, j);
      o[0] = static_cast<float>(bg.x), o[1] = static_cast<float>(bg.y), o[2] = static_cast<float>(bg.z);
      if (!c[0].valid && !c[1].valid) return;
      out_.received[p] = 1;
      const int best = !c[0].valid ? 1 : !c[1].valid ? 0 : (c[1].depth > c[0].depth ? 1 : 0);
      Vec3 colour = key_colour(*keys_[best], c[best].src);
      if (c[0].valid && c[1].valid) {
        const PrimaryHit& a = prev->hits[c[0].src];
        const PrimaryHit& b = next->hits[c[1].src];
        const bool same_object = scene_.object_of(a.group, static_cast<PrimKind>(a.kind), a.prim) ==
                                 scene_.object_of(b.group, static_cast<PrimKind>(b.kind), b.prim);
        const double tol = kSameSurface * footprint_ * std::fabs(c[best].depth) + tiny_;
        if (same_object && std::fabs(c[0].depth - c[1].depth) <= tol)
          colour = key_colour(*prev, c[0].src) * (1 - w_next_) + key_colour(*next, c[1].src) * w_next_;
      }
      o[0] = static_cast<float>(colour.x), o[1] = static_cast<float>(colour.y), o[2] = static_cast<float>(colour.z);
      depth_[p] = c[best].depth;
      winner_[p] = {static_cast<int8_t>(best), c[best].src};
      if (c[0].valid && c[1].valid) runner_up_[p] = {static_cast<int8_t>(1 - best), c[1 - best].src};
      const PrimaryHit& wh = keys_[best]->hits[c[best].src];
      out_.object[p] = scene_.object_of(wh.group, static_cast<PrimKind>(wh.kind), wh.prim);
      out_.status[p] = PixelStatus::reprojected;
    });
  }

  /// A mesh that deformed since a keyframe has no points to splat where it
  /// is now (splat_point leaves them out), so nothing there would hide what
  /// it now covers: every elemental image that can see it, where it is or
  /// where a keyframe saw it, is traced (lens_reach.hpp).
  void trace_where_meshes_deformed() {
    const AccelScene& accel = scene_.accel();
    std::vector<BoundingSphere> deformed;
    for (const PointImage* key : keys_)
      for (uint32_t g = 0; key && g < accel.group_count(); ++g)
        if (!key->same_pose(accel, g))
          for (const Bounds3& b : {accel.group_bounds(g, accel.transform(g)), key->bounds[g]})
            if (!b.empty()) deformed.push_back({b.centre(), 0.5 * length(b.diagonal())});
    if (deformed.empty()) return;
    const double half_angle = lens_half_angle(camera_.desc());
    for_each_pixel([&](int i, int j, size_t p) {
      if (out_.status[p] == PixelStatus::reprojected && lens_reaches(camera_, camera_.lens_of_pixel(i, j), deformed, half_angle))
        out_.status[p] = PixelStatus::missed;
    });
  }

  /// 4. Leaks: a point seen through a gap between a nearer surface's points
  /// has nearer neighbours on two opposite sides in its elemental image.
  void find_leaks() {
    leak_.assign(n_, 0);
    if (!opt_.detect_leaks) return;
    static constexpr int kPairs[4][2][2] = {{{-1, 0}, {1, 0}}, {{0, -1}, {0, 1}}, {{-1, -1}, {1, 1}}, {{-1, 1}, {1, -1}}};
    for_each_pixel([&](int i, int j, size_t p) {
      if (out_.status[p] != PixelStatus::reprojected) return;
      const LensIndex lens = camera_.lens_of_pixel(i, j);
      const double tol = kLeakStep * footprint_ * std::fabs(depth_[p]) + tiny_;
      auto nearer = [&](int di, int dj) {
        const int ni = i + di, nj = j + dj;
        if (ni < 0 || nj < 0 || ni >= W_ || nj >= H_) return false;
        const size_t q = static_cast<size_t>(nj) * W_ + ni;
        return out_.status[q] == PixelStatus::reprojected && depth_[q] - depth_[p] > tol &&
               camera_.lens_of_pixel(ni, nj) == lens;
      };
      // Up to two pixels out on each side: gaps can be two pixels wide.
      auto side = [&](int di, int dj) { return nearer(di, dj) || nearer(2 * di, 2 * dj); };
      for (const auto& pair : kPairs) {
        const bool a = side(pair[0][0], pair[0][1]), b = side(pair[1][0], pair[1][1]);
        if (a && b) {
          leak_[p] = kLeak;
          break;
        }
        if (a || b) leak_[p] = kBehindStep;
      }
    });
  }

  /// 5. Local visibility: the pixel's own centre ray against the primitives
  /// that landed here and around it (its winner, the other keyframe's
  /// candidate, the winners of its 8 neighbours in the same elemental
  /// image), each alone and exactly; the nearest hit wins. This resolves
  /// silhouettes and surfaces that cross without a BVH traversal. No hit:
  /// missed.
  void check_visibility() {
    std::vector<RayCounts> tile_rays(static_cast<size_t>(tiles_.count()));
    depth_line_.assign(n_, 0);
    for_each_tile(tiles_, opt_.threads, [&](int tile) {
      const TileRect r = tiles_.rect(tile);
      RayCounts counts;
      for (int j = r.y0; j < r.y1; ++j)
        for (int i = r.x0; i < r.x1; ++i) check_pixel(i, j, counts);
      tile_rays[static_cast<size_t>(tile)] = counts;
    });
    for (const RayCounts& c : tile_rays) out_.rays += c;
  }

  /// 6. The occluded regions grown: a pixel found hidden behind a silhouette
  /// makes its neighbours in the same elemental image suspect too (a nearer
  /// surface that grew since the keyframe covers a patch, not a pixel). Each
  /// suspect gets the same occlusion ray; the flood stops where none is hidden.
  void grow_occlusions() {
    if (!opt_.detect_leaks) return;
    for_each_tile(tiles_, opt_.threads, [&](int tile) {
      const TileRect r = tiles_.rect(tile);
      std::vector<size_t> queue;
      for (int j = r.y0; j < r.y1; ++j)
        for (int i = r.x0; i < r.x1; ++i)
          if (out_.status[static_cast<size_t>(j) * W_ + i] == PixelStatus::leak) queue.push_back(static_cast<size_t>(j) * W_ + i);
      std::vector<uint8_t> tested(static_cast<size_t>(r.x1 - r.x0) * (r.y1 - r.y0), 0);
      while (!queue.empty()) {
        const size_t p = queue.back();
        queue.pop_back();
        const int i = static_cast<int>(p % W_), j = static_cast<int>(p / W_);
        const LensIndex lens = camera_.lens_of_pixel(i, j);
        for (int dj = -1; dj <= 1; ++dj)
          for (int di = -1; di <= 1; ++di) {
            const int ni = i + di, nj = j + dj;
            if (ni < r.x0 || nj < r.y0 || ni >= r.x1 || nj >= r.y1) continue;
            const size_t q = static_cast<size_t>(nj) * W_ + ni;
            uint8_t& seen = tested[static_cast<size_t>(nj - r.y0) * (r.x1 - r.x0) + (ni - r.x0)];
            if (seen || out_.status[q] != PixelStatus::reprojected || !(camera_.lens_of_pixel(ni, nj) == lens)) continue;
            seen = 1;
            const auto pr = primary_ray(camera_, scene_.bounds(), scene_.epsilon(), ni, nj);
            if (!pr) continue;
            // The shown surface's line t, back to this ray's parameter.
            Ray front = pr->ray;
            front.tfar = (depth_line_[q] - pr->t_offset) / pr->t_sign - scene_.epsilon();
            if (front.tfar > front.tnear && scene_.accel().occluded(front)) {
              out_.status[q] = PixelStatus::leak;
              queue.push_back(q);
            }
          }
      }
    });
  }

  ReprojectedFrame& frame() { return out_; }

 private:
  struct Winner {
    int8_t key = -1;
    uint32_t src = 0;
  };

  // fn(i, j, p) for every pixel, tile by tile (elemental images) on the workers.
  template <class Fn>
  void for_each_pixel(Fn&& fn) {
    for_each_tile(tiles_, opt_.threads, [&](int tile) {
      const TileRect r = tiles_.rect(tile);
      for (int j = r.y0; j < r.y1; ++j)
        for (int i = r.x0; i < r.x1; ++i) fn(i, j, static_cast<size_t>(j) * W_ + i);
    });
  }

  static Vec3 key_colour(const PointImage& key, uint32_t src) {
    const float* c = key.colour.at(src % key.camera.width(), src / key.camera.width());
    return {c[0], c[1], c[2]};
  }

  // Step 5 for pixel (i, j).
  void check_pixel(int i, int j, RayCounts& counts) {
    const size_t p = static_cast<size_t>(j) * W_ + i;
    if (out_.status[p] != PixelStatus::reprojected) return;
    if (leak_[p] == kLeak) {
      out_.status[p] = PixelStatus::leak;
      return;
    }
    Winner cands[10];
    int nc = 0;
    auto add = [&](const Winner& w) {
      if (w.key < 0) return;
      const PrimaryHit& h = keys_[w.key]->hits[w.src];
      for (int k = 0; k < nc; ++k) {
        const PrimaryHit& o = keys_[cands[k].key]->hits[cands[k].src];
        if (o.prim == h.prim && o.group == h.group && o.kind == h.kind) return;
      }
      cands[nc++] = w;
    };
    add(winner_[p]);
    add(runner_up_[p]);
    const LensIndex lens = camera_.lens_of_pixel(i, j);
    for (int dj = -1; dj <= 1 && opt_.local_visibility; ++dj)
      for (int di = -1; di <= 1; ++di) {
        const int ni = i + di, nj = j + dj;
        if ((di == 0 && dj == 0) || ni < 0 || nj < 0 || ni >= W_ || nj >= H_) continue;
        const size_t q = static_cast<size_t>(nj) * W_ + ni;
        if (winner_[q].key >= 0 && leak_[q] != kLeak && camera_.lens_of_pixel(ni, nj) == lens) add(winner_[q]);
      }
    const auto pr = primary_ray(camera_, scene_.bounds(), scene_.epsilon(), i, j);
    Hit best, hit;
    int chosen = -1;
    for (int k = 0; pr && k < nc; ++k) {
      const PrimaryHit& h = keys_[cands[k].key]->hits[cands[k].src];
      if (scene_.accel().intersect_primitive(pr->ray, h.group, static_cast<PrimKind>(h.kind), h.prim, hit) &&
          hit.t < best.t) {
        best = hit;
        chosen = k;
      }
    }
    if (chosen < 0) {
      out_.status[p] = PixelStatus::rejected;
      return;
    }
    if (hidden_in_front(*pr, best, leak_[p] == kBehindStep, out_.status[p])) return;
    float* o = out_.colour.at(i, j);
    if (opt_.reuse == Reuse::geometry) {
      const Vec3 c = shade(scene_, pr->ray, scene_.surface(pr->ray, best), 1, counts);
      o[0] = static_cast<float>(c.x), o[1] = static_cast<float>(c.y), o[2] = static_cast<float>(c.z);
    } else if (chosen > 0) {
      const Vec3 c = key_colour(*keys_[cands[chosen].key], cands[chosen].src);
      o[0] = static_cast<float>(c.x), o[1] = static_cast<float>(c.y), o[2] = static_cast<float>(c.z);
    }
    out_.object[p] = scene_.object_of(best.group, best.kind, best.prim);
    depth_line_[p] = pr->t_offset + pr->t_sign * best.t;
  }

  // Whether something the keyframes missed stands in front of `best` on the
  // pixel's ray (then `status` says leak or rejected). The slab |t| < g
  // about the array is seen by at most one lens per point (cones narrower
  // than the pitch), so keyframes sample it with gaps: a surface there may
  // have left no point; one short occlusion ray across the slab, in front of
  // the hit, settles it. Behind a depth step (`behind_step`), the nearer
  // surface may cover the pixel centre with none of its primitives nearby:
  // the ray checks the whole way to the hit.
  bool hidden_in_front(const PrimaryRay& pr, const Hit& best, bool behind_step, PixelStatus& status) const {
    const double eps = scene_.epsilon();
    if (behind_step) {
      Ray front = pr.ray;
      front.tfar = best.t - eps;
      if (front.tfar > front.tnear && scene_.accel().occluded(front)) {
        status = PixelStatus::leak;
        return true;
      }
      return false;
    }
    if (!opt_.check_near_slab) return false;
    const double gap = camera_.desc().gap;
    const double t_line = pr.t_offset + pr.t_sign * best.t;
    Ray slab = pr.ray;
    if (camera_.desc().mode == RecordingMode::orthoscopic) {
      slab.tnear = std::fmax(pr.ray.tnear, pr.t_offset - gap);
      slab.tfar = pr.t_offset - std::fmax(t_line, -gap) - eps;
    } else {
      slab.tfar = std::fmin(best.t, gap) - eps;
    }
    if (slab.tfar > slab.tnear && scene_.accel().occluded(slab)) {
      status = PixelStatus::rejected;
      return true;
    }
    return false;
  }

  const RenderContext& scene_;
  const LensArray& camera_;
  const ReprojectOptions& opt_;
  const PointImage* keys_[2];
  const int W_, H_;
  const size_t n_;
  const ElementalTiles tiles_;
  const double footprint_;  // a pixel's angle through its lens
  const double tiny_;       // depth tolerance floor, scaled to the scene
  double w_next_ = 0;       // the next keyframe's weight in a blend
  ZBuffer z_[2];
  ReprojectedFrame out_;
  std::vector<float> depth_;          // the winner's depth
  std::vector<Winner> winner_, runner_up_;
  std::vector<uint8_t> leak_;         // kLeak, kBehindStep or 0
  std::vector<double> depth_line_;    // line t of each checked hit
};

}  // namespace

ReprojectedFrame reproject(const RenderContext& scene, const LensArray& camera, int frame, const PointImage* prev,
                           const PointImage* next, const ReprojectOptions& opt) {
  if (!prev && !next) throw std::invalid_argument("reprojection needs at least one keyframe");
  scene.accel().build();  // before the tiles, on all cores (AccelScene::build)
  check_key(scene, prev);
  check_key(scene, next);
  Reprojection r(scene, camera, frame, prev, next, opt);
  auto clock = Clock::now();
  r.splat();
  r.frame().seconds.splat = lap(clock);
  r.merge();
  r.trace_where_meshes_deformed();
  r.frame().seconds.merge = lap(clock);
  r.find_leaks();
  r.frame().seconds.leaks = lap(clock);
  r.check_visibility();
  r.grow_occlusions();
  r.frame().seconds.check = lap(clock);
  return std::move(r.frame());
}

}  // namespace holoray
