#include "render/path_tracer.hpp"

#include <algorithm>
#include <cmath>

#include "render/emitters.hpp"
#include "render/environment.hpp"
#include "render/gltf_brdf.hpp"
#include "render/light_falloff.hpp"
#include "render/shading_vec.hpp"
#include "shading/bsdf.h"
#include "shading/lights.h"
#include "shading/warp.h"

namespace holoray {

namespace sh = shading;

namespace {


// Russian roulette starts after this many bounces (pbrt-v4's depth 1 of
// its 0-based count is our third vertex: the eye's, and two more).
constexpr int kRouletteDepth = 3;

// A vertex's BSDF from its material (shading/bsdf.h: which lobe each
// model's terms become). `entering`: the ray met the outward side, for a
// refracting material's relative index.
sh::HrBsdf bsdf_of(const SurfacePoint& sp, float cos_o, bool entering, bool principled) {
  const Material& m = *sp.material;
  const Vec3 c = sp.colour;
  switch (m.model) {
    case ShadingModel::gltf:
      return (principled ? sh::hr_principled_bsdf : sh::hr_gltf_bsdf)(to_f(c), sp.metallic, sp.roughness, static_cast<float>(dielectric_f0(m.ior)),
                              static_cast<float>(m.transmission), cos_o);
    case ShadingModel::tachyon:
      // Tachyon's transparency goes straight on (no refraction, ior 1).
      return sh::hr_plain_bsdf(to_f(c * m.kd), sh::vec3(static_cast<float>(m.ks)), sh::vec3(static_cast<float>(m.transmittance)),
                               1.0f);
    case ShadingModel::nff:
    case ShadingModel::blinn_phong:
      break;
  }
  const float ior = m.ior > 0 ? static_cast<float>(m.ior) : 1.0f;
  return sh::hr_plain_bsdf(to_f(c * m.kd), sh::vec3(static_cast<float>(m.ks)), sh::vec3(static_cast<float>(m.transmittance)),
                           entering ? 1.0f / ior : ior);
}

bool black(const Vec3& v) { return !(v.x > 0 || v.y > 0 || v.z > 0); }

}  // namespace

Vec3 path_escape(const RenderContext& scene, const Vec3& dir) {
  const EnvironmentMap* env = scene.settings().environment;
  return env ? env->radiance(dir) : scene.background();
}

namespace {

// A path's vertex: where it is, its local frame (the shading normal turned
// to the side the path came from, +z), the direction back along the path
// and the BSDF there.
struct Vertex {
  Vec3 position, ng, above, below;
  sh::vec3 t, b, n, wo;
  sh::HrBsdf bsdf;
};

// One light sample's share at vertex `v`: light arriving along `dir`
// (world, unit) from `dist` away, `le` its radiance over the density it was
// drawn with (solid angle; `pdf` 0 for a delta light, which nothing else can
// draw), MIS-weighted against the BSDF's own sampling of `dir`. Zero when
// the light is behind the surface (unless it transmits, rough: then from
// behind, on that side of the shading normal too) or blocked.
Vec3 light_sample(const RenderContext& scene, const Vertex& v, const Vec3& dir, double dist, const Vec3& le, double pdf,
                  RayCounts& counts) {
  const bool behind = dot(dir, v.ng) <= 0;
  if (behind && !(v.bsdf.transmit_alpha > 0)) return {};
  const sh::vec3 wi = sh::hr_to_local(to_f(dir), v.t, v.b, v.n);
  if (behind != (wi.z < 0)) return {};
  const sh::vec3 f = sh::hr_bsdf_eval(v.bsdf, v.wo, wi);
  if (!(f.x > 0 || f.y > 0 || f.z > 0)) return {};
  ++counts.shadow;
  const Vec3 from = behind ? v.below : v.above;
  if (scene.accel().occluded(Ray{from, dir, 0, std::isinf(dist) ? INFINITY : dist - 2 * scene.epsilon()})) return {};
  const double w = pdf > 0 ? sh::hr_power_heuristic(static_cast<float>(pdf), sh::hr_bsdf_pdf(v.bsdf, v.wo, wi)) : 1.0;
  return mul(to_d(f), le) * w;
}

// Next-event estimation at `v`: every point, spot and directional light
// (one point of a soft one), every area light (one point each), one
// direction of the environment, one point of the emissive surfaces.
Vec3 direct_light(const RenderContext& scene, const Vertex& v, sh::HrSampler& sampler, RayCounts& counts) {
  const double eps = scene.epsilon();
  Vec3 sum;
  for (const PointLight& light : scene.lights()) {
    if (light.headlight && scene.settings().skip_headlights) continue;
    const sh::vec2 u = sh::hr_next2(sampler);  // a pair for each light, soft or not: the streams stay aligned
    Vec3 dir = -light.direction, from = light.position;
    double dist = INFINITY, cos_l = 1;
    if (light.kind == LightKind::directional) {
      if (light.cos_half_angle < 1) {
        // Uniform over the sun's cone: radiance S / cone, so the estimate
        // is f S, as a delta light's (Cycles' disk: within 0.01 %).
        sh::vec3 ct, cb;
        const sh::vec3 axis = to_f(dir);
        sh::hr_frame(axis, ct, cb);
        dir = normalize(to_d(sh::hr_to_world(sh::hr_uniform_cone(u, float(light.cos_half_angle)), ct, cb, axis)));
      }
    } else {
      if (light.radius > 0) {
        // A disk facing the point (Cycles' sphere light): drawn uniformly,
        // its radiance I / (pi r^2) makes the estimate f I cos_l / d^2.
        const Vec3 facing = normalize(v.position - light.position);
        from = to_d(sh::hr_disk_light_point(to_f(light.position), to_f(facing), float(light.radius), u));
        cos_l = std::fabs(dot(facing, normalize(v.position - from)));
      }
      dir = from - v.position;
      dist = length(dir);
      if (!(dist > eps)) continue;
      dir = dir / dist;
    }
    const float falloff = sh::hr_light_falloff(falloff_params(light), to_f(dir), static_cast<float>(dist));
    if (falloff > 0) sum += light_sample(scene, v, dir, dist, light.intensity * (M_PI * falloff * cos_l), 0, counts);
  }
  for (const AreaLight& a : scene.scene().area_lights()) {
    const sh::vec2 u = sh::hr_next2(sampler);
    Vec3 dir = to_d(sh::hr_area_light_point(to_f(a.centre), to_f(a.axis_u), to_f(a.axis_v), a.ellipse, u)) - v.position;
    const double dist2 = dot(dir, dir), dist = std::sqrt(dist2);
    if (!(dist > eps)) continue;
    dir = dir / dist;
    const double cos_l = -dot(dir, a.normal);  // one-sided: it lights the side its normal faces
    if (!(cos_l > 0)) continue;
    const double pdf = dist2 / (cos_l * a.area);
    sum += light_sample(scene, v, dir, dist, a.radiance * (1 / pdf), pdf, counts);
  }
  // The environment and the emitters draw their dimensions only where the
  // render has them (fixed per render: the streams stay aligned).
  const EnvironmentMap* env = scene.settings().environment;
  if (env && !env->black()) {
    const sh::vec2 u_cell = sh::hr_next2(sampler), u_env = sh::hr_next2(sampler);
    Vec3 dir;
    double pdf;
    const Vec3 le = env->sample(u_cell.x, u_env.x, u_env.y, dir, pdf);
    if (pdf > 0) sum += light_sample(scene, v, dir, INFINITY, le * (1 / pdf), pdf, counts);
  }
  if (const EmissiveTriangles* emitters = scene.settings().emitters; emitters && !emitters->empty()) {
    const sh::vec2 u_pick = sh::hr_next2(sampler), u_emit = sh::hr_next2(sampler);
    const EmissiveTriangles::Sample s = emitters->sample(u_pick.x, u_emit.x, u_emit.y);
    Vec3 dir = s.position - v.position;
    const double dist2 = dot(dir, dir), dist = std::sqrt(dist2);
    dir = dir / dist;
    const double cos_l = std::fabs(dot(s.normal, dir));  // emission is two-sided
    if (dist > 2 * eps && cos_l > 0) {
      const double pdf = s.pdf_area * dist2 / cos_l;
      sum += light_sample(scene, v, dir, dist, scene.emission(s.surface, dist) * (1 / pdf), pdf, counts);
    }
  }
  return sum;
}

// What the path's ray meets of the lights that light sampling also draws:
// area lights before `t_max` (seen from their lit side; not by the eye, as
// Blender's by default) and, at its hit, an emissive surface; each weighted
// against its light sampling's density unless the bounce was a delta lobe.
Vec3 area_lights_met(const RenderContext& scene, const Ray& ray, double t_max, bool specular, double last_pdf) {
  Vec3 sum;
  for (const AreaLight& a : scene.scene().area_lights()) {
    const float t = sh::hr_area_light_hit(to_f(ray.org), to_f(ray.dir), static_cast<float>(std::fmin(t_max, 3.0e38)),
                                          to_f(a.centre), to_f(a.axis_u), to_f(a.axis_v), to_f(a.normal), a.ellipse);
    const double cos_l = -dot(ray.dir, a.normal);
    if (!(t > 0) || !(cos_l > 0)) continue;
    const float pdf_light = sh::hr_area_to_solid_angle(static_cast<float>(1 / a.area), t * t, static_cast<float>(cos_l));
    sum += a.radiance * (specular ? 1.0 : sh::hr_power_heuristic(static_cast<float>(last_pdf), pdf_light));
  }
  return sum;
}

Vec3 emission_met(const RenderContext& scene, const SurfacePoint& sp, const Hit& hit, const Ray& ray, bool specular,
                  double last_pdf) {
  const EmissiveTriangles* emitters = scene.settings().emitters;
  double w = 1;
  if (!specular && emitters && hit.kind == PrimKind::triangle) {
    const float pdf_light = sh::hr_area_to_solid_angle(static_cast<float>(emitters->pdf_area(hit.group, hit.prim)),
                                                       static_cast<float>(hit.t * hit.t),
                                                       static_cast<float>(std::fabs(dot(sp.ng, ray.dir))));
    w = sh::hr_power_heuristic(static_cast<float>(last_pdf), pdf_light);
  }
  return scene.emission(sp, hit.t) * w;
}

// The vertex at `sp`, met along `ray`.
Vertex vertex_at(const RenderContext& scene, const Ray& ray, const SurfacePoint& sp) {
  Vertex v;
  v.position = sp.position;
  const Vec3 view = -ray.dir;
  const bool front = dot(sp.ng, view) >= 0;
  v.ng = front ? sp.ng : -sp.ng;
  Vec3 ns = front ? sp.ns : -sp.ns;
  if (dot(ns, view) <= 0) ns = v.ng;  // a shading normal turned away from the viewer by interpolation
  v.n = to_f(ns);
  sh::hr_frame(v.n, v.t, v.b);
  v.wo = sh::hr_to_local(to_f(view), v.t, v.b, v.n);
  v.bsdf = bsdf_of(sp, v.wo.z, front, scene.settings().principled);
  v.above = sp.position + v.ng * scene.epsilon();
  v.below = sp.position - v.ng * scene.epsilon();
  return v;
}

}  // namespace

Vec3 path_radiance(const RenderContext& scene, const Ray& eye, sh::HrSampler& sampler, RayCounts& counts,
                   SurfacePoint* first, Hit* first_hit, bool* hit_found) {
  const EnvironmentMap* env = scene.settings().environment;
  const bool env_lights = env && !env->black();
  Vec3 radiance, throughput{1, 1, 1};
  Ray ray = eye;
  bool specular = true;  // the last bounce was a delta lobe (or there was none): no MIS on what it meets
  double last_pdf = 0;
  if (hit_found) *hit_found = false;
  for (int depth = 1;; ++depth) {
    Hit hit;
    const bool found = scene.accel().intersect(ray, hit, depth == 1 ? RayCoherence::coherent : RayCoherence::incoherent);
    if (depth > 1) radiance += mul(throughput, area_lights_met(scene, ray, found ? hit.t : INFINITY, specular, last_pdf));
    if (!found) {
      double w = 1;
      if (!specular && env_lights) w = sh::hr_power_heuristic(static_cast<float>(last_pdf), static_cast<float>(env->pdf(ray.dir)));
      radiance += mul(throughput, path_escape(scene, ray.dir)) * w;
      break;
    }
    const SurfacePoint sp = scene.surface(ray, hit);
    if (depth == 1) {
      if (first) *first = sp;
      if (first_hit) *first_hit = hit;
      if (hit_found) *hit_found = true;
    }
    const Material& m = *sp.material;
    if (m.emitter) {  // a Tachyon light's sphere: its colour, unshaded
      radiance += mul(throughput, sp.colour);
      break;
    }
    if (m.emission.x > 0 || m.emission.y > 0 || m.emission.z > 0)
      radiance += mul(throughput, emission_met(scene, sp, hit, ray, specular, last_pdf));
    // max_depth counts the eye ray as 1 (pbrt's maxDepth; Cycles' bounces
    // plus 1): a vertex past it only shows its emission, above, which
    // completes the MIS of the vertex before.
    if (depth > scene.max_depth()) break;

    const Vertex v = vertex_at(scene, ray, sp);
    if (!black(to_d(v.bsdf.diffuse)) || v.bsdf.alpha > 0) radiance += mul(throughput, direct_light(scene, v, sampler, counts));

    // The next direction, from the BSDF.
    const sh::vec2 u_lobe = sh::hr_next2(sampler);
    const sh::vec2 u_dir = sh::hr_next2(sampler);
    sh::vec3 wi, weight;
    float pdf;
    bool delta, through;
    if (!sh::hr_bsdf_sample(v.bsdf, v.wo, u_lobe.x, u_dir, wi, weight, pdf, delta, through)) break;
    const Vec3 dir = normalize(to_d(sh::hr_to_world(wi, v.t, v.b, v.n)));
    // A reflected direction below the geometric surface (the shading
    // normal's tilt) would leave from inside: the path ends there.
    if (!through && dot(dir, v.ng) <= 0) break;
    if (through && !delta && dot(dir, v.ng) >= 0) break;  // rough transmission back above it: the same, mirrored
    throughput = mul(throughput, to_d(weight));
    specular = delta;
    last_pdf = pdf;
    if (through) ++counts.refracted;
    else ++counts.reflected;
    ray = Ray{through ? v.below : v.above, dir, 0, INFINITY};
    // Russian roulette (pbrt-v4's): a path whose throughput has fallen
    // below 1 goes on with that probability, weighted up to stay unbiased.
    const double keep = std::max({throughput.x, throughput.y, throughput.z});
    if (depth >= kRouletteDepth && keep < 1) {
      if (!(u_lobe.y < keep)) break;
      throughput = throughput * (1 / keep);
    }
  }
  return radiance;
}

}  // namespace holoray
