// holoray/render: glTF 2.0's metallic-roughness shading model
// (gltf_brdf.hpp): per seen light the BRDF times the part of the surface
// that is there (BLEND: alpha); no ambient term; a mirror ray below
// kMirrorRoughness weighted by the Fresnel mix, and BLEND's and
// KHR_materials_transmission's light straight through.
#pragma once

#include "render/gltf_brdf.hpp"
#include "render/shading_terms.hpp"

namespace holoray::shading {

struct GltfModel {
  static Vec3 ambient(const RenderContext&, const HitFrame&) { return {}; }

  // The BRDF's inputs at a hit. Metallic and roughness come from the
  // SurfacePoint (textures applied), not the HitFrame: NFF's hot loops keep
  // their frames as small as before glTF.
  static GltfSurface surface(const HitFrame& f, const SurfacePoint& sp) {
    return GltfSurface{f.colour, sp.metallic, sp.roughness, dielectric_f0(f.m->ior), f.m->transmission};
  }


  /// A seen light's term; out of line, so that NFF's hot path stays as small as it was.
  [[gnu::noinline]] static Vec3 light(const HitFrame& f, const SurfacePoint& sp, const PointLight& light,
                                      const Vec3& to_light, double falloff);

  /// The mirror and transmitted rays at `sp`; out of line as light().
  [[gnu::noinline]] static SecondaryRays secondary_rays(const RenderContext& scene, const Ray& ray,
                                                        const SurfacePoint& sp, const HitFrame& f);

  // What secondary_rays() gives at `sp`, asked without building its
  // record: a mirror ray below kMirrorRoughness, a transmitted one where any
  // light goes through. A rough opaque glTF lane (most of a glTF scene) then
  // costs the packet's secondary passes nothing (lit_spheres.gltf: 4 % of its
  // cycles went to zeroing and copying empty records).
  static bool mirrors(const SurfacePoint& sp) { return sp.roughness < kMirrorRoughness; }
  static bool transmits(const Material& m) { return m.transmittance > 0 || m.transmission > 0; }
};

}  // namespace holoray::shading
