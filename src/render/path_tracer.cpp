#include "render/path_tracer.hpp"

#include <algorithm>
#include <cmath>

#include "render/emitters.hpp"
#include "render/environment.hpp"
#include "render/gltf_brdf.hpp"
#include "shading/bsdf.h"
#include "shading/lights.h"
#include "shading/warp.h"

namespace holoray {

namespace sh = shading;

namespace {

sh::vec3 to_f(const Vec3& v) { return {static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z)}; }
Vec3 to_d(const sh::vec3& v) { return {v.x, v.y, v.z}; }

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

sh::HrLightFalloff falloff_of(const PointLight& l) {
  sh::HrLightFalloff f;
  f.kind = static_cast<int>(l.kind);
  f.direction = to_f(l.direction);
  f.kc = static_cast<float>(l.kc), f.kl = static_cast<float>(l.kl), f.kq = static_cast<float>(l.kq);
  f.range = static_cast<float>(l.range);
  f.fall_start = static_cast<float>(l.fall_start), f.fall_end = static_cast<float>(l.fall_end);
  f.cos_fall_start = static_cast<float>(l.cos_fall_start), f.cos_fall_end = static_cast<float>(l.cos_fall_end);
  f.smooth_cone = l.smooth_cone;
  f.unit = l.unit_falloff;
  return f;
}

bool black(const Vec3& v) { return !(v.x > 0 || v.y > 0 || v.z > 0); }

}  // namespace

Vec3 path_escape(const RenderContext& scene, const Vec3& dir) {
  const EnvironmentMap* env = scene.settings().environment;
  return env ? env->radiance(dir) : scene.background();
}

Vec3 path_radiance(const RenderContext& scene, const Ray& eye, sh::HrSampler& sampler, RayCounts& counts,
                   SurfacePoint* first, Hit* first_hit, bool* hit_found) {
  const EnvironmentMap* env = scene.settings().environment;
  const bool env_lights = env && !env->black();
  const EmissiveTriangles* emitters = scene.settings().emitters;
  if (emitters && emitters->empty()) emitters = nullptr;
  const double eps = scene.epsilon();
  const int max_depth = scene.max_depth();
  Vec3 radiance, throughput{1, 1, 1};
  Ray ray = eye;
  bool specular = true;  // the last bounce was a delta lobe (or there was none): no MIS on what it meets
  double last_pdf = 0;
  if (hit_found) *hit_found = false;
  const std::vector<AreaLight>& area_lights = scene.scene().area_lights();
  for (int depth = 1;; ++depth) {
    Hit hit;
    const bool found = scene.accel().intersect(ray, hit, depth == 1 ? RayCoherence::coherent : RayCoherence::incoherent);
    // Area lights the ray meets before the scene, from their lit side:
    // unseen by the eye (as Blender's, by default), weighted against their
    // own sampling below.
    if (depth > 1)
      for (const AreaLight& a : area_lights) {
        const float t_light = sh::hr_area_light_hit(to_f(ray.org), to_f(ray.dir), found ? float(hit.t) : 3.0e38f, to_f(a.centre),
                                                    to_f(a.axis_u), to_f(a.axis_v), to_f(a.normal), a.ellipse);
        const double cos_l = -dot(ray.dir, a.normal);
        if (!(t_light > 0) || !(cos_l > 0)) continue;
        double w = 1;
        if (!specular) w = sh::hr_power_heuristic(float(last_pdf), sh::hr_area_to_solid_angle(float(1 / a.area), t_light * t_light, float(cos_l)));
        radiance += mul(throughput, a.radiance) * w;
      }
    if (!found) {
      const Vec3 le = path_escape(scene, ray.dir);
      double w = 1;
      if (!specular && env_lights) w = sh::hr_power_heuristic(static_cast<float>(last_pdf), static_cast<float>(env->pdf(ray.dir)));
      radiance += mul(throughput, le) * w;
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
    // Emission met by a BSDF ray: weighted against the emitters' own
    // sampling (next-event estimation below) where that could have drawn it.
    if (m.emission.x > 0 || m.emission.y > 0 || m.emission.z > 0) {
      double w = 1;
      if (!specular && emitters && hit.kind == PrimKind::triangle) {
        const double cos_l = std::fabs(dot(sp.ng, ray.dir));
        const double pdf_light = sh::hr_area_to_solid_angle(static_cast<float>(emitters->pdf_area(hit.group, hit.prim)),
                                                            static_cast<float>(hit.t * hit.t), static_cast<float>(cos_l));
        w = sh::hr_power_heuristic(static_cast<float>(last_pdf), static_cast<float>(pdf_light));
      }
      radiance += mul(throughput, scene.emission(sp, hit.t)) * w;
    }
    // max_depth counts the eye ray as 1 (pbrt's maxDepth; Cycles' bounces
    // plus 1): a vertex past it only shows its emission, above, which
    // completes the MIS of the vertex before.
    if (depth > max_depth) break;

    // The local frame: both normals turned to the side the ray came from.
    const Vec3 view = -ray.dir;
    const bool front = dot(sp.ng, view) >= 0;
    const Vec3 ng = front ? sp.ng : -sp.ng;
    Vec3 ns = front ? sp.ns : -sp.ns;
    if (dot(ns, view) <= 0) ns = ng;  // a shading normal turned away from the viewer by interpolation
    sh::vec3 t, b;
    const sh::vec3 n = to_f(ns);
    sh::hr_frame(n, t, b);
    const sh::vec3 wo = sh::hr_to_local(to_f(view), t, b, n);
    const sh::HrBsdf bsdf = bsdf_of(sp, wo.z, front, scene.settings().principled);
    const Vec3 above = sp.position + ng * eps, below = sp.position - ng * eps;
    const bool smooth_part = !black(to_d(bsdf.diffuse)) || bsdf.alpha > 0;

    // Next-event estimation: every delta light, one environment sample,
    // one point on the emissive surfaces.
    const sh::vec2 u_env_cell = sh::hr_next2(sampler);
    const sh::vec2 u_env = sh::hr_next2(sampler);
    const sh::vec2 u_emit_pick = sh::hr_next2(sampler);
    const sh::vec2 u_emit = sh::hr_next2(sampler);
    if (smooth_part) {
      for (const PointLight& light : scene.lights()) {
        if (light.headlight && scene.settings().skip_headlights) continue;
        Vec3 to_light;
        double dist = INFINITY, cos_l = 1;
        // One sample of a soft light (a sun's disk, a point light's
        // radius) per light per vertex: each pair of its own.
        const sh::vec2 u_soft = sh::hr_next2(sampler);
        if (light.kind == LightKind::directional) {
          to_light = -light.direction;
          if (light.cos_half_angle < 1) {
            // Uniform over the sun's cone: radiance S / cone, so the
            // estimate is f S, as a delta light's (Cycles' disk: within 0.01 %).
            sh::vec3 ct, cb;
            const sh::vec3 axis = to_f(to_light);
            sh::hr_frame(axis, ct, cb);
            to_light = normalize(to_d(sh::hr_to_world(sh::hr_uniform_cone(u_soft, float(light.cos_half_angle)), ct, cb, axis)));
          }
        } else {
          Vec3 from = light.position;
          if (light.radius > 0) {
            // A disk facing the point (Cycles' sphere light): drawn
            // uniformly, its radiance I / (pi r^2) makes the estimate f I cos_l / d^2.
            const Vec3 facing = normalize(sp.position - light.position);
            from = to_d(sh::hr_disk_light_point(to_f(light.position), to_f(facing), float(light.radius), u_soft));
            to_light = from - sp.position;
            dist = length(to_light);
            if (!(dist > eps)) continue;
            cos_l = std::fabs(dot(facing, to_light / dist));
          }
          to_light = from - sp.position;
          dist = length(to_light);
          if (!(dist > eps)) continue;
          to_light = to_light / dist;
        }
        if (dot(to_light, ng) <= 0) continue;
        const sh::vec3 wi = sh::hr_to_local(to_f(to_light), t, b, n);
        const sh::vec3 f = sh::hr_bsdf_eval(bsdf, wo, wi);
        if (!(f.x > 0 || f.y > 0 || f.z > 0)) continue;
        const float falloff = sh::hr_light_falloff(falloff_of(light), to_f(to_light), static_cast<float>(dist));
        if (!(falloff > 0)) continue;
        ++counts.shadow;
        if (scene.accel().occluded(Ray{above, to_light, 0, dist - eps})) continue;
        radiance += mul(throughput, mul(to_d(f), light.intensity)) * (M_PI * falloff * cos_l);
      }
      // Every area light, one point each, uniform over its area.
      for (const AreaLight& a : area_lights) {
        const sh::vec2 u_area = sh::hr_next2(sampler);
        const Vec3 p = to_d(sh::hr_area_light_point(to_f(a.centre), to_f(a.axis_u), to_f(a.axis_v), a.ellipse, u_area));
        Vec3 dir = p - sp.position;
        const double dist2 = dot(dir, dir), dist = std::sqrt(dist2);
        if (!(dist > eps)) continue;
        dir = dir / dist;
        const double cos_l = -dot(dir, a.normal);  // one-sided: it lights the side its normal faces
        if (!(cos_l > 0) || dot(dir, ng) <= 0) continue;
        const sh::vec3 wi = sh::hr_to_local(to_f(dir), t, b, n);
        const sh::vec3 f = sh::hr_bsdf_eval(bsdf, wo, wi);
        if (!(f.x > 0 || f.y > 0 || f.z > 0)) continue;
        ++counts.shadow;
        if (scene.accel().occluded(Ray{above, dir, 0, dist - eps})) continue;
        const double pdf = dist2 / (cos_l * a.area);
        const float w = sh::hr_power_heuristic(static_cast<float>(pdf), sh::hr_bsdf_pdf(bsdf, wo, wi));
        radiance += mul(throughput, mul(to_d(f), a.radiance)) * (w / pdf);
      }
      if (env_lights) {
        Vec3 dir;
        double pdf;
        const Vec3 le = env->sample(u_env_cell.x, u_env.x, u_env.y, dir, pdf);
        if (pdf > 0 && dot(dir, ng) > 0) {
          const sh::vec3 wi = sh::hr_to_local(to_f(dir), t, b, n);
          const sh::vec3 f = sh::hr_bsdf_eval(bsdf, wo, wi);
          if (f.x > 0 || f.y > 0 || f.z > 0) {
            ++counts.shadow;
            if (!scene.accel().occluded(Ray{above, dir, 0, INFINITY})) {
              const float w = sh::hr_power_heuristic(static_cast<float>(pdf), sh::hr_bsdf_pdf(bsdf, wo, wi));
              radiance += mul(throughput, mul(to_d(f), le)) * (w / pdf);
            }
          }
        }
      }
      if (emitters) {
        const EmissiveTriangles::Sample s = emitters->sample(u_emit_pick.x, u_emit.x, u_emit.y);
        Vec3 dir = s.position - sp.position;
        const double dist2 = dot(dir, dir), dist = std::sqrt(dist2);
        dir = dir / dist;
        const double cos_l = std::fabs(dot(s.normal, dir));
        if (dist > 2 * eps && cos_l > 0 && dot(dir, ng) > 0) {
          const sh::vec3 wi = sh::hr_to_local(to_f(dir), t, b, n);
          const sh::vec3 f = sh::hr_bsdf_eval(bsdf, wo, wi);
          if (f.x > 0 || f.y > 0 || f.z > 0) {
            ++counts.shadow;
            if (!scene.accel().occluded(Ray{above, dir, 0, dist - 2 * eps})) {
              const double pdf = s.pdf_area * dist2 / cos_l;
              const float w = sh::hr_power_heuristic(static_cast<float>(pdf), sh::hr_bsdf_pdf(bsdf, wo, wi));
              radiance += mul(throughput, mul(to_d(f), scene.emission(s.surface, dist))) * (w / pdf);
            }
          }
        }
      }
    }

    // The next direction, from the BSDF.
    const sh::vec2 u_lobe = sh::hr_next2(sampler);
    const sh::vec2 u_dir = sh::hr_next2(sampler);
    sh::vec3 wi, weight;
    float pdf;
    bool delta, through;
    if (!sh::hr_bsdf_sample(bsdf, wo, u_lobe.x, u_dir, wi, weight, pdf, delta, through)) break;
    const Vec3 dir = normalize(to_d(sh::hr_to_world(wi, t, b, n)));
    // A reflected direction below the geometric surface (the shading
    // normal's tilt) would leave from inside: the path ends there.
    if (!through && dot(dir, ng) <= 0) break;
    throughput = mul(throughput, to_d(weight));
    specular = delta;
    last_pdf = pdf;
    if (through) ++counts.refracted;
    else ++counts.reflected;
    ray = Ray{through ? below : above, dir, 0, INFINITY};
    const double keep = std::max({throughput.x, throughput.y, throughput.z});
    if (depth >= kRouletteDepth && keep < 1) {
      if (!(u_lobe.y < keep)) break;
      throughput = throughput * (1 / keep);
    }
  }
  return radiance;
}

}  // namespace holoray
