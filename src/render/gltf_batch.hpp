// holoray/render: glTF's direct light for the 16 lanes of a shading packet as
// one float batch (issue 43, "glTF materials alike"): the lanes gathered once
// as one array per coordinate, each light's shadow rays built straight into
// Embree's 16-wide layout, and the metallic-roughness BRDF (gltf_brdf.hpp,
// the specification's Appendix B) evaluated four lanes per SSE instruction.
//
// Lights: points and spots with their attenuation and range window, glTF's
// smooth spot cone, directional lights (shading.cpp's light_falloff and
// shadow_ray, term for term). Tachyon's spot (linear in the angle) is not
// batched: can_batch() says so and the caller shades that light in double.
// In float, where shade(Ray) is in double: the two agree to the image budget
// (at least 60 dB, tests/test_render.cpp and tests/test_gltf_batch.cpp).
// GGX's denominator is taken as |N x H|^2 + (N.H)^2 a^2, not
// (N.H)^2 (a^2 - 1) + 1, whose float cancellation near a smooth surface's
// peak would be most of its value. Each lane's arithmetic is its own, so the
// image is the same for any tile order, thread count or rank count.
#pragma once

#include "accel/accel_scene.hpp"
#include "math/vec.hpp"
#include "render/gltf_brdf.hpp"
#include "render/render_scene.hpp"

namespace holoray {

/// The lanes of a shading packet whose hits have glTF materials, world
/// frame. Lanes with hit[k] false hold zeros and cast nothing.
struct GltfLanes {
  alignas(16) float px[kPacketSize], py[kPacketSize], pz[kPacketSize];  ///< hit point
  alignas(16) float nx[kPacketSize], ny[kPacketSize], nz[kPacketSize];  ///< unit shading normal, viewer's side
  alignas(16) float ox[kPacketSize], oy[kPacketSize], oz[kPacketSize];  ///< shadow rays' origin (lifted off the surface)
  alignas(16) float vx[kPacketSize], vy[kPacketSize], vz[kPacketSize];  ///< unit, toward the viewer
  alignas(16) float n_dot_v[kPacketSize];  ///< max(|N.V|, 1e-6), as gltf_direct takes it
  alignas(16) float br[kPacketSize], bg[kPacketSize], bb[kPacketSize];  ///< base colour c, linear RGB
  alignas(16) float metallic[kPacketSize];  ///< clamped to [0, 1]
  alignas(16) float a2[kPacketSize];        ///< max(roughness^4, 1e-12): GGX's alpha squared
  alignas(16) float f0[kPacketSize];        ///< the dielectric's normal-incidence reflectance
  alignas(16) float diffuse[kPacketSize];   ///< 1 - clamp(transmission): the dielectric's diffuse share kept
  alignas(16) float cover[kPacketSize];     ///< 1 - transmittance (BLEND's alpha): the surface that is there
  alignas(16) int hit[kPacketSize];         ///< -1: the lane is shaded, 0: not

  /// Lane k from a hit (double, as the surface point holds it).
  void set(int k, const Vec3& p, const Vec3& n, const Vec3& above, const Vec3& view, const GltfSurface& s,
           double transmittance);
  /// Lane k shades nothing.
  void clear(int k);
};

/// What one light's stage leaves for the lanes: the unit direction to the
/// light, N.L and the light's falloff there, where the shadow ray was cast.
struct GltfLightRays {
  alignas(16) float ux[kPacketSize], uy[kPacketSize], uz[kPacketSize];
  alignas(16) float n_dot_l[kPacketSize], falloff[kPacketSize];
};

/// Whether gltf_shadow_rays() takes `light`: every kind but a spot whose
/// falloff is linear in the angle (Tachyon's).
bool can_batch(const PointLight& light);

/// Builds the lanes' shadow rays toward `light` (can_batch) into `shadows`
/// (Embree's RTCRay16 layout; lanes without a ray invalid), as shadow_ray()
/// does: from the lifted origin, unbounded toward a directional light, else
/// a segment ending `eps` short of the light; none where N.L <= 0, the light
/// is on the surface or its falloff leaves nothing. Returns how many were cast.
int gltf_shadow_rays(const GltfLanes& lanes, const PointLight& light, double eps, ShadowPacket& shadows,
                     GltfLightRays& out);

/// The light's term, intensity * falloff * cover * gltf_direct(), for the
/// lanes whose shadow ray was cast and not blocked (`seen[k]`), added to
/// `colours[k]`; the other lanes untouched.
void add_gltf_light(const GltfLanes& lanes, const GltfLightRays& rays, const bool seen[kPacketSize],
                    const Vec3& intensity, Vec3 colours[kPacketSize]);

}  // namespace holoray
