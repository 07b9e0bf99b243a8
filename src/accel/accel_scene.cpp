#include "accel/accel_scene.hpp"

#include <embree3/rtcore.h>
#include <fmt/format.h>

#include <cmath>
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
inline bool hit_shape(const Cone& c, const Vec3& o, const Vec3& d, double tn, double tf, double& t, Vec3& n) {
  return intersect_cone(c, o, d, tn, tf, t, n);
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
  const unsigned N = args->N;
  for (unsigned i = 0; i < N; ++i) {
    if (args->valid[i] != -1) continue;
    const Vec3 o{RTCRayN_org_x(args->ray, N, i), RTCRayN_org_y(args->ray, N, i), RTCRayN_org_z(args->ray, N, i)};
    const Vec3 d{RTCRayN_dir_x(args->ray, N, i), RTCRayN_dir_y(args->ray, N, i), RTCRayN_dir_z(args->ray, N, i)};
    double t;
    Vec3 n;
    if (hit_shape(shape, o, d, RTCRayN_tnear(args->ray, N, i), RTCRayN_tfar(args->ray, N, i), t, n))
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

struct AccelScene::Impl {
  std::string last_error;
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;

  void check(const char* what) {
    if (!last_error.empty()) throw std::runtime_error(fmt::format("{}: {}", what, last_error));
  }
  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

AccelScene::AccelScene(TriangleData triangles, std::vector<Sphere> spheres, std::vector<Cone> cones)
    : impl_(std::make_unique<Impl>()), tri_(std::move(triangles)), spheres_(std::move(spheres)), cones_(std::move(cones)) {
  Impl& m = *impl_;
  m.device = rtcNewDevice(nullptr);
  if (!m.device) throw std::runtime_error(fmt::format("cannot create the Embree device (error {})", static_cast<int>(rtcGetDeviceError(nullptr))));
  rtcSetDeviceErrorFunction(m.device, on_embree_error, &m.last_error);
  m.scene = rtcNewScene(m.device);
  // Robust mode: watertight triangle edges (rays exactly on a shared edge
  // otherwise fall through; the plane-depth test hits this).
  rtcSetSceneFlags(m.scene, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(m.scene, RTC_BUILD_QUALITY_HIGH);
  m.check("creating the Embree scene");

  if (!tri_.indices.empty()) {
    RTCGeometry g = rtcNewGeometry(m.device, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, tri_.positions.data(), 0, 3 * sizeof(float),
                               tri_.positions.size() / 3);
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, tri_.indices.data(), 0, 3 * sizeof(uint32_t),
                               tri_.indices.size() / 3);
    rtcCommitGeometry(g);
    rtcAttachGeometryByID(m.scene, g, static_cast<unsigned>(PrimKind::triangle));
    rtcReleaseGeometry(g);
    for (size_t i = 0; i + 2 < tri_.positions.size(); i += 3)
      bounds_.extend(Vec3{tri_.positions[i], tri_.positions[i + 1], tri_.positions[i + 2]});
  }
  auto add_user = [&](auto& shapes, PrimKind kind) {
    using Shape = typename std::remove_reference_t<decltype(shapes)>::value_type;
    if (shapes.empty()) return;
    RTCGeometry g = rtcNewGeometry(m.device, RTC_GEOMETRY_TYPE_USER);
    rtcSetGeometryUserPrimitiveCount(g, static_cast<unsigned>(shapes.size()));
    rtcSetGeometryUserData(g, shapes.data());
    rtcSetGeometryBoundsFunction(g, shape_bounds<Shape>, nullptr);
    rtcSetGeometryIntersectFunction(g, shape_intersect<Shape>);
    rtcSetGeometryOccludedFunction(g, shape_occluded<Shape>);
    rtcCommitGeometry(g);
    rtcAttachGeometryByID(m.scene, g, static_cast<unsigned>(kind));
    rtcReleaseGeometry(g);
    for (const Shape& s : shapes) bounds_.extend(bounds_of(s));
  };
  add_user(spheres_, PrimKind::sphere);
  add_user(cones_, PrimKind::cone);
  rtcCommitScene(m.scene);
  m.check("building the Embree scene");
}

AccelScene::~AccelScene() = default;

void* AccelScene::rtc_scene() const { return impl_->scene; }

bool AccelScene::intersect(const Ray& r, Hit& hit, RayCoherence coherence) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  if (coherence == RayCoherence::coherent) ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  RTCRayHit rh;
  rh.ray = to_rtc_ray(r);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(impl_->scene, &ctx, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;

  hit.kind = static_cast<PrimKind>(rh.hit.geomID);
  hit.prim = rh.hit.primID;
  hit.u = rh.hit.u;
  hit.v = rh.hit.v;
  hit.t = rh.ray.tfar;
  // Refine t (and the normal) in double precision: Embree reports float.
  switch (hit.kind) {
    case PrimKind::triangle: {
      const uint32_t* idx = &tri_.indices[3 * size_t{hit.prim}];
      auto vtx = [&](int k) {
        const float* p = &tri_.positions[3 * size_t{idx[k]}];
        return Vec3{p[0], p[1], p[2]};
      };
      const Vec3 v0 = vtx(0), v1 = vtx(1), v2 = vtx(2);
      const Vec3 n = normalize(cross(v1 - v0, v2 - v0));
      hit.ng = n;
      const double dn = dot(r.dir, n);
      if (dn != 0) hit.t = dot(v0 - r.org, n) / dn;
      break;
    }
    case PrimKind::sphere: {
      double t;
      Vec3 n;
      const double slack = 1e-4 * std::fabs(hit.t) + 1e-7;
      hit.ng = normalize(Vec3{rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z});
      if (intersect_sphere(spheres_[hit.prim], r.org, r.dir, hit.t - slack, hit.t + slack, t, n)) {
        hit.t = t;
        hit.ng = n;
      }
      break;
    }
    case PrimKind::cone: {
      double t;
      Vec3 n;
      const double slack = 1e-4 * std::fabs(hit.t) + 1e-7;
      hit.ng = normalize(Vec3{rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z});
      if (intersect_cone(cones_[hit.prim], r.org, r.dir, hit.t - slack, hit.t + slack, t, n)) {
        hit.t = t;
        hit.ng = n;
      }
      break;
    }
  }
  return true;
}

bool AccelScene::occluded(const Ray& r) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRay ray = to_rtc_ray(r);
  rtcOccluded1(impl_->scene, &ctx, &ray);
  return ray.tfar == -INFINITY;
}

}  // namespace holoray
