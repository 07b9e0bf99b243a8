// holoray/render, internal to the shading: the one place that dispatches
// on a material's shading model (Material::model) to its type in
// render/models/: NffModel, BlinnPhongModel, GltfModel, TachyonModel (the
// last shades whole hits: shade() asks for it first). Each model gives its
// ambient term, a seen light's term and its secondary rays.
#pragma once

#include "render/models/blinn_phong_model.hpp"
#include "render/models/gltf_model.hpp"
#include "render/models/nff_model.hpp"
#include "render/models/tachyon_model.hpp"

namespace holoray::shading {

// The light's contribution along the unblocked shadow ray's unit direction `to_light`. NFF's
// materials: diffuse and highlight, computed only for lights that are
// seen, so a shadowed light costs no pow(). glTF's: the metallic-roughness
// BRDF (gltf_brdf.hpp) times the part of the surface that is there
// (BLEND: alpha). blinn_phong's: NFF's with MTL's highlight.
inline Vec3 light_contribution(const HitFrame& f, const SurfacePoint& sp, const PointLight& light, const Vec3& to_light,
                        double falloff) {
  if (f.m->model != ShadingModel::nff) [[unlikely]] {
    if (f.m->model == ShadingModel::gltf) return GltfModel::light(f, sp, light, to_light, falloff);
    return BlinnPhongModel::light(f, sp, light, to_light, falloff);
  }
  return NffModel::light(f, light, to_light, falloff);
}


// The ambient term: Ia Kd C (NFF, Blinn-Phong); none for glTF.
inline Vec3 ambient_term(const RenderContext& scene, const HitFrame& f) {
  if (f.m->model == ShadingModel::gltf) return GltfModel::ambient(scene, f);
  return NffModel::ambient(scene, f);
}

// Whether secondary_rays() can give a ray for material `m` at all (a glTF
// material's depends on its texel's roughness: assumed yes).
inline bool may_cast_secondary(const Material& m) {
  return m.model == ShadingModel::gltf || m.ks > 0 || m.transmittance > 0;
}


inline SecondaryRays secondary_rays(const RenderContext& scene, const Ray& ray, const SurfacePoint& sp, const HitFrame& f) {
  if (f.m->model == ShadingModel::gltf) [[unlikely]]
    return GltfModel::secondary_rays(scene, ray, sp, f);
  SecondaryRays s;
  s.mirror = NffModel::mirror(ray, f, s.mirror_ray, s.mirror_weight);
  s.transmit = NffModel::transmit(scene, ray, sp, f, s.transmit_ray, s.transmit_weight, s.transmit_reflects);
  return s;
}


// For a packet's passes, one ray kind at a time (copying whole
// SecondaryRays records stalled on store forwarding: teapot_s6 spent 4 % of
// its cycles there). Whether a lane may cast any secondary ray, asked
// without building one: a rough opaque glTF lane (most of a glTF scene)
// then costs the passes nothing (lit_spheres.gltf: 4 % of its cycles).
inline bool casts_secondary(const SurfacePoint& sp, const HitFrame& f) {
  return f.m->model == ShadingModel::gltf ? GltfModel::mirrors(sp) || GltfModel::transmits(*f.m) : may_cast_secondary(*f.m);
}

// The mirror ray of a hit, written into `out` and `weight`; false when it casts none.
[[gnu::always_inline]] inline bool mirror_ray(const RenderContext& scene, const Ray& ray, const SurfacePoint& sp,
                                              const HitFrame& f, Ray& out, Vec3& weight) {
  if (f.m->model == ShadingModel::gltf) [[unlikely]] {
    if (!GltfModel::mirrors(sp)) return false;
    const SecondaryRays g = GltfModel::secondary_rays(scene, ray, sp, f);
    if (g.mirror) out = g.mirror_ray, weight = g.mirror_weight;
    return g.mirror;
  }
  return NffModel::mirror(ray, f, out, weight);
}

// The transmitted ray of a hit (`reflects`: totally reflected instead);
// false when it casts none.
[[gnu::always_inline]] inline bool transmitted_ray(const RenderContext& scene, const Ray& ray, const SurfacePoint& sp,
                                                   const HitFrame& f, Ray& out, Vec3& weight, bool& reflects) {
  if (f.m->model == ShadingModel::gltf) [[unlikely]] {
    if (!GltfModel::transmits(*f.m)) return false;
    const SecondaryRays g = GltfModel::secondary_rays(scene, ray, sp, f);
    if (g.transmit) out = g.transmit_ray, weight = g.transmit_weight;
    reflects = g.transmit_reflects;
    return g.transmit;
  }
  return NffModel::transmit(scene, ray, sp, f, out, weight, reflects);
}

}  // namespace holoray::shading
