#include "accel/accel_scene.hpp"

#include "accel/embree_api.hpp"
#include "math/vec_pair.hpp"
#include "util/parallel.hpp"

#include <fmt/format.h>

#include <atomic>
#include <cmath>
#include <mutex>
#include <cstddef>
#include <cstring>
#include <type_traits>
#include <numeric>
#include <stdexcept>
#include <string>

namespace holoray {

namespace {

// Embree's BVH is float; widen each box so double-precision hits on its
// surface are never culled by rounding.
RTCBounds to_rtc(const Bounds3& b) {
  const Vec3 pad = (b.hi - b.lo) * 1e-6 + Vec3{1e-6, 1e-6, 1e-6} * std::fmax(1.0, length(max(-b.lo, b.hi)) * 1e-3);
  const Vec3 lo = b.lo - pad, hi = b.hi + pad;
  RTCBounds r;
  r.lower_x = std::nextafter(static_cast<float>(lo.x), -INFINITY);
  r.lower_y = std::nextafter(static_cast<float>(lo.y), -INFINITY);
  r.lower_z = std::nextafter(static_cast<float>(lo.z), -INFINITY);
  r.upper_x = std::nextafter(static_cast<float>(hi.x), INFINITY);
  r.upper_y = std::nextafter(static_cast<float>(hi.y), INFINITY);
  r.upper_z = std::nextafter(static_cast<float>(hi.z), INFINITY);
  return r;
}

template <class Shape>
void shape_bounds(const RTCBoundsFunctionArguments* args) {
  const auto* shapes = static_cast<const Shape*>(args->geometryUserPtr);
  *args->bounds_o = to_rtc(bounds_of(shapes[args->primID]));
}

inline bool hit_shape(const Sphere& s, const Vec3& o, const Vec3& d, double tn, double tf, double& t, Vec3& n) {
  return intersect_sphere(s, o, d, tn, tf, t, n);
}
inline bool hit_shape(const PreparedCone& c, const Vec3& o, const Vec3& d, double tn, double tf, double& t, Vec3& n) {
  return intersect_cone(c, o, d, tn, tf, t, n);
}

inline bool meets_shape(const Sphere& s, const Vec3& o, const Vec3& d, double tn, double tf) {
  return meets_sphere(s, o, d, tn, tf);
}
inline bool meets_shape(const PreparedCone& c, const Vec3& o, const Vec3& d, double tn, double tf) {
  return meets_cone(c, o, d, tn, tf);
}

template <class Shape>
void shape_intersect(const RTCIntersectFunctionNArguments* args) {
  const auto* shapes = static_cast<const Shape*>(args->geometryUserPtr);
  const Shape& shape = shapes[args->primID];
  RTCRayN* rays = RTCRayHitN_RayN(args->rayhit, args->N);
  RTCHitN* hits = RTCRayHitN_HitN(args->rayhit, args->N);
  const unsigned N = args->N;
  for (unsigned i = 0; i < N; ++i) {
    if (args->valid[i] != -1) continue;
    const Vec3 o{RTCRayN_org_x(rays, N, i), RTCRayN_org_y(rays, N, i), RTCRayN_org_z(rays, N, i)};
    const Vec3 d{RTCRayN_dir_x(rays, N, i), RTCRayN_dir_y(rays, N, i), RTCRayN_dir_z(rays, N, i)};
    double t;
    Vec3 n;
    if (!hit_shape(shape, o, d, RTCRayN_tnear(rays, N, i), RTCRayN_tfar(rays, N, i), t, n)) continue;
    const float tf = static_cast<float>(t);
    if (!(tf < RTCRayN_tfar(rays, N, i))) continue;
    RTCRayN_tfar(rays, N, i) = tf;
    RTCHitN_Ng_x(hits, N, i) = static_cast<float>(n.x);
    RTCHitN_Ng_y(hits, N, i) = static_cast<float>(n.y);
    RTCHitN_Ng_z(hits, N, i) = static_cast<float>(n.z);
    RTCHitN_u(hits, N, i) = 0;
    RTCHitN_v(hits, N, i) = 0;
    RTCHitN_primID(hits, N, i) = args->primID;
    RTCHitN_geomID(hits, N, i) = args->geomID;
    RTCHitN_instID(hits, N, i, 0) = args->context->instID[0];
  }
}

template <class Shape>
void shape_occluded(const RTCOccludedFunctionNArguments* args) {
  const auto* shapes = static_cast<const Shape*>(args->geometryUserPtr);
  const Shape& shape = shapes[args->primID];
  if constexpr (std::is_same_v<Shape, Sphere>)
    if (!shape.casts_shadow) return;
  const unsigned N = args->N;
  for (unsigned i = 0; i < N; ++i) {
    if (args->valid[i] != -1) continue;
    const Vec3 o{RTCRayN_org_x(args->ray, N, i), RTCRayN_org_y(args->ray, N, i), RTCRayN_org_z(args->ray, N, i)};
    const Vec3 d{RTCRayN_dir_x(args->ray, N, i), RTCRayN_dir_y(args->ray, N, i), RTCRayN_dir_z(args->ray, N, i)};
    if (meets_shape(shape, o, d, RTCRayN_tnear(args->ray, N, i), RTCRayN_tfar(args->ray, N, i)))
      RTCRayN_tfar(args->ray, N, i) = -INFINITY;
  }
}

void on_embree_error(void* user, RTCError code, const char* message) {
  auto* last = static_cast<std::string*>(user);
  if (last->empty()) *last = fmt::format("Embree error {}: {}", static_cast<int>(code), message ? message : "");
}

RTCRay to_rtc_ray(const Ray& r) {
  RTCRay ray{};
  ray.org_x = static_cast<float>(r.org.x);
  ray.org_y = static_cast<float>(r.org.y);
  ray.org_z = static_cast<float>(r.org.z);
  ray.dir_x = static_cast<float>(r.dir.x);
  ray.dir_y = static_cast<float>(r.dir.y);
  ray.dir_z = static_cast<float>(r.dir.z);
  ray.tnear = static_cast<float>(r.tnear);
  ray.tfar = std::isinf(r.tfar) ? INFINITY : static_cast<float>(r.tfar);
  ray.mask = ~0u;
  ray.flags = 0;
  return ray;
}

}  // namespace

// Embree ids: a static group g puts its geometries in the top level as
// 3g + kind; a movable group is the instance 3g of a child scene that holds
// its geometries as `kind`.
struct AccelScene::Impl {
  std::string last_error;
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::vector<RTCScene> children;                  // per group; null for static groups
  std::vector<RTCGeometry> instances;              // per group; null for static groups
  bool instanced = false;                          // some group is movable (an instance)
  // What build() still has to commit: the child scenes marked here, then
  // the top level whenever `built` is false.
  std::mutex build_lock;
  std::atomic<bool> built{false};
  std::vector<char> child_stale;  // per group

  // The scene, its hierarchies built: what every query traces.
  RTCScene traced(const AccelScene& owner) {
    if (!built.load(std::memory_order_acquire)) owner.build();
    return scene;
  }

  void check(const char* what) {
    if (!last_error.empty()) throw std::runtime_error(fmt::format("{}: {}", what, last_error));
  }
  ~Impl() {
    for (RTCScene s : children)
      if (s) rtcReleaseScene(s);
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

namespace {

GeometryGroup single_group(TriangleData triangles, std::vector<Sphere> spheres, std::vector<Cone> cones) {
  GeometryGroup g;
  g.triangles = std::move(triangles);
  g.spheres = std::move(spheres);
  g.cones = std::move(cones);
  return g;
}

// Embree's filter for a group with cut-away triangles: a candidate hit the
// cutout removes is invalid, and the traversal goes on past it.
template <class Ref>
void cutout_filter(const RTCFilterFunctionNArguments* a) {
  const auto* ref = static_cast<const Ref*>(a->geometryUserPtr);
  for (unsigned i = 0; i < a->N; ++i) {
    if (a->valid[i] != -1) continue;
    const unsigned prim = RTCHitN_primID(a->hit, a->N, i);
    if (ref->cutout->cut(ref->group, prim, RTCHitN_u(a->hit, a->N, i), RTCHitN_v(a->hit, a->N, i))) a->valid[i] = 0;
  }
}

template <class Ref>
void attach_geometry(RTCDevice device, RTCScene scene, GeometryGroup& geo, std::vector<PreparedCone>& cones,
                     unsigned id_base, const Ref* cutout) {
  TriangleData& tri = geo.triangles;
  if (!tri.indices.empty()) {
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    if (cutout && cutout->cutout) {
      rtcSetGeometryUserData(g, const_cast<Ref*>(cutout));
      rtcSetGeometryIntersectFilterFunction(g, cutout_filter<Ref>);
      rtcSetGeometryOccludedFilterFunction(g, cutout_filter<Ref>);
    }
    if (geo.deformable) rtcSetGeometryBuildQuality(g, RTC_BUILD_QUALITY_REFIT);
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, tri.positions.data(), 0, 3 * sizeof(float),
                               tri.positions.size() / 3);
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, tri.indices.data(), 0, 3 * sizeof(uint32_t),
                               tri.indices.size() / 3);
    rtcCommitGeometry(g);
    rtcAttachGeometryByID(scene, g, id_base + static_cast<unsigned>(PrimKind::triangle));
    rtcReleaseGeometry(g);
  }
  auto add_user = [&](auto& shapes, PrimKind kind) {
    using Shape = typename std::remove_reference_t<decltype(shapes)>::value_type;
    if (shapes.empty()) return;
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
    rtcSetGeometryUserPrimitiveCount(g, static_cast<unsigned>(shapes.size()));
    rtcSetGeometryUserData(g, shapes.data());
    rtcSetGeometryBoundsFunction(g, shape_bounds<Shape>, nullptr);
    rtcSetGeometryIntersectFunction(g, shape_intersect<Shape>);
    rtcSetGeometryOccludedFunction(g, shape_occluded<Shape>);
    rtcCommitGeometry(g);
    rtcAttachGeometryByID(scene, g, id_base + static_cast<unsigned>(kind));
    rtcReleaseGeometry(g);
  };
  add_user(geo.spheres, PrimKind::sphere);
  add_user(cones, PrimKind::cone);
}

Bounds3 geometry_bounds(const GeometryGroup& geo) {
  Bounds3 b;
  const auto& p = geo.triangles.positions;
  for (size_t i = 0; i + 2 < p.size(); i += 3) b.extend(Vec3{p[i], p[i + 1], p[i + 2]});
  for (const Sphere& s : geo.spheres) b.extend(bounds_of(s));
  for (const Cone& c : geo.cones) b.extend(bounds_of(c));
  return b;
}

Bounds3 transformed(const Bounds3& b, const Affine& a) {
  Bounds3 r;
  if (b.empty()) return r;
  for (int k = 0; k < 8; ++k)
    r.extend(a.point(Vec3{(k & 1) ? b.hi.x : b.lo.x, (k & 2) ? b.hi.y : b.lo.y, (k & 4) ? b.hi.z : b.lo.z}));
  return r;
}

void to_rtc_transform(const Affine& a, float out[12]) {
  // RTC_FORMAT_FLOAT3X4_ROW_MAJOR
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) out[4 * r + c] = static_cast<float>(a.m[3 * r + c]);
    out[4 * r + 3] = static_cast<float>(a.translation[r]);
  }
}

}  // namespace

AccelScene::AccelScene(TriangleData triangles, std::vector<Sphere> spheres, std::vector<Cone> cones)
    : AccelScene([&] {
        std::vector<GeometryGroup> g;
        g.push_back(single_group(std::move(triangles), std::move(spheres), std::move(cones)));
        return g;
      }()) {}

AccelScene::AccelScene(std::vector<GeometryGroup> groups) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.device = rtcNewDevice(nullptr);
  if (!m.device) throw std::runtime_error(fmt::format("cannot create the Embree device (error {})", static_cast<int>(rtcGetDeviceError(nullptr))));
  rtcSetDeviceErrorFunction(m.device, on_embree_error, &m.last_error);
  auto new_scene = [&](bool dynamic = false) {
    RTCScene s = rtcNewScene(m.device);
    // Robust mode: watertight triangle edges (rays exactly on a shared edge
    // otherwise fall through; the plane-depth test hits this).
    rtcSetSceneFlags(s, dynamic ? RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_DYNAMIC : RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(s, RTC_BUILD_QUALITY_HIGH);
    return s;
  };
  m.scene = new_scene();
  m.check("creating the Embree scene");

  groups_.resize(groups.size());
  m.children.assign(groups.size(), nullptr);
  m.instances.assign(groups.size(), nullptr);
  for (size_t gi = 0; gi < groups.size(); ++gi) {
    Group& g = groups_[gi];
    g.geo = std::move(groups[gi]);
    g.geo.movable |= g.geo.deformable;
    g.object_bounds = geometry_bounds(g.geo);
    g.cones.reserve(g.geo.cones.size());
    for (const Cone& c : g.geo.cones) g.cones.push_back(prepare_cone(c));
    g.cutout_ref = {g.geo.cutout, static_cast<uint32_t>(gi)};
    const unsigned base = 3 * static_cast<unsigned>(gi);
    if (!g.geo.movable) {
      attach_geometry(m.device, m.scene, g.geo, g.cones, base, &g.cutout_ref);
      continue;
    }
    m.instanced = true;
    RTCScene child = new_scene(g.geo.deformable);
    attach_geometry(m.device, child, g.geo, g.cones, 0, &g.cutout_ref);
    m.children[gi] = child;
    RTCGeometry inst = rtcNewGeometry(m.device, RTC_GEOMETRY_TYPE_INSTANCE);
    rtcSetGeometryInstancedScene(inst, child);
    float xf[12];
    to_rtc_transform(Affine{}, xf);
    rtcSetGeometryTransform(inst, 0, RTC_FORMAT_FLOAT3X4_ROW_MAJOR, xf);
    rtcCommitGeometry(inst);
    rtcAttachGeometryByID(m.scene, inst, base);
    m.instances[gi] = inst;  // owned by the scene; kept to update its transform
    rtcReleaseGeometry(inst);
  }
  m.check("building the Embree scene");
  m.child_stale.assign(groups_.size(), 1);
  for (const Group& g : groups_) bounds_.extend(g.object_bounds);
}

AccelScene::~AccelScene() = default;

void AccelScene::build() const {
  Impl& m = *impl_;
  if (m.built.load(std::memory_order_acquire)) return;
  const std::lock_guard lock(m.build_lock);
  if (m.built.load(std::memory_order_relaxed)) return;
  // Isolated: while Embree's build waits on its tasks, this thread must not
  // take a tile of the render that called it, whose query would wait on
  // the lock it holds.
  run_isolated([&] {
    for (size_t gi = 0; gi < m.children.size(); ++gi)
      if (m.children[gi] && m.child_stale[gi]) {
        rtcCommitScene(m.children[gi]);
        if (m.instances[gi]) rtcCommitGeometry(m.instances[gi]);
        m.child_stale[gi] = 0;
      }
    rtcCommitScene(m.scene);
  });
  m.check("building the Embree scene");
  m.built.store(true, std::memory_order_release);
}

bool AccelScene::built() const { return impl_->built.load(std::memory_order_acquire); }

void AccelScene::set_transforms(const std::vector<Affine>& object_to_world) {
  if (object_to_world.size() != groups_.size())
    throw std::invalid_argument(fmt::format("expected {} transforms (one per scene file), got {}", groups_.size(),
                                            object_to_world.size()));
  Impl& m = *impl_;
  bool changed = false;
  bounds_ = Bounds3{};
  for (size_t gi = 0; gi < groups_.size(); ++gi) {
    Group& g = groups_[gi];
    const Affine& a = object_to_world[gi];
    if (!g.geo.movable) {
      if (!a.is_identity())
        throw std::invalid_argument(fmt::format("scene group {} was built static and cannot be moved", gi));
      bounds_.extend(g.object_bounds);
      continue;
    }
    const Affine inv = a.inverse();  // throws for a singular transform
    if (a.m != g.to_world.m || a.translation != g.to_world.translation) {
      g.to_world = a;
      g.to_object = inv;
      g.identity = a.is_identity();
      float xf[12];
      to_rtc_transform(a, xf);
      rtcSetGeometryTransform(m.instances[gi], 0, RTC_FORMAT_FLOAT3X4_ROW_MAJOR, xf);
      rtcCommitGeometry(m.instances[gi]);
      changed = true;
    }
    bounds_.extend(transformed(g.object_bounds, g.to_world));
  }
  if (changed) m.built.store(false, std::memory_order_release);
  m.check("moving the scene's objects");
}

void AccelScene::set_positions(uint32_t group, const std::vector<float>& positions, uint64_t pose) {
  if (group >= groups_.size() || !groups_[group].geo.deformable)
    throw std::invalid_argument(fmt::format("scene group {} was not built deformable", group));
  Group& g = groups_[group];
  TriangleData& tri = g.geo.triangles;
  if (positions.size() != tri.positions.size())
    throw std::invalid_argument(fmt::format("scene group {} has {} vertices, got {}", group, tri.positions.size() / 3,
                                            positions.size() / 3));
  Impl& m = *impl_;
  std::copy(positions.begin(), positions.end(), tri.positions.begin());  // Embree shares this buffer
  if (!tri.indices.empty()) {
    RTCGeometry geom = rtcGetGeometry(m.children[group], static_cast<unsigned>(PrimKind::triangle));
    rtcUpdateGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0);
    rtcCommitGeometry(geom);
    m.child_stale[group] = 1;
    m.built.store(false, std::memory_order_release);
  }
  g.object_bounds = geometry_bounds(g.geo);
  g.pose = pose;
  bounds_ = Bounds3{};
  for (const Group& each : groups_) bounds_.extend(transformed(each.object_bounds, each.to_world));
  m.check("deforming a mesh");
}

Bounds3 AccelScene::group_bounds(uint32_t group, const Affine& to_world) const {
  return transformed(groups_[group].object_bounds, to_world);
}

size_t AccelScene::triangle_count() const {
  return std::accumulate(groups_.begin(), groups_.end(), size_t{0},
                         [](size_t n, const Group& g) { return n + g.geo.triangles.indices.size() / 3; });
}
size_t AccelScene::sphere_count() const {
  return std::accumulate(groups_.begin(), groups_.end(), size_t{0},
                         [](size_t n, const Group& g) { return n + g.geo.spheres.size(); });
}
size_t AccelScene::cone_count() const {
  return std::accumulate(groups_.begin(), groups_.end(), size_t{0},
                         [](size_t n, const Group& g) { return n + g.geo.cones.size(); });
}

void* AccelScene::rtc_scene() const { return impl_->traced(*this); }

bool AccelScene::refine(const Group& g, const Ray& r, bool strict, double t_guess, Hit& hit) const {
  // Work in the group's object space: there the geometry is exact (double)
  // and t is the same as in the world because the direction is not renormalised.
  const Vec3 o = g.identity ? r.org : g.to_object.point(r.org);
  const Vec3 d = g.identity ? r.dir : g.to_object.dir(r.dir);
  Vec3 n_obj;
  switch (hit.kind) {
    case PrimKind::triangle: {
      const TriangleData& tri = g.geo.triangles;
      const uint32_t* idx = &tri.indices[3 * size_t{hit.prim}];
      auto vtx = [&](int k) {
        const float* p = &tri.positions[3 * size_t{idx[k]}];
        return Vec3{p[0], p[1], p[2]};
      };
      const Vec3 v0 = vtx(0), e1 = vtx(1) - v0, e2 = vtx(2) - v0;
      const Vec3 n = normalize(cross(e1, e2));
      const double dn = dot(d, n);
      if (dn == 0) {
        if (strict) return false;
        hit.t = t_guess;
      } else {
        hit.t = dot(v0 - o, n) / dn;
      }
      const Vec3 p = o + d * hit.t;
      const double area = dot(cross(e1, e2), n);
      hit.u = dot(cross(p - v0, e2), n) / area;
      hit.v = dot(cross(e1, p - v0), n) / area;
      if (strict) {
        constexpr double kTol = 1e-9;
        if (!(hit.u >= -kTol && hit.v >= -kTol && hit.u + hit.v <= 1 + kTol)) return false;
        if (!(hit.t > r.tnear && hit.t < r.tfar)) return false;
      }
      n_obj = n;
      break;
    }
    case PrimKind::sphere:
    case PrimKind::cone: {
      double t;
      Vec3 n;
      const double slack = strict ? INFINITY : 1e-4 * std::fabs(t_guess) + 1e-7;
      const double lo = strict ? r.tnear : t_guess - slack, hi = strict ? r.tfar : t_guess + slack;
      const bool ok = hit.kind == PrimKind::sphere ? intersect_sphere(g.geo.spheres[hit.prim], o, d, lo, hi, t, n)
                                                   : intersect_cone(g.cones[hit.prim], o, d, lo, hi, t, n);
      if (!ok) {
        if (strict) return false;
        hit.t = t_guess;  // keep Embree's float answer (and normal, set by the caller)
        hit.p_object = o + d * hit.t;
        return true;
      }
      hit.t = t;
      hit.u = hit.v = 0;
      n_obj = n;
      break;
    }
  }
  hit.p_object = o + d * hit.t;
  hit.ng = g.identity ? n_obj : g.to_world.normal(n_obj);
  return true;
}

void AccelScene::resolve(const Ray& r, unsigned geom_id, unsigned inst_id, unsigned prim_id, const float ng[3],
                         float u, float v, float t, Hit& hit, bool refined) const {
  primitive_of(RawHit{geom_id, inst_id, prim_id, {}, 0, 0, 0}, hit.group, hit.kind, hit.prim);
  const Group& g = groups_[hit.group];
  // The refinement of a triangle sets its t, barycentrics and normal
  // whatever the ray; that of a sphere or cone keeps Embree's normal (object
  // space) and t where it finds no root.
  const bool refine_triangle = refined && hit.kind == PrimKind::triangle;
  if (!refine_triangle) {
    const Vec3 ng_obj = normalize(Vec3{ng[0], ng[1], ng[2]});
    hit.ng = g.identity ? ng_obj : g.to_world.normal(ng_obj);
    hit.u = u;
    hit.v = v;
  }
  // Spheres and cones keep their double-precision hit (their callbacks
  // computed it; a float one measured 75 dB on balls_s4's sphereflake).
  if (refined || hit.kind != PrimKind::triangle) {
    refine(g, r, false, t, hit);
    return;
  }
  hit.t = t;
  hit.p_object = g.identity ? r.org + r.dir * hit.t : g.to_object.point(r.org) + g.to_object.dir(r.dir) * hit.t;
}

bool AccelScene::intersect(const Ray& r, Hit& hit, RayCoherence coherence, bool refined) const {
  RTCRayHit rh;
  rh.ray = to_rtc_ray(r);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  embree::intersect1(impl_->traced(*this), rh, coherence == RayCoherence::coherent);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
  const float ng[3] = {rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z};
  resolve(r, rh.hit.geomID, rh.hit.instID[0], rh.hit.primID, ng, rh.hit.u, rh.hit.v, rh.ray.tfar, hit, refined);
  return true;
}

namespace {
// The packet's lanes as Embree's SoA layout; inactive lanes are zeroed and
// masked off. Same float conversion as to_rtc_ray.
template <class RTCRayK>
void to_rtc_packet(const RayPacket& p, RTCRayK& ray, int valid[kPacketSize]) {
  for (int k = 0; k < kPacketSize; ++k) {
    valid[k] = p.active[k] ? -1 : 0;
    const RTCRay one = p.active[k] ? to_rtc_ray(p.rays[k]) : RTCRay{};
    ray.org_x[k] = one.org_x;
    ray.org_y[k] = one.org_y;
    ray.org_z[k] = one.org_z;
    ray.dir_x[k] = one.dir_x;
    ray.dir_y[k] = one.dir_y;
    ray.dir_z[k] = one.dir_z;
    ray.tnear[k] = one.tnear;
    ray.tfar[k] = one.tfar;
    ray.time[k] = 0;
    ray.mask[k] = one.mask;
    ray.id[k] = static_cast<unsigned>(k);
    ray.flags[k] = 0;
  }
}
}  // namespace

void AccelScene::intersect_raw(const RayPacket& p, RawHit raw[kPacketSize], bool found[kPacketSize],
                               RayCoherence coherence) const {
  static_assert(kPacketSize == 16, "the packet kernels below are Embree's 16-wide ones");
  alignas(64) int valid[kPacketSize];
  alignas(64) RTCRayHit16 rh;
  to_rtc_packet(p, rh.ray, valid);
  for (int k = 0; k < kPacketSize; ++k) {
    rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
  }
  embree::intersect16(valid, impl_->traced(*this), rh, coherence == RayCoherence::coherent);
  for (int k = 0; k < kPacketSize; ++k) {
    found[k] = p.active[k] && rh.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID;
    if (!found[k]) continue;
    raw[k] = {rh.hit.geomID[k], rh.hit.instID[0][k], rh.hit.primID[k], {rh.hit.Ng_x[k], rh.hit.Ng_y[k], rh.hit.Ng_z[k]},
              rh.hit.u[k], rh.hit.v[k], rh.ray.tfar[k]};
  }
}

void AccelScene::refine_triangle_pair(const Ray* const r[2], const float t_guess[2], Hit* const hit[2]) const {
  Vec3 v0[2], v1[2], v2[2];
  for (int l = 0; l < 2; ++l) {
    const TriangleData& tri = groups_[hit[l]->group].geo.triangles;
    const uint32_t* idx = &tri.indices[3 * size_t{hit[l]->prim}];
    auto vtx = [&](int k) {
      const float* p = &tri.positions[3 * size_t{idx[k]}];
      return Vec3{p[0], p[1], p[2]};
    };
    v0[l] = vtx(0), v1[l] = vtx(1), v2[l] = vtx(2);
  }
  // refine()'s triangle case for two lanes, in its operations and order.
  const Vec3Pair o = pair_of(r[0]->org, r[1]->org), d = pair_of(r[0]->dir, r[1]->dir);
  const Vec3Pair a = pair_of(v0[0], v0[1]), e1 = pair_of(v1[0], v1[1]) - a, e2 = pair_of(v2[0], v2[1]) - a;
  const Vec3Pair m = cross(e1, e2), n = normalize(m);
  const __m128d dn = dot(d, n);
  // A ray in the triangle's plane keeps Embree's t.
  const __m128d t = select(_mm_cmpeq_pd(dn, _mm_setzero_pd()), _mm_set_pd(t_guess[1], t_guess[0]),
                           _mm_div_pd(dot(a - o, n), dn));
  const Vec3Pair p = along(o, d, t), q = p - a;
  const __m128d area = dot(m, n);
  const __m128d u = _mm_div_pd(dot(cross(q, e2), n), area), v = _mm_div_pd(dot(cross(e1, q), n), area);
  for (int l = 0; l < 2; ++l) {
    Hit& h = *hit[l];
    h.t = lane(t, l);
    h.u = lane(u, l);
    h.v = lane(v, l);
    h.p_object = lane(p, l);
    h.ng = lane(n, l);
  }
}

void AccelScene::intersect(const RayPacket& p, Hit hits[kPacketSize], bool found[kPacketSize],
                           RayCoherence coherence, bool refined) const {
  RawHit raw[kPacketSize];
  intersect_raw(p, raw, found, coherence);
  // Triangles of groups placed by the identity (the eye rays' usual hits)
  // are refined two lanes at a time, bit for bit refine(); the others one
  // by one.
  int pending = -1;
  for (int k = 0; k < kPacketSize; ++k) {
    if (!found[k]) continue;
    Hit& h = hits[k];
    if (refined) {
      primitive_of(raw[k], h.group, h.kind, h.prim);
      if (h.kind == PrimKind::triangle && groups_[h.group].identity) {
        if (pending < 0) {
          pending = k;
          continue;
        }
        const Ray* r[2] = {&p.rays[pending], &p.rays[k]};
        const float t[2] = {raw[pending].t, raw[k].t};
        Hit* const two[2] = {&hits[pending], &h};
        refine_triangle_pair(r, t, two);
        pending = -1;
        continue;
      }
    }
    resolve(p.rays[k], raw[k].geom_id, raw[k].inst_id, raw[k].prim_id, raw[k].ng, raw[k].u, raw[k].v, raw[k].t, h,
            refined);
  }
  if (pending >= 0) {
    const RawHit& r = raw[pending];
    resolve(p.rays[pending], r.geom_id, r.inst_id, r.prim_id, r.ng, r.u, r.v, r.t, hits[pending], refined);
  }
}

void AccelScene::primitive_of(const RawHit& raw, uint32_t& group, PrimKind& kind, uint32_t& prim) const {
  if (raw.inst_id != RTC_INVALID_GEOMETRY_ID) {
    group = raw.inst_id / 3;
    kind = static_cast<PrimKind>(raw.geom_id);
  } else {
    group = raw.geom_id / 3;
    kind = static_cast<PrimKind>(raw.geom_id % 3);
  }
  prim = raw.prim_id;
}

namespace {
// Whether a shadow packet takes the coherent traversal. Embree 3.13.5's
// coherent occlusion packets loop forever in a scene with instances (seen
// on animated glTF shots): coherent only without.
bool coherent_occlusion(RayCoherence coherence, bool instanced) {
  return coherence == RayCoherence::coherent && !instanced;
}
}  // namespace

void AccelScene::occluded(const RayPacket& p, bool blocked[kPacketSize], RayCoherence coherence) const {
  alignas(64) int valid[kPacketSize];
  alignas(64) RTCRay16 ray;
  to_rtc_packet(p, ray, valid);
  embree::occluded16(valid, impl_->traced(*this), ray, coherent_occlusion(coherence, impl_->instanced));
  for (int k = 0; k < kPacketSize; ++k) blocked[k] = p.active[k] && ray.tfar[k] == -INFINITY;
}

// ShadowPacket's rays are RTCRay16's members in RTCRay16's order.
static_assert(sizeof(RTCRay16) == offsetof(ShadowPacket, valid) && offsetof(ShadowPacket, tfar) == offsetof(RTCRay16, tfar) &&
              offsetof(ShadowPacket, flags) == offsetof(RTCRay16, flags));

void AccelScene::occluded(ShadowPacket& p, bool blocked[kPacketSize], RayCoherence coherence) const {
  static_assert(alignof(ShadowPacket) >= alignof(RTCRay16));
  embree::occluded16(p.valid, impl_->traced(*this), *reinterpret_cast<RTCRay16*>(&p),
                     coherent_occlusion(coherence, impl_->instanced));
  for (int k = 0; k < kPacketSize; ++k) blocked[k] = p.valid[k] != 0 && p.tfar[k] == -INFINITY;
}

bool AccelScene::intersect_primitive(const Ray& r, uint32_t group, PrimKind kind, uint32_t prim, Hit& hit) const {
  if (group >= groups_.size()) return false;
  const Group& g = groups_[group];
  const size_t count = kind == PrimKind::triangle ? g.geo.triangles.indices.size() / 3
                       : kind == PrimKind::sphere ? g.geo.spheres.size()
                                                  : g.geo.cones.size();
  if (prim >= count) return false;
  hit.group = group;
  hit.kind = kind;
  hit.prim = prim;
  return refine(g, r, true, 0, hit);
}

bool AccelScene::occluded(const Ray& r) const {
  RTCRay ray = to_rtc_ray(r);
  embree::occluded1(impl_->traced(*this), ray, false);
  return ray.tfar == -INFINITY;
}

}  // namespace holoray
