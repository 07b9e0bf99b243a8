#include "render/path_tracer.hpp"

#include <cmath>
#include <new>
#include <type_traits>

#include "render/emitters.hpp"
#include "render/environment.hpp"
#include "render/gltf_brdf.hpp"
#include "render/light_falloff.hpp"
#include "render/path_records.h"
#include "render/shading_vec.hpp"

namespace holoray {

Vec3 path_escape(const RenderContext& scene, const Vec3& dir) {
  const EnvironmentMap* env = scene.settings().environment;
  return env ? env->radiance(dir) : scene.background();
}

}  // namespace holoray

// The CPU's hooks of the shared integrator (render/path_integrator.h): its
// scene is the RenderContext, traced by Embree.
namespace holoray::shading {

struct HrPathDevice {
  const RenderContext& scene;
  RayCounts& counts;
  const EnvironmentMap* env;  ///< null: the background colour, not light-sampled
  const EmissiveTriangles* emitters;
  SurfacePoint* first;  ///< the first hit's surface, hit, and whether there was one (optional)
  Hit* first_hit;
  bool* hit_found;
  FirstVertexRecord* record = nullptr;  ///< optional: the first vertex's light (path_tracer.hpp)
  int depth = 0;                        ///< the last ray traced's vertex, while recording
};

struct HrPathHit {
  Hit hit;
  SurfacePoint sp;
};

// Read where they are: copied out each bounce, they cost 1 % of a path.
static inline double hr_path_hit_t(const HrPathHit& h) { return h.hit.t; }
static inline const Vec3& hr_path_hit_p(const HrPathHit& h) { return h.sp.position; }
static inline const Vec3& hr_path_hit_ng(const HrPathHit& h) { return h.sp.ng; }
static inline const Vec3& hr_path_hit_ns(const HrPathHit& h) { return h.sp.ns; }

static inline bool hr_path_trace(HrPathDevice& d, const Vec3& o, const Vec3& dir, double tmin, double tmax, int depth,
                                 HrPathHit& h) {
  const Ray ray{o, dir, tmin, tmax};
  if (d.record) {
    d.depth = depth;
    if (depth == 2) d.record->bounce_dir = dir, d.record->bounced = true;
  }
  if (!d.scene.accel().intersect(ray, h.hit, depth == 1 ? RayCoherence::coherent : RayCoherence::incoherent)) return false;
  // Built in place (a prvalue's guaranteed elision): assigned, the 136-byte
  // record was copied each bounce, 2 % of a path.
  static_assert(std::is_trivially_destructible_v<SurfacePoint>);
  ::new (&h.sp) SurfacePoint(d.scene.surface(ray, h.hit));
  if (depth == 1) {
    if (d.first) *d.first = h.sp;
    if (d.first_hit) *d.first_hit = h.hit;
    if (d.hit_found) *d.hit_found = true;
  }
  // Tachyon's colour is its texture's (or its vertex colours') at the hit,
  // seen at the distance along this ray, as Whitted's shading and the GPU's
  // hook read it; the AOVs above keep the material's own colour, as theirs.
  if (h.sp.material->model == ShadingModel::tachyon) h.sp.colour = d.scene.surface_colour(h.sp, length(h.sp.position - o));
  if (depth == 1 && d.record) d.record->hit = h.hit, d.record->surface = h.sp;
  return true;
}

static inline Vec3 hr_path_unblocked(HrPathDevice& d, const Vec3& from, const Vec3& dir, double tmax, const Vec3& term) {
  if (d.scene.accel().occluded(Ray{from, dir, 0, tmax})) return {};
  if (d.record && d.depth == 1) {  // a next-event term at the first vertex
    FirstVertexRecord& r = *d.record;
    if (r.terms == FirstVertexRecord::kMaxTerms) r.overflow = true;
    else r.dir[r.terms] = dir, r.incoming[r.terms++] = term;
  }
  return term;
}

static inline void hr_path_count(HrPathDevice& d, int kind) {
  if (kind == HR_PATH_RAY_SHADOW) ++d.counts.shadow;
  else if (kind == HR_PATH_RAY_REFRACTED) ++d.counts.refracted;
  else ++d.counts.reflected;
}

static inline double hr_path_epsilon(HrPathDevice& d) { return d.scene.epsilon(); }
static inline int hr_path_max_depth(HrPathDevice& d) { return d.scene.max_depth(); }

// A Tachyon light's sphere: its colour, unshaded.
static inline bool hr_path_light_sphere(HrPathDevice& d, const HrPathHit& h, Vec3& colour) {
  if (!h.sp.material->emitter) return false;
  colour = h.sp.colour;
  if (d.record && d.depth == 1) d.record->sphere = true;
  return true;
}

static inline Vec3 hr_path_emission(HrPathDevice& d, const HrPathHit& h, const Vec3& dir, bool specular, float last_pdf) {
  const Hit& hit = h.hit;
  const Material& m = *h.sp.material;
  if (!(m.emission.x > 0 || m.emission.y > 0 || m.emission.z > 0)) return {};
  double w = 1;
  if (!specular && d.emitters && hit.kind == PrimKind::triangle) {
    const float pdf_light = hr_area_to_solid_angle(static_cast<float>(d.emitters->pdf_area(hit.group, hit.prim)),
                                                   static_cast<float>(hit.t * hit.t),
                                                   static_cast<float>(std::fabs(dot(h.sp.ng, dir))));
    w = hr_power_heuristic(last_pdf, pdf_light);
  }
  const Vec3 e = d.scene.emission(h.sp, hit.t) * w;
  if (d.record && d.depth == 1) d.record->emission = e;
  return e;
}

// Which lobe each model's terms become: shading/bsdf.h. `entering`: the ray
// met the outward side, for a refracting material's relative index.
static inline HrBsdf hr_path_bsdf(HrPathDevice& d, const HrPathHit& h, float cos_o, bool entering) {
  const SurfacePoint& sp = h.sp;
  const Material& m = *sp.material;
  const Vec3 c = sp.colour;
  switch (m.model) {
    case ShadingModel::gltf:
      return (d.scene.settings().principled ? hr_principled_bsdf : hr_gltf_bsdf)(
          to_f(c), sp.metallic, sp.roughness, static_cast<float>(dielectric_f0(m.ior)), static_cast<float>(m.transmission), cos_o);
    case ShadingModel::tachyon:
      // Tachyon's transparency goes straight on (no refraction, ior 1).
      return hr_plain_bsdf(to_f(c * m.kd), vec3(static_cast<float>(m.ks)), vec3(static_cast<float>(m.transmittance)), 1.0f);
    case ShadingModel::nff:
    case ShadingModel::blinn_phong:
      break;
  }
  const float ior = m.ior > 0 ? static_cast<float>(m.ior) : 1.0f;
  return hr_plain_bsdf(to_f(c * m.kd), vec3(static_cast<float>(m.ks)), vec3(static_cast<float>(m.transmittance)),
                       entering ? 1.0f / ior : ior);
}

static inline int hr_path_light_count(HrPathDevice& d) { return static_cast<int>(d.scene.lights().size()); }

static inline HrPathLight hr_path_light(HrPathDevice& d, int l) {
  const PointLight& light = d.scene.lights()[static_cast<size_t>(l)];
  HrPathLight L;
  L.kind = static_cast<int>(light.kind);
  L.position = light.position, L.direction = light.direction, L.intensity = light.intensity;
  L.cos_half_angle = light.cos_half_angle, L.radius = light.radius;
  L.falloff = falloff_params(light);
  L.skip = light.headlight && d.scene.settings().skip_headlights;
  return L;
}

static inline int hr_path_area_light_count(HrPathDevice& d) { return static_cast<int>(d.scene.scene().area_lights().size()); }

static inline HrPathAreaLight hr_path_area_light(HrPathDevice& d, int a) {
  const AreaLight& light = d.scene.scene().area_lights()[static_cast<size_t>(a)];
  HrPathAreaLight A;
  A.centre = light.centre, A.axis_u = light.axis_u, A.axis_v = light.axis_v, A.normal = light.normal;
  A.radiance = light.radiance, A.area = light.area, A.ellipse = light.ellipse;
  return A;
}

static inline Vec3 hr_path_escape(HrPathDevice& d, const Vec3& dir) { return path_escape(d.scene, dir); }
static inline bool hr_path_env_lights(HrPathDevice& d) { return d.env && !d.env->black(); }
static inline float hr_path_env_pdf(HrPathDevice& d, const Vec3& dir) { return static_cast<float>(d.env->pdf(dir)); }

static inline Vec3 hr_path_env_sample(HrPathDevice& d, float u_cell, vec2 u, Vec3& dir, double& pdf) {
  return d.env->sample(u_cell, u.x, u.y, dir, pdf);
}

static inline bool hr_path_has_emitters(HrPathDevice& d) { return d.emitters && !d.emitters->empty(); }

static inline bool hr_path_emitter_sample(HrPathDevice& d, vec2 u_pick, vec2 u_emit, const Vec3& p, Vec3& dir, double& dist,
                                          Vec3& le, double& pdf) {
  const EmissiveTriangles::Sample s = d.emitters->sample(u_pick.x, u_emit.x, u_emit.y);
  dir = s.position - p;
  const double dist2 = dot(dir, dir);
  dist = std::sqrt(dist2);
  dir = dir / dist;
  const double cos_l = std::fabs(dot(s.normal, dir));  // emission is two-sided
  if (!(dist > 2 * d.scene.epsilon() && cos_l > 0)) return false;
  pdf = s.pdf_area * dist2 / cos_l;
  le = d.scene.emission(s.surface, dist) * (1 / pdf);
  return true;
}

}  // namespace holoray::shading

#include "render/path_integrator.h"

namespace holoray {

namespace {

using shading::HrPathDevice;

bool any_positive(const shading::vec3& v) { return v.x > 0 || v.y > 0 || v.z > 0; }

// The shading normal on the side of the surface an eye looking along
// `eye_dir` sees, as hr_path_vertex turns it.
Vec3 eye_side_normal(const SurfacePoint& s, const Vec3& eye_dir) { return dot(s.ng, eye_dir) <= 0 ? s.ns : -s.ns; }

// Turns the record of a traced path into FirstVertexRecord's terms: each
// next-event term over f at x, the bounce's share (what the path gathered
// past x) over f along the bounce, and whether it may be shared.
void finish_record(HrPathDevice& d, FirstVertexRecord& r, const Vec3& radiance, bool found) {
  if (!found || r.sphere || r.overflow) return;
  const shading::HrPathHit h{r.hit, r.surface};
  r.vertex = shading::hr_path_vertex(d, h, r.eye_dir);
  const shading::HrPathVertex& v = r.vertex;
  if (any_positive(v.bsdf.mirror) || (any_positive(v.bsdf.transmit) && !(v.bsdf.transmit_alpha > 0))) return;
  r.shareable = true;
  r.radiance = radiance;
  r.shading_normal = dot(eye_side_normal(r.surface, r.eye_dir), r.eye_dir) < 0;
  // f = albedo cos / pi whatever the eye (hr_bsdf_eval): the terms need no
  // second look.
  r.lambert = !(v.bsdf.alpha > 0) && !any_positive(v.bsdf.transmit) && !(v.bsdf.principled > 0);
  if (r.lambert) return;
  Vec3 rest = radiance - r.emission;
  for (int k = 0; k < r.terms; ++k) rest -= r.incoming[k];
  rest = {std::fmax(rest.x, 0.0), std::fmax(rest.y, 0.0), std::fmax(rest.z, 0.0)};  // rounding
  if (r.bounced && (rest.x > 0 || rest.y > 0 || rest.z > 0)) {
    if (r.terms == FirstVertexRecord::kMaxTerms) {
      r.shareable = false;
      return;
    }
    r.dir[r.terms] = r.bounce_dir, r.incoming[r.terms++] = rest;
  }
  for (int k = 0; k < r.terms; ++k) {
    r.dir_local[k] = shading::hr_to_local(to_f(r.dir[k]), v.t, v.b, v.n);
    const shading::vec3 f = shading::hr_bsdf_eval(v.bsdf, v.wo, r.dir_local[k]);
    auto over = [](double term, float fk) { return fk > 0 ? term / fk : 0.0; };
    r.incoming[k] = {over(r.incoming[k].x, f.x), over(r.incoming[k].y, f.y), over(r.incoming[k].z, f.z)};
  }
}

}  // namespace

Vec3 path_radiance(const RenderContext& scene, const Ray& eye, shading::HrSampler& sampler, RayCounts& counts,
                   SurfacePoint* first, Hit* first_hit, bool* hit_found, FirstVertexRecord* record) {
  bool found = false;
  if (record) {
    record->clear(eye.dir);
    if (!hit_found) hit_found = &found;
  }
  if (hit_found) *hit_found = false;
  HrPathDevice d{scene, counts, scene.settings().environment, scene.settings().emitters, first, first_hit, hit_found, record};
  const Vec3 radiance = shading::hr_path_radiance(d, eye.org, eye.dir, eye.tnear, eye.tfar, sampler);
  if (record) finish_record(d, *record, radiance, *hit_found);
  return radiance;
}

bool path_radiance_toward(const RenderContext& scene, const FirstVertexRecord& r, const Vec3& dir, Vec3& out) {
  // The record's side of the surface must face this eye too.
  const Vec3& ng = r.surface.ng;
  if ((dot(ng, r.eye_dir) <= 0) != (dot(ng, dir) <= 0)) return false;
  // The same frame at x for both eyes (hr_path_vertex): the shading
  // normal, unless it turns from the eye.
  if (r.shading_normal != (dot(eye_side_normal(r.surface, r.eye_dir), dir) < 0)) return false;
  if (r.lambert) {
    out = r.radiance;
    return true;
  }
  const shading::HrPathVertex& v = r.vertex;
  const shading::vec3 wo = shading::hr_to_local(to_f(-dir), v.t, v.b, v.n);
  shading::HrBsdf bsdf = v.bsdf;
  if (any_positive(bsdf.transmit)) {  // glTF's transmitted share is 1 - F at the eye's angle (hr_gltf_bsdf)
    RayCounts unused;
    HrPathDevice d{scene, unused, nullptr, nullptr, nullptr, nullptr, nullptr};
    bsdf = shading::hr_path_bsdf(d, shading::HrPathHit{r.hit, r.surface}, wo.z, dot(ng, dir) <= 0);
  }
  out = r.emission;
  for (int k = 0; k < r.terms; ++k) {
    const shading::vec3 f = shading::hr_bsdf_eval(bsdf, wo, r.dir_local[k]);
    out += Vec3{f.x * r.incoming[k].x, f.y * r.incoming[k].y, f.z * r.incoming[k].z};
  }
  return true;
}

}  // namespace holoray
