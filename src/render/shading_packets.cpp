// holoray/render: shade() and shade_secondary() for packets of 16 rays:
// shadow rays toward each light as one packet, secondary rays traced as a
// packet when coherent, NFF's and glTF's lights as float batches
// (light_batch.hpp, gltf_batch.hpp).
#include <algorithm>
#include <cmath>
#include <type_traits>

#include "render/gltf_batch.hpp"
#include "render/light_batch.hpp"
#include "render/shading.hpp"
#include "render/shading_models.hpp"

namespace holoray {

using namespace shading;

namespace {

// The colour seen along each active lane of `rays` at ray-tree `depth`:
// traced as one packet, the hits shaded as a packet. Only nearly parallel
// rays come here, and Embree's coherent (frustum) traversal takes them
// faster (teapot_s6 0.907x, gears_s4 0.951x the whole command); it does not
// agree with the single-ray kernel on every ray (gears: 1 mirror ray in 2 M
// found another surface), which the image budget allows.
void trace_packet(const RenderContext& scene, const RayPacket& rays, int depth, RayCounts& counts,
                  Vec3 colours[kPacketSize]) {
  Hit hits[kPacketSize];
  bool found[kPacketSize] = {};
  scene.accel().intersect(rays, hits, found, RayCoherence::coherent, !scene.only_plain_nff());
  SurfacePoint sps[kPacketSize];
  bool any = false;
  for (int k = 0; k < kPacketSize; ++k) {
    if (!rays.active[k]) continue;
    colours[k] = scene.background();
    if (found[k]) sps[k] = scene.surface(rays.rays[k], hits[k]);
    any |= found[k];
  }
  if (any) shade(scene, rays, found, sps, depth, counts, colours);
}

// trace() for a packet's secondary ray: in a scene of plain NFF materials
// with Embree's float hit (RenderScene::only_plain_nff).
Vec3 trace_secondary(const RenderContext& scene, const Ray& ray, int depth, RayCounts& counts) {
  Hit hit;
  if (!scene.accel().intersect(ray, hit, RayCoherence::incoherent, !scene.only_plain_nff())) return scene.background();
  return shade(scene, ray, scene.surface(ray, hit), depth, counts);
}

// A packet of secondary rays is traced as a packet only when its rays are
// nearly parallel (every one within ~25 degrees of their mean) and at least
// this many: off a large smooth mirror (the teapot) that is 6 % faster per
// frame; off small spheres (balls) the rays scatter, and packets of them, and
// of their hits' shadow rays, were 27 % slower than single rays.
constexpr double kMinCoherentCos = 0.9;
constexpr int kMinCoherentLanes = 4;

// add_secondary() for the lanes of a packet: the mirror rays of all lanes,
// then the transmitted (or totally reflected) rays, each set traced a level
// deeper as one packet when coherent, else one by one. Same rays, weights and
// order of addition per lane as add_secondary().
void add_secondary(const RenderContext& scene, const RayPacket& rays, const bool hit[kPacketSize],
                   const SurfacePoint sps[kPacketSize], const HitFrame f[kPacketSize], int depth, RayCounts& counts,
                   Vec3 colours[kPacketSize]) {
  if (depth >= scene.max_depth()) return;
  // Most NFF surfaces are matte: their packets skip building 16 empty ray
  // pairs (tree_s11, all matte: 4 % of its cycles went there).
  bool any = false;
  for (int k = 0; k < kPacketSize; ++k)
    any |= hit[k] && casts_secondary(sps[k], f[k]);
  if (!any) return;
  RayPacket next;
  Vec3 weight[kPacketSize];
  auto flush = [&] {
    Vec3 mean;
    int n = 0;
    for (int k = 0; k < kPacketSize; ++k)
      if (next.active[k]) mean += next.rays[k].dir, ++n;
    if (n == 0) return;
    mean = normalize(mean);
    double spread = 1;
    for (int k = 0; k < kPacketSize; ++k)
      if (next.active[k]) spread = std::fmin(spread, dot(next.rays[k].dir, mean));
    if (n < kMinCoherentLanes || spread < kMinCoherentCos) {
      for (int k = 0; k < kPacketSize; ++k)
        if (next.active[k]) colours[k] += mul(trace_secondary(scene, next.rays[k], depth + 1, counts), weight[k]);
      return;
    }
    Vec3 seen[kPacketSize];
    trace_packet(scene, next, depth + 1, counts, seen);
    for (int k = 0; k < kPacketSize; ++k)
      if (next.active[k]) colours[k] += mul(seen[k], weight[k]);
  };
  // Each lane's rays are written straight into the packet, the mirror rays
  // first (shading_models.hpp: mirror_ray, transmitted_ray).
  for (int k = 0; k < kPacketSize; ++k) {
    next.active[k] = false;
    if (!hit[k]) continue;
    next.active[k] = mirror_ray(scene, rays.rays[k], sps[k], f[k], next.rays[k], weight[k]);
    counts.reflected += next.active[k];
  }
  flush();
  for (int k = 0; k < kPacketSize; ++k) {
    next.active[k] = false;
    if (!hit[k]) continue;
    bool reflects = false;
    next.active[k] = transmitted_ray(scene, rays.rays[k], sps[k], f[k], next.rays[k], weight[k], reflects);
    if (next.active[k]) ++(reflects ? counts.reflected : counts.refracted);
  }
  flush();
}


}  // namespace

void shade_secondary(const RenderContext& scene, const RayPacket& rays, const bool hit[kPacketSize],
                     const SurfacePoint sps[kPacketSize], int depth, RayCounts& counts, Vec3 colours[kPacketSize]) {
  HitFrame f[kPacketSize];
  for (int k = 0; k < kPacketSize; ++k)
    if (hit[k]) f[k] = frame_of(scene, rays.rays[k], sps[k]);
  add_secondary(scene, rays, hit, sps, f, depth, counts, colours);
}

namespace {

// What every light's shadow rays need of a packet's lanes, one array per
// coordinate, gathered once per packet: the hit points, the shading normals
// and the shadow rays' origins (already rounded to Embree's floats).
struct LaneGeometry {
  alignas(64) double px[kPacketSize], py[kPacketSize], pz[kPacketSize];
  alignas(64) double nx[kPacketSize], ny[kPacketSize], nz[kPacketSize];
  float origin[kPacketSize][3];

  void gather(const bool hit[kPacketSize], const SurfacePoint sps[kPacketSize], const HitFrame f[kPacketSize]) {
    for (int k = 0; k < kPacketSize; ++k) {
      // Missed lanes get harmless values: every lane is computed, the hit ones kept.
      const Vec3 p = hit[k] ? sps[k].position : Vec3{}, n = hit[k] ? f[k].ns : Vec3{}, o = hit[k] ? f[k].above : Vec3{};
      px[k] = p.x, py[k] = p.y, pz[k] = p.z, nx[k] = n.x, ny[k] = n.y, nz[k] = n.z;
      origin[k][0] = static_cast<float>(o.x), origin[k][1] = static_cast<float>(o.y), origin[k][2] = static_cast<float>(o.z);
    }
  }
};

// One point light of unit falloff (NFF's) for a packet's lanes without the
// shadow cache: shadow_ray<true>()'s arithmetic, each operation the same as
// there and in the same order (the same bits as the RayPacket path), on
// every lane without a branch, the rays written straight into Embree's
// 16-wide layout instead of a RayPacket of doubles that occluded() then
// converts, each origin rounded once per packet, not once per light. GCC
// leaves the loop scalar: the gain is the branches and conversions saved.
template <class MarkLit>
void shade_point_light(const RenderContext& scene, const bool hit[kPacketSize], const LaneGeometry& g,
                       const SurfacePoint sps[kPacketSize],
                       const HitFrame f[kPacketSize], size_t l, RayCounts& counts, Vec3 colours[kPacketSize],
                       MarkLit&& mark_lit) {
  const PointLight& light = scene.lights()[l];
  const double eps = scene.epsilon();
  const double lx = light.position.x, ly = light.position.y, lz = light.position.z;
  ShadowPacket shadows;
  alignas(64) double ux[kPacketSize], uy[kPacketSize], uz[kPacketSize];
  for (int k = 0; k < kPacketSize; ++k) {
    const double dx = lx - g.px[k], dy = ly - g.py[k], dz = lz - g.pz[k];
    const double dist = std::sqrt(dx * dx + dy * dy + dz * dz);
    const double inv = 1.0 / dist;
    ux[k] = dx * inv, uy[k] = dy * inv, uz[k] = dz * inv;
    const double n_dot_l = g.nx[k] * ux[k] + g.ny[k] * uy[k] + g.nz[k] * uz[k];
    shadows.set(k, g.origin[k], Vec3{ux[k], uy[k], uz[k]}, dist - eps, hit[k] & (dist > eps) & !(n_dot_l <= 0));
  }
  int cast = 0;
  for (int k = 0; k < kPacketSize; ++k) cast += shadows.valid[k] != 0;
  if (cast == 0) return;
  counts.shadow += static_cast<uint64_t>(cast);
  bool blocked[kPacketSize];
  scene.accel().occluded(shadows, blocked);
  for (int k = 0; k < kPacketSize; ++k)
    if (shadows.valid[k] && !blocked[k])
      colours[k] += light_contribution(f[k], sps[k], light, Vec3{ux[k], uy[k], uz[k]}, 1.0), mark_lit(k, l);
}

// The lanes of a packet for its point lights of unit falloff: as an
// NffLanes batch when every hit lane's material is NFF's (true), else as
// LaneGeometry for shade_point_light (false).
bool gather_lanes(const bool hit[kPacketSize], const SurfacePoint sps[kPacketSize],
                  const HitFrame f[kPacketSize], NffLanes& batch, LaneGeometry& lanes) {
  for (int k = 0; k < kPacketSize; ++k)
    if (hit[k] && f[k].m->model != ShadingModel::nff) {
      lanes.gather(hit, sps, f);
      return false;
    }
  for (int k = 0; k < kPacketSize; ++k) {
    if (!hit[k]) {
      batch.clear(k);
      continue;
    }
    const Material& m = *f[k].m;
    batch.set(k, sps[k].position, f[k].ns, f[k].above, f[k].view, f[k].colour * m.kd, m.ks, m.shine);
  }
  return true;
}

// One light for a packet's lanes gathered as a float batch, without the
// shadow cache: NFF's point lights of unit falloff (NffLanes,
// light_batch.hpp) or glTF's lights that can_batch() (GltfLanes,
// gltf_batch.hpp). The shadow rays go as one packet; the lanes it reaches
// get the light's term and, with `parts`, its bit.
template <class Lanes>
void shade_batched_light(const RenderContext& scene, const Lanes& batch, size_t l, RayCounts& counts,
                         Vec3 colours[kPacketSize], ShadeParts parts[]) {
  constexpr bool nff = std::is_same_v<Lanes, NffLanes>;
  const PointLight& light = scene.lights()[l];
  ShadowPacket shadows;
  std::conditional_t<nff, NffLightRays, GltfLightRays> rays;
  int cast;
  if constexpr (nff) cast = nff_shadow_rays(batch, light.position, scene.epsilon(), shadows, rays);
  else cast = gltf_shadow_rays(batch, light, scene.epsilon(), shadows, rays);
  if (cast == 0) return;
  counts.shadow += static_cast<uint64_t>(cast);
  bool blocked[kPacketSize];
  scene.accel().occluded(shadows, blocked);
  bool seen[kPacketSize];
  for (int k = 0; k < kPacketSize; ++k) seen[k] = (shadows.valid[k] != 0) & !blocked[k];
  if constexpr (nff) add_nff_light(batch, rays, seen, light.intensity, colours);
  else add_gltf_light(batch, rays, seen, light.intensity, colours);
  if (parts && l < kMaxPartLights)
    for (int k = 0; k < kPacketSize; ++k) parts[k].lit |= static_cast<uint32_t>(seen[k]) << l;
}


}  // namespace

void shade(const RenderContext& scene, const RayPacket& rays, const bool hit_in[kPacketSize],
           const SurfacePoint sps[kPacketSize], int depth, RayCounts& counts, Vec3 colours[kPacketSize],
           ShadeParts parts[kPacketSize]) {
  // Tachyon materials take their own packet path; the NFF lanes go on below.
  bool hit[kPacketSize], tachyon[kPacketSize];
  bool any_tachyon = false;
  for (int k = 0; k < kPacketSize; ++k) {
    tachyon[k] = hit_in[k] && sps[k].material->model == ShadingModel::tachyon;
    hit[k] = hit_in[k] && !tachyon[k];
    any_tachyon |= tachyon[k];
  }
  if (any_tachyon) TachyonModel::shade(scene, rays, tachyon, sps, depth, counts, colours);
  if (parts)
    for (int k = 0; k < kPacketSize; ++k) parts[k] = ShadeParts{};
  auto mark_lit = [&](int k, size_t l) {
    if (parts && l < kMaxPartLights) parts[k].lit |= 1u << l;
  };
  HitFrame f[kPacketSize];
  CellRef cells[kPacketSize];  // set and read only when there is a cache
  const bool cached = scene.shadow_cache() != nullptr;
  for (int k = 0; k < kPacketSize; ++k) {
    if (!hit[k]) continue;
    f[k] = frame_of(scene, rays.rays[k], sps[k]);
    colours[k] = ambient_term(scene, f[k]);
    add_emission(scene, rays.rays[k], sps[k], colours[k]);
    if (cached) cells[k] = cell_of(scene, sps[k]);
  }
  // The shadow rays of one packet toward one light share their end point:
  // traced together as a packet.
  RayPacket shadows;
  bool blocked[kPacketSize];
  double falloff[kPacketSize];
  const auto& lights = scene.lights();
  LaneGeometry lanes;  // gathered for the first point light of unit falloff
  NffLanes batch;      // the same, when every lane's material is NFF's
  enum { not_yet, double_lanes, float_batch } gathered = not_yet;
  // One light's lanes; `Unit` as shadow_ray's.
  auto shade_light = [&]<bool Unit>(size_t l, std::bool_constant<Unit>) {
    if constexpr (Unit) {
      if (!cached) {
        if (gathered == not_yet) gathered = gather_lanes(hit, sps, f, batch, lanes) ? float_batch : double_lanes;
        if (gathered == float_batch) shade_batched_light(scene, batch, l, counts, colours, parts);
        else shade_point_light(scene, hit, lanes, sps, f, l, counts, colours, mark_lit);
        return;
      }
    }
    int cast = 0;
    for (int k = 0; k < kPacketSize; ++k) {
      shadows.active[k] = hit[k] && shadow_ray<Unit>(scene, f[k], sps[k], lights[l], shadows.rays[k], falloff[k]);
      if (!shadows.active[k]) continue;
      if (!cached) {
        ++cast;
        continue;
      }
      const int seen = cached_visibility(scene, f[k], sps[k], cells[k], static_cast<int>(l), shadows.rays[k], counts);
      if (seen >= 0) {
        if (seen) colours[k] += light_contribution(f[k], sps[k], lights[l], shadows.rays[k].dir, falloff[k]), mark_lit(k, l);
        shadows.active[k] = false;
        continue;
      }
      ++cast;
    }
    if (cast == 0) return;
    counts.shadow += static_cast<uint64_t>(cast);
    scene.accel().occluded(shadows, blocked);
    for (int k = 0; k < kPacketSize; ++k)
      if (shadows.active[k] && !blocked[k])
        colours[k] += light_contribution(f[k], sps[k], lights[l], shadows.rays[k].dir, falloff[k]), mark_lit(k, l);
  };
  // Every hit lane glTF's (no shadow cache): the lights go as float batches.
  bool gltf_packet = !cached, any_hit = false;
  for (int k = 0; k < kPacketSize; ++k)
    if (hit[k]) gltf_packet &= f[k].m->model == ShadingModel::gltf, any_hit = true;
  gltf_packet &= any_hit;
  GltfLanes gltf_lanes;
  if (gltf_packet)
    for (int k = 0; k < kPacketSize; ++k) {
      if (hit[k]) gltf_lanes.set(k, sps[k].position, f[k].ns, f[k].above, f[k].view, GltfModel::surface(f[k], sps[k]),
                                 f[k].m->transmittance);
      else gltf_lanes.clear(k);
    }
  for (size_t l = 0; l < lights.size(); ++l) {
    if (gltf_packet && can_batch(lights[l])) shade_batched_light(scene, gltf_lanes, l, counts, colours, parts);
    else if (lights[l].unit_falloff) shade_light(l, std::true_type{});
    else shade_light(l, std::false_type{});
  }
  if (!parts) {
    add_secondary(scene, rays, hit, sps, f, depth, counts, colours);
    return;
  }
  // The secondary light as the difference, so that the colour is added up
  // in the same order as without parts (bit for bit the same image).
  Vec3 local[kPacketSize];
  std::copy(colours, colours + kPacketSize, local);
  add_secondary(scene, rays, hit, sps, f, depth, counts, colours);
  for (int k = 0; k < kPacketSize; ++k) {
    if (!hit[k]) continue;
    const Vec3 s = colours[k] - local[k];
    parts[k].secondary[0] = static_cast<float>(s.x), parts[k].secondary[1] = static_cast<float>(s.y),
    parts[k].secondary[2] = static_cast<float>(s.z);
  }
}


}  // namespace holoray
