// holoray/render: NFF's direct light for the 16 lanes of a shading packet as
// one batch (issue 43): one float array per coordinate, four lanes per SSE
// instruction, the shadow rays written straight into Embree's 16-wide layout,
// pow from glibc's vector maths (libmvec).
//
// The formula is shading.hpp's (nff-notes §5, §10.10) for a point light of
// unit falloff: Il*(Kd*C*max(0, N.L) + Ks*max(0, R.V)^Shine), no shadow ray
// where N.L <= 0 or the light lies on the surface. In float, where the
// single-ray path (shade(Ray)) is in double: the two agree to the image
// budget (at least 60 dB, tests/test_render.cpp), not bit for bit. Each
// lane's arithmetic is its own (no sum across lanes), and packets are cut
// from the image's layout, so the image is the same for any tile order,
// thread count or rank count. (libmvec, like libm, picks its kernel by the
// processor: machines of different kinds may differ in a last bit.)
#pragma once

#include "accel/accel_scene.hpp"
#include "math/vec.hpp"

namespace holoray {

/// The lanes of a shading packet as the light stage needs them, world frame.
/// Lanes with hit[k] false hold zeros and cast nothing.
struct NffLanes {
  alignas(16) float px[kPacketSize], py[kPacketSize], pz[kPacketSize];  ///< hit point
  alignas(16) float nx[kPacketSize], ny[kPacketSize], nz[kPacketSize];  ///< unit shading normal, viewer's side
  alignas(16) float ox[kPacketSize], oy[kPacketSize], oz[kPacketSize];  ///< shadow rays' origin (lifted off the surface)
  alignas(16) float n_dot_v[kPacketSize];  ///< N.V, V toward the viewer
  alignas(16) float vx[kPacketSize], vy[kPacketSize], vz[kPacketSize];  ///< unit, toward the viewer
  alignas(16) float dr[kPacketSize], dg[kPacketSize], db[kPacketSize];  ///< Kd*C, linear RGB
  alignas(16) float ks[kPacketSize], shine[kPacketSize];                ///< highlight weight and exponent
  alignas(16) int hit[kPacketSize];  ///< -1: the lane is shaded, 0: not

  /// Lane k from a hit (double, as the surface point holds it).
  void set(int k, const Vec3& p, const Vec3& n, const Vec3& above, const Vec3& view, const Vec3& kd_colour, double ks_,
           double shine_);
  /// Lane k shades nothing.
  void clear(int k);
};

/// What one light's stage leaves for the lanes: the unit direction to the
/// light and N.L, where the shadow ray was cast.
struct NffLightRays {
  alignas(16) float ux[kPacketSize], uy[kPacketSize], uz[kPacketSize];
  alignas(16) float n_dot_l[kPacketSize];
};

/// Builds the shadow rays of the lanes toward a point light at `light`
/// (world) into `shadows` (Embree's RTCRay16 layout; lanes without a ray
/// invalid), each a segment ending `eps` short of the light. Returns how
/// many were cast.
int nff_shadow_rays(const NffLanes& lanes, const Vec3& light, double eps, ShadowPacket& shadows, NffLightRays& out);

/// The light's term, Il*(Kd*C*N.L + Ks*(R.V)^Shine) (the highlight where
/// Ks > 0 and R.V > 0), for the lanes whose shadow ray was cast and not
/// blocked (`seen[k]`), added to `colours[k]`; the other lanes untouched.
void add_nff_light(const NffLanes& lanes, const NffLightRays& rays, const bool seen[kPacketSize], const Vec3& intensity,
                   Vec3 colours[kPacketSize]);

}  // namespace holoray
