#include "render/shadow_cache.hpp"

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <new>

#include "render/render_scene.hpp"

namespace holoray {

namespace {

constexpr int kStateShift = 30;
constexpr int kSideShift = 29;  // vertex words: which side of the surface faces the light
constexpr uint32_t kIdMask = (uint32_t{1} << kSideShift) - 1;
constexpr uint32_t kLit = uint32_t{1} << kStateShift, kBlocked = uint32_t{2} << kStateShift,
                   kPartial = uint32_t{3} << kStateShift;
// Below this |cos| between a sample's normal and its light the light grazes
// the surface: which side a ray leaves from is not settled; call it partial.
constexpr double kGrazingCos = 1e-6;
// The cell table's own size per primitive (SurfaceCells::PrimCells, and a
// cone's frame), for the bound.
constexpr uint64_t kTableBytesPerPrim = 24, kConeFrameBytes = 80;

uint64_t table_bytes(const AccelScene& accel) {
  return (accel.triangle_count() + accel.sphere_count() + accel.cone_count()) * kTableBytesPerPrim +
         accel.cone_count() * kConeFrameBytes;
}

// Per cell: its packed states; per vertex: a word per light. Both counted
// at the larger cost.
uint64_t slots_for(const AccelScene& accel, size_t lights, uint64_t limit) {
  if (lights == 0) return 0;
  const uint64_t table = table_bytes(accel);
  return limit > table ? (limit - table) / (4 * lights) : 0;
}

uint32_t load(uint32_t& w) { return std::atomic_ref<uint32_t>(w).load(std::memory_order_relaxed); }
void store(uint32_t& w, uint32_t v) { std::atomic_ref<uint32_t>(w).store(v, std::memory_order_relaxed); }

// Every group's transform and pose, bit for bit: what sync() compares.
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
    bits.push_back(accel.pose(g));  // a deformed mesh moved its cells' corners
  }
  return bits;
}

}  // namespace

ShadowCache::ShadowCache(const RenderScene& scene, const ShadowCacheOptions& options)
    : scene_(scene),
      cells_(scene.accel(), options.cell_size,
             slots_for(scene.accel(), scene.lights().size(), options.memory_limit_bytes)),
      lights_(std::min<size_t>(scene.lights().size(), kMaxCachedLights)) {
  allocate();
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

void ShadowCache::Free::operator()(uint32_t* p) const { std::free(p); }


void ShadowCache::allocate() {
  auto zeroed = [](uint64_t words) {
    auto* p = static_cast<uint32_t*>(std::calloc(words ? words : 1, sizeof(uint32_t)));
    if (!p) throw std::bad_alloc();
    return std::unique_ptr<uint32_t[], Free>(p);
  };
  states_.reset();
  vwords_.reset();
  states_ = zeroed(cells_.slot_count());
  vwords_ = zeroed(cells_.vertex_count() * lights_);
}

uint64_t ShadowCache::bytes() const {
  return (cells_.slot_count() + cells_.vertex_count() * lights_) * 4 + table_bytes(scene_.accel());
}

bool ShadowCache::sync() {
  std::vector<uint64_t> now = transform_bits(scene_.accel());
  if (now == snapshot_) return false;
  allocate();  // fresh zero pages: cheaper than writing zeros over what was touched
  snapshot_ = std::move(now);
  ++clears_;
  return true;
}

CellRef ShadowCache::locate(const SurfacePoint& sp) const {
  if (lights_ == 0) return CellRef::none();
  // Spheres and cones locate by the object-space point: only they pay for the transform.
  Vec3 p_object = sp.position;
  if (sp.kind != PrimKind::triangle && !scene_.accel().is_identity(sp.group))
    p_object = scene_.accel().inverse_transform(sp.group).point(sp.position);
  return cells_.locate(sp.group, sp.kind, sp.prim, sp.u, sp.v, p_object);
}

// A blocking primitive's id for the one-occluder test: unique over the
// scene, never 0; 0 for an open cone (not convex: a segment may pass in at
// one end and out at the other) and past 2^29 primitives, which keeps such
// cells partial.
uint32_t ShadowCache::occluder_id(uint32_t group, PrimKind kind, uint32_t prim) const {
  if (kind == PrimKind::cone) return 0;
  const uint64_t id = uint64_t{prim_base_[group][static_cast<int>(kind)]} + prim + 1;
  return id <= kIdMask ? static_cast<uint32_t>(id) : 0;
}

// One sample's shadow ray toward `light` (a corner's is traced once per
// vertex and light, kept in vwords_): lit, blocked (with the closest occluder, for the one-occluder test) or
// undecidable (the light on or grazing the surface there); with
// the side of the surface that faces the light.
uint32_t ShadowCache::vertex_state(const CellCorner& corner, uint32_t group, int light, RayCounts& counts) const {
  uint32_t& word = vwords_[corner.vertex * lights_ + static_cast<size_t>(light)];
  uint32_t v = load(word);
  if (v == 0) {
    v = sample_state(corner.sample, group, light, counts);
    store(word, v);
  }
  return v;
}

uint32_t ShadowCache::sample_state(const CellSample& sample, uint32_t group, int light, RayCounts& counts) const {
  uint32_t v;
  const AccelScene& accel = scene_.accel();
  const Affine& xf = accel.transform(group);
  const bool moved = !accel.is_identity(group);
  const Vec3 p = moved ? xf.point(sample.p_object) : sample.p_object;
  const Vec3 nrm = moved ? xf.normal(sample.n_object) : sample.n_object;
  const Vec3 light_pos = scene_.lights()[static_cast<size_t>(light)].position;
  const double eps = scene_.epsilon();
  Vec3 to_light = light_pos - p;
  const double dist = length(to_light);
  const double c = dist > 2 * eps ? dot(nrm, to_light / dist) : 0;
  if (!(std::fabs(c) >= kGrazingCos)) {
    v = kPartial;
  } else {
    const int s = c > 0 ? 1 : -1;
    // As the shading's shadow ray (shading.cpp, shadow_ray), from the light's side.
    const Ray ray{p + nrm * (s * eps), to_light / dist, 0, dist - eps};
    Hit hit;
    ++counts.cache_samples;
    v = (s > 0 ? uint32_t{1} << kSideShift : 0) |
        (accel.intersect(ray, hit) ? kBlocked | occluder_id(hit.group, hit.kind, hit.prim) : kLit);
  }
  return v;
}

LightVisibility ShadowCache::classify(const SurfacePoint& sp, const CellRef& cell, int light,
                                      RayCounts& counts) const {
  CellCorner corners[SurfaceCells::kMaxCorners];
  const int corner_count = cells_.corners(sp.group, sp.kind, sp.prim, cell.local, corners);
  // The centre last, and only when the corners agree: it is the one ray a
  // cell does not share, there to find shadows smaller than the cell.
  const int n = corner_count + 1;
  uint32_t first = 0, side = 0;
  int lit = 0, blocked = 0;
  bool same = true;
  for (int k = 0; k < n; ++k) {
    const uint32_t v = k < corner_count
                           ? vertex_state(corners[k], sp.group, light, counts)
                           : sample_state(cells_.centre(sp.group, sp.kind, sp.prim, cell.local), sp.group, light, counts);
    const uint32_t state = v & kPartial;
    const uint32_t s = v & (uint32_t{1} << kSideShift);
    // Undecidable, or the corners leave from different sides: a terminator crosses the cell.
    if (state == kPartial || (k > 0 && s != side)) return LightVisibility::partial;
    side = s;
    if (state == kLit) {
      ++lit;
      continue;
    }
    const uint32_t id = v & kIdMask;
    if (blocked++ == 0) first = id;
    else same &= id == first;
    if (k == corner_count - 1 && lit != 0 && blocked != 0) return LightVisibility::partial;  // an edge: skip the centre
  }
  if (lit == n) return LightVisibility::lit;
  if (blocked == n && same && first != 0) return LightVisibility::shadowed;
  return LightVisibility::partial;
}

LightVisibility ShadowCache::visibility(const SurfacePoint& sp, const CellRef& cell, int light,
                                        RayCounts& counts) const {
  if (cell.slot == CellRef::kNone || static_cast<size_t>(light) >= lights_) return LightVisibility::unknown;
  // One word holds every light's state of the cell: the first light's load
  // brings it in for the others. Two threads classifying one cell OR in the
  // same bits.
  std::atomic_ref<uint32_t> word(states_[cell.slot]);
  const int shift = 2 * light;
  uint32_t state = word.load(std::memory_order_relaxed) >> shift & 3u;
  if (state == 0) {
    state = static_cast<uint32_t>(classify(sp, cell, light, counts));
    word.fetch_or(state << shift, std::memory_order_relaxed);
  }
  return static_cast<LightVisibility>(state);
}

}  // namespace holoray
