#include "temporal/reverse.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <utility>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "render/renderer.hpp"
#include "render/shading.hpp"
#include "render/tiles.hpp"
#include "temporal/lens_reach.hpp"

namespace holoray {

namespace {

// One keyframe, ready for lookups: its camera, its records, and per scene
// group the map from the frame's world to the keyframe's world.
struct Key {
  const PointImage* image = nullptr;
  std::vector<Affine> now_to_key;  // per group: key to_world * current to_object
  std::vector<uint8_t> moved;      // per group: now_to_key is not the identity, or deformed
  std::vector<uint8_t> deformed;   // per group: its vertices changed (no transform maps its hits)
  bool anything_moved = false;
  double footprint = 0;  // s / g of the keyframe camera
  // Bounding spheres (world centre, radius) of the groups moved since the
  // keyframe, where they are now and where the keyframe saw them.
  std::vector<BoundingSphere> moved_spheres;
};

// What a lookup needs of an eye-ray hit: where (world), in which scene
// group (whose motion maps it back) and on which object.
struct EyeHit {
  Vec3 position;
  uint32_t group = 0;
  int object = -1;
};

// Where keyframe pixel idx and its 8 neighbours in the same elemental
// image on the same primitive disagree, an edge may cross the pixel's own
// point: `shadow` gets the lights whose visibility changes (their shadow
// rays are traced), `secondary` whether the light of the mirror and
// refraction rays changes by more than kSecondaryStep (they are traced).
// Worked out once per pixel when the keyframe is traced (trace_point_image):
// up to 14 frames look each keyframe pixel up.
constexpr float kSecondaryStep = 1.0f / 255;
PointImage::Edges pixel_edges(const PointImage& key, size_t idx) {
  PointImage::Edges e;
  const LensArray& kc = key.camera;
  const int W = kc.width(), H = kc.height();
  const int i = static_cast<int>(idx % W), j = static_cast<int>(idx / W);
  const LensIndex lens = kc.lens_of_pixel(i, j);
  const ShadeParts& own_parts = key.parts[idx];
  const PrimaryHit& own = key.hits[idx];
  bool secondary = false;
  for (int dj = -1; dj <= 1; ++dj)
    for (int di = -1; di <= 1; ++di) {
      const int ni = i + di, nj = j + dj;
      if ((di == 0 && dj == 0) || ni < 0 || nj < 0 || ni >= W || nj >= H || !kc.pixel_in_lens(ni, nj, lens)) continue;
      const size_t q = static_cast<size_t>(nj) * W + ni;
      const PrimaryHit& h = key.hits[q];
      if (h.status != PrimaryHit::kHit || h.prim != own.prim || h.group != own.group || h.kind != own.kind) continue;
      const ShadeParts& p = key.parts[q];
      e.shadow |= p.lit ^ own_parts.lit;
      for (int c = 0; c < 3; ++c) secondary |= std::fabs(p.secondary[c] - own_parts.secondary[c]) > kSecondaryStep;
    }
  e.secondary = secondary;
  return e;
}

// Answers the hits of a reprojected frame from its keyframes. Called from
// worker threads: const and thread-safe.
class PointImageLookup {
 public:
  PointImageLookup(const RenderContext& scene, const LensArray& camera, const PointImage* prev, const PointImage* next,
                   double w_next, const ReverseOptions& opt)
      : scene_(scene), same_surface_(opt.same_surface),
        tiny_(1e-7 * std::fmax(1.0, length(scene.bounds().diagonal()))) {
    // The keyframe nearer in time first.
    const PointImage* images[2] = {prev, next};
    if (w_next > 0.5) std::swap(images[0], images[1]);
    const size_t groups = scene.accel().group_count();
    for (int k = 0; k < 2; ++k) {
      if (!images[k]) continue;
      Key& key = keys_[k];
      key.image = images[k];
      key.footprint = images[k]->camera.pixel_pitch() / images[k]->camera.desc().gap;
      key.now_to_key.resize(groups);
      key.moved.resize(groups);
      key.deformed.resize(groups);
      for (size_t g = 0; g < groups; ++g) {
        const auto group = static_cast<uint32_t>(g);
        key.now_to_key[g] = images[k]->to_world[g] * scene.accel().inverse_transform(group);
        key.deformed[g] = !images[k]->same_pose(scene.accel(), group);
        key.moved[g] = !key.now_to_key[g].is_identity() || key.deformed[g];
        key.anything_moved |= key.moved[g] != 0;
        if (!key.moved[g]) continue;
        for (const Bounds3& b : {scene.accel().group_bounds(group, scene.accel().transform(group)), images[k]->bounds[g]})
          if (!b.empty()) key.moved_spheres.push_back({b.centre(), 0.5 * length(b.diagonal())});
      }
      // The frame's camera: every pixel has its keyframe pixel's line.
      if (!same_camera_ && camera.desc().grid == Grid::square && images[k]->camera.desc() == camera.desc())
        same_camera_ = &key;
    }
    lens_half_angle_ = lens_half_angle(camera.desc());
  }

  // A keyframe with the frame's own camera on a square grid (a locked-off
  // shot whose objects move), whose elemental images lens_unchanged() may
  // copy; null otherwise.
  const PointImage* same_camera_image() const { return same_camera_ ? same_camera_->image : nullptr; }

  // Elemental image `lens` of same_camera_image() is this frame's: no line
  // of the lens (through its centre, within its field of view, either way
  // along it) meets a group that moved since that keyframe, where the group
  // is now or where the keyframe saw it; each line then meets what it met in
  // the keyframe, and its colour reuse would read its own keyframe pixel
  // (lens_reach.hpp: tested against the groups' bounding spheres).
  bool lens_unchanged(const LensArray& camera, LensIndex lens) const {
    if (!same_camera_) return false;
    return !lens_reaches(camera, lens, same_camera_->moved_spheres, lens_half_angle_);
  }

  // The colour of an eye-ray hit from the keyframes with visibility reuse,
  // true when they have it: `ray` the eye ray, `line_dir` the pixel's line
  // direction (world, unit, toward the viewer's side of the array); rays
  // traced go to `counts`. Where the light of the mirror and refraction
  // rays changes around the keyframe pixel, `colour` gets the local terms
  // alone and `secondary` is set: the caller traces those rays, packets of
  // them at a time. (Colour reuse: filtered_colour.)
  bool find(const Ray& ray, const Vec3& line_dir, const Hit& hit, const SurfacePoint& sp, RayCounts& counts,
            Vec3& colour, bool& secondary) const {
    for (const Key& key : keys_) {
      if (!key.image || key.anything_moved) continue;
      PanelHit ph;
      const size_t idx = locate(key, line_dir, {sp.position, hit.group, sp.object}, ph);
      if (idx == kNone) continue;
      const ShadeParts& parts = key.image->parts[idx];
      const PointImage::Edges& e = key.image->edges[idx];
      colour = shade_local(scene_, ray, sp, parts.lit, e.shadow, counts);
      secondary = e.secondary;
      if (!secondary) colour += Vec3{parts.secondary[0], parts.secondary[1], parts.secondary[2]};
      return true;
    }
    return false;
  }

  static constexpr size_t kNone = ~size_t{0};

  // The keyframe pixel that saw this hit, or kNone; `ph` gets where the
  // hit lands on the keyframe's panel, `landing` (optional) its lens.
  size_t locate(const Key& key, const Vec3& line_dir, const EyeHit& hit, PanelHit& ph,
                LensIndex* landing = nullptr) const {
    const LensArray& kc = key.image->camera;
    const Frame& kf = kc.desc().frame;
    Vec3 p = hit.position, d = line_dir;
    if (key.deformed[hit.group]) return kNone;
    if (key.moved[hit.group]) {
      const Affine& m = key.now_to_key[hit.group];
      p = m.point(p);
      d = m.dir(d);
    }
    const Vec3 x = kf.to_local_point(p);
    const Vec3 dl = kf.to_local_dir(d);
    if (!(dl.z > 0)) return kNone;
    if (!kc.project_along(x, dl, ph, landing)) return kNone;
    const size_t idx = static_cast<size_t>(ph.j) * kc.width() + ph.i;
    return same_surface(key, idx, hit.object, ph.t) ? idx : kNone;
  }

  // Keyframe pixel idx saw object `object` at line parameter t (within
  // same_surface_ footprints).
  bool same_surface(const Key& key, size_t idx, int object, double t) const {
    const PointImage::Seen& rec = key.image->seen[idx];
    return rec.object == object && object >= 0 &&
           std::fabs(rec.t - t) <= same_surface_ * key.footprint * std::fabs(t) + tiny_;
  }

  // Colour reuse, filtered as Nehab et al. filter their cache: the bilinear
  // weights of the 2 x 2 pixels of the landing lens around the landing
  // point, over those that saw the same surface (the nearest one must), in
  // the nearer keyframe that has it. Nearest-pixel reuse errs by up to half
  // a footprint in position and half a pixel in direction; the filter makes
  // that error second order where shading is smooth. Measured (bench shots,
  // K = 8): +0.6 to +1.3 dB for 2 to 5 points of time saved. Blending both
  // keyframes by time gave +0.6 dB more but cost a second lookup per hit,
  // more than it saved.
  bool filtered_colour(const Vec3& line_dir, const EyeHit& hit, Vec3& colour) const {
    for (const Key& key : keys_) {
      if (!key.image) continue;
      PanelHit ph;
      LensIndex lens;
      const size_t idx = locate(key, line_dir, hit, ph, &lens);
      if (idx == kNone) continue;
      const LensArray& kc = key.image->camera;
      const double fx = ph.u - 0.5, fy = ph.v - 0.5;
      const int i0 = ph.i + (fx < 0 ? -1 : 0), j0 = ph.j + (fy < 0 ? -1 : 0);
      const double wx = fx < 0 ? fx + 1 : fx, wy = fy < 0 ? fy + 1 : fy;
      Vec3 c{0, 0, 0};
      double w = 0;
      for (int b = 0; b < 2; ++b)
        for (int a = 0; a < 2; ++a) {
          const int i = i0 + a, j = j0 + b;
          const double wa = (a ? wx : 1 - wx) * (b ? wy : 1 - wy);
          if (wa <= 0 || i < 0 || j < 0 || i >= kc.width() || j >= kc.height() || !kc.pixel_in_lens(i, j, lens))
            continue;
          const size_t q = static_cast<size_t>(j) * kc.width() + i;
          if (q != idx && !same_surface(key, q, hit.object, ph.t)) continue;
          const float* k = key.image->colour.data.data() + 3 * q;
          c += Vec3{k[0], k[1], k[2]} * wa;
          w += wa;
        }
      colour = c / w;  // w >= 0.25: the nearest pixel's weight
      return true;
    }
    return false;
  }

  const RenderContext& scene_;
  Key keys_[2];
  const Key* same_camera_ = nullptr;  // the first of keys_ with the frame's camera (square grid)
  double same_surface_, tiny_;
  double lens_half_angle_ = 0;
};

void check_key(const RenderContext& scene, const PointImage* k, ReverseReuse reuse) {
  if (!k) return;
  const auto pixels = static_cast<size_t>(k->camera.pixel_count());
  if (k->hits.size() != pixels)
    throw std::invalid_argument(
        fmt::format("the point image of frame {} has {} records for {} pixels", k->frame, k->hits.size(), pixels));
  const size_t groups = scene.accel().group_count();
  if (k->to_world.size() != groups || k->pose.size() != groups || k->bounds.size() != groups)
    throw std::invalid_argument(fmt::format("the point image of frame {} has {} transforms for {} scene groups",
                                            k->frame, k->to_world.size(), groups));
  if (k->seen.size() != pixels)
    throw std::invalid_argument(
        fmt::format("the point image of frame {} has {} object ids for {} pixels", k->frame, k->seen.size(), pixels));
  if (reuse == ReverseReuse::visibility && k->parts.size() != pixels)
    throw std::invalid_argument(fmt::format(
        "the point image of frame {} has {} shading records for {} pixels: trace it for visibility reuse", k->frame,
        k->parts.size(), pixels));
  if (reuse == ReverseReuse::visibility && k->edges.size() != pixels)
    throw std::invalid_argument(fmt::format(
        "the point image of frame {} has {} edge records for {} pixels: trace it for visibility reuse", k->frame,
        k->edges.size(), pixels));
}

void store(ImageBuffer& image, size_t p, const Vec3& c) {
  float* o = image.data.data() + 3 * p;
  o[0] = static_cast<float>(c.x), o[1] = static_cast<float>(c.y), o[2] = static_cast<float>(c.z);
}

// The hits that no keyframe answered, gathered from successive packets of
// a tile and shaded 16 at a time: shading (shadow, mirror and refraction
// rays) runs as packets whose cost hardly depends on how many lanes are
// active, so shading the leftover lanes of each packet where they stand
// would cost nearly a full frame's shading whatever the reuse. A queue of
// `secondary_only` lanes traces only their mirror and refraction rays and
// adds that light to the colour each was pushed with (visibility reuse's
// local terms): off a flat mirror they are a coherent packet, which one by
// one cost the teapot shot more than tracing the frame in full.
class ShadeQueue {
 public:
  explicit ShadeQueue(bool secondary_only = false) : secondary_only_(secondary_only) {}
  void push(const Ray& ray, const SurfacePoint& sp, size_t pixel, const Vec3& base = {}) {
    rays_.rays[n_] = ray;
    rays_.active[n_] = true;
    sp_[n_] = sp;
    pixel_[n_] = pixel;
    base_[n_] = base;
    ++n_;
  }
  bool full() const { return n_ == kPacketSize; }
  void flush(const RenderContext& scene, RayCounts& counts, ImageBuffer& colour) {
    if (n_ == 0) return;
    bool hit[kPacketSize] = {};
    std::fill(hit, hit + n_, true);
    Vec3 c[kPacketSize];
    if (secondary_only_) {
      shade_secondary(scene, rays_, hit, sp_, 1, counts, c);
      for (int l = 0; l < n_; ++l) store(colour, pixel_[l], base_[l] + c[l]);
    } else {
      shade(scene, rays_, hit, sp_, 1, counts, c);
      for (int l = 0; l < n_; ++l) store(colour, pixel_[l], c[l]);
    }
    rays_ = RayPacket{};
    n_ = 0;
  }

 private:
  bool secondary_only_;
  RayPacket rays_;
  SurfacePoint sp_[kPacketSize];
  size_t pixel_[kPacketSize] = {};
  Vec3 base_[kPacketSize];
  int n_ = 0;
};

// Pixel p of a keyframe as the frame's own (nothing on its line changed):
// its colour and object; a surface counts as reprojected, background as
// traced (as a traced eye ray that met nothing would).
void take_pixel(ReprojectedFrame& out, const PointImage& key, size_t p) {
  std::copy_n(key.colour.data.data() + 3 * p, 3, out.colour.data.data() + 3 * p);
  out.object[p] = key.seen[p].object;
  if (key.seen[p].object >= 0) out.status[p] = PixelStatus::reprojected, out.received[p] = 1;
}

// Frame setup shared by keyframes and reprojected frames. Each of them
// writes every pixel's colour (the packets cover every tile's rectangle;
// a copy takes every pixel), so the colour is left unset.
ReprojectedFrame blank_frame(const LensArray& camera) {
  const size_t n = static_cast<size_t>(camera.pixel_count());
  ReprojectedFrame out;
  out.colour = ImageBuffer::unset(camera.width(), camera.height(), 3);
  out.status.assign(n, PixelStatus::traced);
  out.received.assign(n, 0);
  out.object.assign(n, -1);
  return out;
}

// The packets of full tracing (render_frame's, in the array's preferred
// style), tile by tile on `threads` workers: per tile, `tile(counts,
// each_packet)` where each_packet(fn) calls fn(px, n) for the tile's packets
// in order. Returns the rays of all tiles.
template <class Tile>
RayCounts for_each_packet(const LensArray& camera, int threads, Tile&& tile) {
  const int P = camera.desc().pixels_per_lens;
  const bool subaperture = preferred_style(camera.desc()) == TraceStyle::subaperture;
  const ElementalTiles tiles(camera, TileOrder::row_major, 0, -1, subaperture ? kSubapertureLenses : 1);
  std::vector<RayCounts> tile_rays(static_cast<size_t>(tiles.count()));
  for_each_tile(tiles, threads, [&](int t) {
    const TileRect r = tiles.rect(t);
    auto each_packet = [&](auto&& fn) { for_each_packet_of(r, P, subaperture, fn); };
    tile(tile_rays[static_cast<size_t>(t)], each_packet);
  });
  RayCounts total;
  for (const RayCounts& c : tile_rays) total += c;
  return total;
}

// A keyframe: the packets of full tracing, so its colour equals
// render_frame's bit for bit, keeping every pixel's hit and, when `parts`
// is given, its shading records.
ReprojectedFrame trace_keyframe(const RenderContext& scene, const LensArray& camera, std::vector<PrimaryHit>& hits,
                                std::vector<ShadeParts>* parts, int threads) {
  const int W = camera.width();
  ReprojectedFrame out = blank_frame(camera);
  hits.assign(out.status.size(), PrimaryHit{});
  if (parts) parts->assign(out.status.size(), ShadeParts{});
  out.rays = for_each_packet(camera, threads, [&](RayCounts& counts, auto&& each_packet) {
    PacketScratch scratch;
    each_packet([&](const PixelXY* px, int k) {
      Vec3 c[kPacketSize];
      PrimaryHit ph[kPacketSize];
      ShadeParts sh[kPacketSize];
      // The object from the hit record, not from a copy of 16 surface points.
      render_packet(scene, camera, px, k, 1, scratch, counts, c, ph, nullptr, parts ? sh : nullptr);
      for (int l = 0; l < k; ++l) {
        const size_t p = static_cast<size_t>(px[l].j) * W + px[l].i;
        store(out.colour, p, c[l]);
        if (ph[l].status == PrimaryHit::kHit)
          out.object[p] = scene.object_of(ph[l].group, static_cast<PrimKind>(ph[l].kind), ph[l].prim);
        hits[p] = ph[l];
        if (parts) (*parts)[p] = sh[l];
      }
    });
  });
  return out;
}

// A reprojected frame: every eye ray traced in the packets of full tracing;
// `lookup` answers the hits it can, the others are queued and shaded in
// full packets. Colour reuse looks up Embree's float hit (RawHit: its
// position is good to about 1e-7 of its distance, far below the
// same-surface tolerance) and refines only the hits it must shade; the
// refinement and the surface point (normals, material) were a fifth of a
// reprojected frame. Visibility reuse shades at every hit and refines all.
ReprojectedFrame trace_reusing(const RenderContext& scene, const LensArray& camera, const PointImageLookup& lookup,
                               ReverseReuse reuse, bool copy, int threads) {
  const int W = camera.width();
  ReprojectedFrame out = blank_frame(camera);
  const Vec3 background = scene.background();
  const AccelScene& accel = scene.accel();
  // Colour reuse in a locked-off shot: elemental images that no moving
  // object can reach are the keyframe's (PointImageLookup::lens_unchanged).
  const PointImage* same = copy && reuse == ReverseReuse::color ? lookup.same_camera_image() : nullptr;
  out.rays = for_each_packet(camera, threads, [&](RayCounts& counts, auto&& each_packet) {
    ShadeQueue queue, secondary_queue(true);
    // Per tile, not per packet: constructing them costs (as EyePacket is).
    PrimaryRay primary[kPacketSize];
    RayPacket rays;
    RawHit raw[kPacketSize];
    Hit hits[kPacketSize];
    SurfacePoint sps[kPacketSize];
    LensIndex last_lens{-1, -1};
    bool last_unchanged = false;
    each_packet([&](const PixelXY* all, int n) {
      const PixelXY* px = all;
      int k = n;
      PixelXY kept[kPacketSize];
      if (same) {  // lens by lens: a sub-aperture packet spans 16 of them
        k = 0;
        for (int l = 0; l < n; ++l) {
          const LensIndex lens = camera.lens_of_pixel(all[l].i, all[l].j);
          if (!(lens == last_lens)) last_lens = lens, last_unchanged = lookup.lens_unchanged(camera, lens);
          if (last_unchanged) take_pixel(out, *same, static_cast<size_t>(all[l].j) * W + all[l].i);
          else kept[k++] = all[l];
        }
        if (k == 0) return;
        px = kept;
      }
      bool ok[kPacketSize];
      primary_rays(camera, scene.bounds(), scene.epsilon(), px, k, 0, primary, ok);
      std::fill(rays.active, rays.active + kPacketSize, false);
      for (int l = 0; l < k; ++l) {
        if (!ok[l]) continue;
        rays.active[l] = true;
        rays.rays[l] = primary[l].ray;
        ++counts.eye;
      }
      bool found[kPacketSize] = {};
      if (std::any_of(rays.active, rays.active + k, [](bool a) { return a; }))
        accel.intersect_raw(rays, raw, found, RayCoherence::coherent);
      // Colour reuse first, from the raw hits; then the lanes left are
      // refined and given surface points together (as full tracing does,
      // lane after lane in one loop), then reused by visibility or queued.
      bool left[kPacketSize] = {};
      for (int l = 0; l < k; ++l) {
        const size_t p = static_cast<size_t>(px[l].j) * W + px[l].i;
        if (!found[l]) {
          store(out.colour, p, background);
          continue;
        }
        left[l] = true;
        if (reuse != ReverseReuse::color) continue;
        const Ray& ray = rays.rays[l];
        EyeHit eh;
        PrimKind kind;
        uint32_t prim;
        accel.primitive_of(raw[l], eh.group, kind, prim);
        eh.object = out.object[p] = scene.object_of(eh.group, kind, prim);
        eh.position = ray.org + ray.dir * static_cast<double>(raw[l].t);
        Vec3 c;
        if (lookup.filtered_colour(ray.dir * primary[l].t_sign, eh, c)) {
          store(out.colour, p, c);
          out.status[p] = PixelStatus::reprojected;
          out.received[p] = 1;
          left[l] = false;
        }
      }
      for (int l = 0; l < k; ++l)
        if (left[l]) accel.resolve(rays.rays[l], raw[l], hits[l]);
      for (int l = 0; l < k; ++l)
        if (left[l]) sps[l] = scene.surface(rays.rays[l], hits[l]);
      for (int l = 0; l < k; ++l) {
        if (!left[l]) continue;
        const size_t p = static_cast<size_t>(px[l].j) * W + px[l].i;
        const Ray& ray = rays.rays[l];
        out.object[p] = sps[l].object;
        Vec3 c;
        bool secondary = false;
        if (reuse == ReverseReuse::visibility &&
            lookup.find(ray, ray.dir * primary[l].t_sign, hits[l], sps[l], counts, c, secondary)) {
          out.status[p] = PixelStatus::reprojected;
          out.received[p] = 1;
          if (!secondary) {
            store(out.colour, p, c);
            continue;
          }
          secondary_queue.push(ray, sps[l], p, c);
          if (secondary_queue.full()) secondary_queue.flush(scene, counts, out.colour);
          continue;
        }
        queue.push(ray, sps[l], p);
        if (queue.full()) queue.flush(scene, counts, out.colour);
      }
    });
    queue.flush(scene, counts, out.colour);
    secondary_queue.flush(scene, counts, out.colour);
  });
  return out;
}

// A keyframe that is this frame exactly, or null: the same camera (equal
// descriptions give every pixel the keyframe pixel's line) and every scene
// group where the keyframe saw it. Holds and the still stretches of a
// locked-off shot: the keyframe's image is this frame's full trace.
const PointImage* same_frame(const RenderContext& scene, const LensArray& camera, const PointImage* prev,
                             const PointImage* next) {
  const AccelScene& accel = scene.accel();
  for (const PointImage* k : {prev, next}) {
    if (!k || !(k->camera.desc() == camera.desc()) || k->to_world.size() != accel.group_count() ||
        k->seen.size() != k->hits.size())
      continue;
    bool still = true;
    for (size_t g = 0; g < k->to_world.size() && still; ++g) {
      const Affine& now = accel.transform(static_cast<uint32_t>(g));
      still = k->to_world[g].m == now.m && k->to_world[g].translation == now.translation &&
              k->same_pose(accel, static_cast<uint32_t>(g));
    }
    if (still) return k;
  }
  return nullptr;
}

ReprojectedFrame copy_of(const LensArray& camera, const PointImage& key) {
  ReprojectedFrame out = blank_frame(camera);
  for (size_t p = 0; p < key.seen.size(); ++p) take_pixel(out, key, p);
  // The background too is the keyframe's: nothing in this frame was traced.
  std::fill(out.status.begin(), out.status.end(), PixelStatus::reprojected);
  out.copied_from = key.frame;
  return out;
}

}  // namespace

PointImage trace_point_image(const RenderContext& scene, const LensArray& camera, int frame, ReverseReuse reuse,
                             int threads, RenderStats& stats) {
  scene.accel().build();  // before the clock, on all cores (AccelScene::build)
  const auto start = std::chrono::steady_clock::now();
  PointImage key{frame, camera, {}, {}, {}, {}, {}, {}, {}, {}};
  const bool want_parts = reuse == ReverseReuse::visibility && scene.lights().size() <= kMaxPartLights &&
                          !scene.has_tachyon_materials();
  ReprojectedFrame traced = trace_keyframe(scene, camera, key.hits, want_parts ? &key.parts : nullptr, threads);
  key.colour = std::move(traced.colour);
  key.seen.resize(traced.object.size());
  for (size_t p = 0; p < key.seen.size(); ++p) key.seen[p] = {traced.object[p], key.hits[p].t};
  key.record_groups(scene.accel());
  if (want_parts) {
    key.edges.resize(key.parts.size());
    const int W = camera.width();
    const ElementalTiles tiles(camera, TileOrder::row_major, 0, -1, 1);
    for_each_tile(tiles, threads, [&](int t) {
      const TileRect r = tiles.rect(t);
      for (int j = r.y0; j < r.y1; ++j)
        for (int i = r.x0; i < r.x1; ++i) {
          const size_t p = static_cast<size_t>(j) * W + i;
          if (key.hits[p].status == PrimaryHit::kHit) key.edges[p] = pixel_edges(key, p);
        }
    });
  }
  stats.rays = traced.rays;
  stats.trace_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return key;
}

ReprojectedFrame reverse_reproject(const RenderContext& scene, const LensArray& camera, int frame,
                                   const PointImage* prev, const PointImage* next, const ReverseOptions& opt) {
  if (!prev && !next) throw std::invalid_argument("reprojection needs at least one keyframe");
  scene.accel().build();  // before the tiles, on all cores (AccelScene::build)
  // More lights than a mask holds, or Tachyon's shading (which ShadeParts do
  // not split): keyframes carry no parts, every hit is shaded.
  const bool reusable = opt.reuse == ReverseReuse::color ||
                        (scene.lights().size() <= kMaxPartLights && !scene.has_tachyon_materials());
  if (reusable) {
    check_key(scene, prev, opt.reuse);
    check_key(scene, next, opt.reuse);
  }
  double w_next = prev ? 0.0 : 1.0;
  if (prev && next && next->frame != prev->frame) w_next = double(frame - prev->frame) / double(next->frame - prev->frame);
  const auto start = std::chrono::steady_clock::now();
  std::vector<PrimaryHit> unused;
  const PointImage* same = opt.copy_unchanged ? same_frame(scene, camera, prev, next) : nullptr;
  ReprojectedFrame out = same       ? copy_of(camera, *same)
                         : reusable ? trace_reusing(scene, camera, PointImageLookup(scene, camera, prev, next, w_next, opt),
                                                  opt.reuse, opt.copy_unchanged, opt.threads)
                                  : trace_keyframe(scene, camera, unused, nullptr, opt.threads);
  out.seconds.check = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace holoray
