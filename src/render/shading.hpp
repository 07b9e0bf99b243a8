// holoray/render: Whitted shading with the SPD conventions (nff-notes §5, §10):
//
//   I = Ia*Kd*C + sum over lights seen  Il*(Kd*C*max(0, N.L) + Ks*max(0, R.V)^Shine)
//       + Ks*I_reflected + T*I_transmitted
//
// Ks is both the mirror weight and the highlight weight; refraction follows
// Snell's law with total internal reflection; no shadow ray is cast when the
// normal faces away from the light; shadows are cast by any surface (how
// transmitters attenuate them is unspecified; we treat them as opaque).
#pragma once

#include "render/ray_counts.hpp"
#include "render/render_context.hpp"

namespace holoray {

// The ray-tree depth limit: kMaxRayDepth and kDepthCap (render_scene.hpp),
// a render's own in RenderSettings::max_depth (render_context.hpp). Each
// material's terms are its shading model's (render/models/, dispatched in
// shading_models.hpp).

/// Colour (linear RGB) seen along `ray` (world, unit dir) at ray-tree `depth`.
Vec3 trace(const RenderContext& scene, const Ray& ray, int depth, RayCounts& counts);

/// Colour of a known surface point hit by `ray` (world, unit dir, travelling
/// toward the surface: the viewer is at -ray.dir).
Vec3 shade(const RenderContext& scene, const Ray& ray, const SurfacePoint& sp, int depth, RayCounts& counts);

/// What reverse reprojection (temporal/reverse.hpp) keeps of a shaded eye
/// hit: the part of the shading that rays computed. 16 bytes.
struct ShadeParts {
  uint32_t lit = 0;  ///< bit l: light l was seen (lights 0..31; more: see kMaxPartLights)
  float secondary[3] = {0, 0, 0};  ///< Ks*I_reflected + T*I_transmitted, linear RGB
};
/// Lights a ShadeParts::lit mask can hold; scenes with more are not reused.
inline constexpr int kMaxPartLights = 32;

/// The terms of shade() that need no mirror or refraction ray: Ia*Kd*C plus,
/// for each light seen, its diffuse and highlight terms at `sp` seen along
/// `ray` (zero where the normal faces away from the light), in shade()'s
/// order. A light is seen when its bit is set in `lit`, except for the bits
/// set in `trace`: those lights get their shadow ray (counted in `counts`).
Vec3 shade_local(const RenderContext& scene, const Ray& ray, const SurfacePoint& sp, uint32_t lit, uint32_t trace,
                 RayCounts& counts);

/// The terms of shade() that the mirror and refraction rays bring at `sp`
/// hit by `ray` at ray-tree `depth` (Ks*I_reflected + T*I_transmitted).
Vec3 shade_secondary(const RenderContext& scene, const Ray& ray, const SurfacePoint& sp, int depth, RayCounts& counts);
/// shade_secondary() for the lanes of a packet with hit[k] set, added to
/// colours[k]: their mirror rays, then their transmitted rays, each set
/// traced as one packet when nearly parallel and else one by one, as
/// shade()'s packets trace them (to the image budget, not to the bit).
void shade_secondary(const RenderContext& scene, const RayPacket& rays, const bool hit[kPacketSize],
                     const SurfacePoint sps[kPacketSize], int depth, RayCounts& counts, Vec3 colours[kPacketSize]);

/// shade() for the lanes of a packet with hit[k] set, into colours[k] (other
/// lanes untouched). The shadow rays toward each light go as one packet
/// (rtcOccluded16). The mirror rays of the lanes, then their transmitted
/// rays, go as one packet (rtcIntersect16, Embree's coherent traversal) when
/// they are nearly parallel, and their hits are shaded as a packet one level
/// deeper; else one by one. In a scene of plain NFF materials
/// (RenderScene::only_plain_nff) their triangle hits are Embree's float ones,
/// unrefined. When every hit lane's material is NFF's and the scene has
/// no shadow cache, each point light of unit falloff is shaded as a float
/// batch (light_batch.hpp); when every one is glTF's, every light but
/// Tachyon's linear spot (gltf_batch.hpp): a lane's colour is then shade()'s
/// to the image budget (60 dB), not to the bit; so are the secondary rays' answers.
/// With `parts`, parts[k] also gets what lane k's rays found (ShadeParts).
void shade(const RenderContext& scene, const RayPacket& rays, const bool hit[kPacketSize],
           const SurfacePoint sps[kPacketSize], int depth, RayCounts& counts, Vec3 colours[kPacketSize],
           ShadeParts parts[kPacketSize] = nullptr);

}  // namespace holoray
