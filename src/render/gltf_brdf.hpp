// holoray/render: glTF 2.0's metallic-roughness BRDF (the specification's
// Appendix B) for direct light, and the weight of the one mirror ray a
// smooth glTF surface gets (docs/lights.md, "glTF materials").
//
//   f = (1 - metallic) * [(1 - F_d) (1 - T) c / pi + F_d D V] + metallic * F_m D V
//   F_d = F0 + (1 - F0) (1 - |V.H|)^5,  F0 = ((ior - 1) / (ior + 1))^2 (0.04 at ior 1.5)
//   F_m = c + (1 - c) (1 - |V.H|)^5
//   D = a^2 / (pi ((N.H)^2 (a^2 - 1) + 1)^2),  a = roughness^2 (GGX)
//   V = G / (4 |N.L| |N.V|), Smith's height-uncorrelated masking-shadowing
//       for GGX (Appendix B.3.2)
//
// c is the base colour (linear RGB, texture included); T the
// KHR_materials_transmission factor, the share of the dielectric's diffuse
// lobe that is transmitted instead (gltf_transmit_weight). Every vector is
// in world space and unit length.
#pragma once

#include "math/vec.hpp"

namespace holoray {

/// The material values the BRDF reads (scene_desc.hpp, Material with model
/// gltf): base colour (linear RGB), metallic and roughness in [0, 1], and
/// the dielectric's normal-incidence reflectance F0.
struct GltfSurface {
  Vec3 base;
  double metallic = 0, roughness = 1, f0 = 0.04;
  double transmission = 0;
};

/// F0 of a dielectric of index `ior` against air; 0.04 for 1.5.
double dielectric_f0(double ior);

/// pi * f(l, v) * max(0, N.L): the radiance that light of unit "white
/// Lambertian" radiance (docs/lights.md) arriving along `to_light` sends
/// toward `view`, per unit of that radiance. `n` is the shading normal on
/// the viewer's side. Zero when the light is behind the surface.
Vec3 gltf_direct(const GltfSurface& s, const Vec3& n, const Vec3& view, const Vec3& to_light);

/// Below this roughness a glTF surface reflects the scene through one mirror
/// ray (its GGX lobe is then under ~1 degree wide: one ray is what a
/// one-sample pixel would see); rougher surfaces reflect only the lights,
/// through gltf_direct.
inline constexpr double kMirrorRoughness = 0.1;

/// The mirror ray's weight at a smooth surface: the lobe's integral in the
/// limit of zero roughness, the Fresnel mix at N.V (dielectric F0 for
/// 1 - metallic, the base colour for metallic).
Vec3 gltf_mirror_weight(const GltfSurface& s, double n_dot_v);

/// The weight of the ray transmitted through a KHR_materials_transmission
/// surface: (1 - metallic) T c (1 - F) at N.V. No KHR_materials_volume is
/// read, so the surface is thin-walled: the ray goes on unbent, and for any
/// roughness (a rough surface's blur is not modelled: one ray).
Vec3 gltf_transmit_weight(const GltfSurface& s, double n_dot_v);

}  // namespace holoray
