#include "reuse/shadow_cache.hpp"

#include <cmath>
#include <cstring>

#include "render/render_scene.hpp"

namespace holoray {

namespace {

constexpr int kStateShift = 30;
constexpr uint32_t kIdMask = (uint32_t{1} << kStateShift) - 1;
// Below this |cos| between a sample's normal and its light the light grazes
// the surface: which side a ray leaves from is not settled; call it partial.
constexpr double kGrazingCos = 1e-6;
// The cell table's own size per primitive (SurfaceCells::PrimCells), for the bound.
constexpr uint64_t kTableBytesPerPrim = 16;

uint64_t table_bytes(const AccelScene& accel) {
  return (accel.triangle_count() + accel.sphere_count() + accel.cone_count()) * kTableBytesPerPrim;
}

uint64_t slots_for(const AccelScene& accel, size_t lights, uint64_t limit) {
  if (lights == 0) return 0;
  const uint64_t table = table_bytes(accel);
  return limit > table ? (limit - table) / (4 * lights) : 0;
}

std::vector<uint64_t> transform_bits(const AccelScene& accel) {
  std::vector<uint64_t> bits;
  for (uint32_t g = 0; g < accel.group_count(); ++g) {
    const Affine& a = accel.transform(g);
    double v[12];
    std::memcpy(v, a.m.data(), 9 * sizeof(double));
    v[9] = a.translation.x;
    v[10] = a.translation.y;
    v[11] = a.translation.z;
    for (double d : v) {
      uint64_t b;
      std::memcpy(&b, &d, sizeof b);
      bits.push_back(b);
    }
  }
  return bits;
}

}  // namespace

ShadowCache::ShadowCache(const RenderScene& scene, const ShadowCacheOptions& options)
    : scene_(scene),
      cells_(scene.accel(), options.cell_size,
             slots_for(scene.accel(), scene.lights().size(), options.memory_limit_bytes)),
      lights_(scene.lights().size()) {
  const uint64_t words = cells_.slot_count() * lights_;
  words_.reset(new std::atomic<uint32_t>[words]());
  const AccelScene& accel = scene.accel();
  uint32_t next = 0;
  for (uint32_t g = 0; g < accel.group_count(); ++g) {
    const GeometryGroup& geo = accel.geometry(g);
    std::array<uint32_t, 3> base{};
    base[0] = next;
    next += static_cast<uint32_t>(geo.triangles.indices.size() / 3);
    base[1] = next;
    next += static_cast<uint32_t>(geo.spheres.size());
    base[2] = next;
    next += static_cast<uint32_t>(geo.cones.size());
    prim_base_.push_back(base);
  }
  snapshot_ = transform_bits(accel);
}

uint64_t ShadowCache::bytes() const { return cells_.slot_count() * lights_ * 4 + table_bytes(scene_.accel()); }

bool ShadowCache::sync() {
  std::vector<uint64_t> now = transform_bits(scene_.accel());
  if (now == snapshot_) return false;
  const uint64_t words = cells_.slot_count() * lights_;
  for (uint64_t k = 0; k < words; ++k) words_[k].store(0, std::memory_order_relaxed);
  snapshot_ = std::move(now);
  ++clears_;
  return true;
}

CellRef ShadowCache::locate(const SurfacePoint& sp) const {
  if (lights_ == 0) return CellRef::none();
  // Spheres and cones locate by the object-space point: only they pay for the transform.
  Vec3 p_object = sp.position;
  if (sp.kind != PrimKind::triangle && !scene_.accel().transform(sp.group).is_identity())
    p_object = scene_.accel().inverse_transform(sp.group).point(sp.position);
  return cells_.locate(sp.group, sp.kind, sp.prim, sp.u, sp.v, p_object);
}

uint32_t ShadowCache::encode(uint32_t group, PrimKind kind, uint32_t prim) const {
  const uint64_t id = uint64_t{prim_base_[group][static_cast<int>(kind)]} + prim + 1;
  return id <= kIdMask ? static_cast<uint32_t>(id) : 0;  // no hint past 2^30 primitives
}

OccluderHint ShadowCache::decode(uint32_t id) const {
  OccluderHint h;
  if (id == 0) return h;
  const uint32_t global = id - 1;
  for (uint32_t g = static_cast<uint32_t>(prim_base_.size()); g-- > 0;) {
    for (int k = 2; k >= 0; --k) {
      if (global >= prim_base_[g][k]) {
        h.valid = true;
        h.group = g;
        h.kind = static_cast<PrimKind>(k);
        h.prim = global - prim_base_[g][k];
        return h;
      }
    }
  }
  return h;
}

uint32_t ShadowCache::classify(const SurfacePoint& sp, const CellRef& cell, int light, RayCounts& counts) const {
  constexpr uint32_t kPartial = uint32_t{3} << kStateShift;
  CellSample samples[SurfaceCells::kMaxSamples];
  const int n = cells_.samples(sp.group, sp.kind, sp.prim, cell.local, samples);
  const AccelScene& accel = scene_.accel();
  const Affine& xf = accel.transform(sp.group);
  const bool moved = !xf.is_identity();
  const Vec3 light_pos = scene_.lights()[static_cast<size_t>(light)].position;
  const double eps = scene_.epsilon();
  int side = 0, blocked = 0;
  uint32_t first = 0;
  bool same = true;
  for (int k = 0; k < n; ++k) {
    const Vec3 p = moved ? xf.point(samples[k].p_object) : samples[k].p_object;
    const Vec3 nrm = moved ? xf.normal(samples[k].n_object) : samples[k].n_object;
    Vec3 to_light = light_pos - p;
    const double dist = length(to_light);
    if (!(dist > 2 * eps)) return kPartial | first;
    to_light = to_light / dist;
    const double c = dot(nrm, to_light);
    if (std::fabs(c) < kGrazingCos) return kPartial | first;
    const int s = c > 0 ? 1 : -1;
    if (side != 0 && s != side) return kPartial | first;
    side = s;
    // As the shading's shadow ray (shading.cpp, light_sample), from the light's side.
    const Ray ray{p + nrm * (s * eps), to_light, 0, dist - eps};
    Hit hit;
    ++counts.cache_samples;
    if (accel.intersect(ray, hit)) {
      const uint32_t id = encode(hit.group, hit.kind, hit.prim);
      if (blocked == 0) first = id;
      else if (id != first) same = false;
      ++blocked;
    }
  }
  if (blocked == 0) return uint32_t{1} << kStateShift;
  // An open cone is not convex: a segment may pass in at one end and out at the other.
  if (blocked == n && same && first != 0 && decode(first).kind != PrimKind::cone) return uint32_t{2} << kStateShift;
  return kPartial | first;
}

LightVisibility ShadowCache::visibility(const SurfacePoint& sp, const CellRef& cell, int light, RayCounts& counts,
                                        OccluderHint& hint) const {
  if (cell.slot == CellRef::kNone) return LightVisibility::unknown;
  std::atomic<uint32_t>& word = words_[cell.slot * lights_ + static_cast<size_t>(light)];
  uint32_t v = word.load(std::memory_order_relaxed);
  if (v == 0) {
    v = classify(sp, cell, light, counts);
    word.store(v, std::memory_order_relaxed);
  }
  const auto state = static_cast<LightVisibility>(v >> kStateShift);
  if (state == LightVisibility::partial) hint = decode(v & kIdMask);
  return state;
}

}  // namespace holoray
