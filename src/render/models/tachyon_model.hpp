// holoray/render: Tachyon 0.99's shading model (shade.c's full_shader;
// docs/tachyon-notes.md §3), whole: its own lights, shadow filter, fog and
// secondary rays, for the scenes Tachyon's files describe.
#pragma once

#include "render/shading_terms.hpp"

namespace holoray::shading {

struct TachyonModel {
  /// Colour of a known surface point of a Tachyon material hit by `ray`.
  static Vec3 shade(const RenderContext& scene, const Ray& ray, const SurfacePoint& sp, int depth, RayCounts& counts);
  /// shade() for the lanes of a packet with tachyon[k] set, into colours[k]:
  /// the shadow rays toward each light go as one packet (rtcOccluded16)
  /// unless the scene has transparent surfaces, whose filtering walks each
  /// ray on its own.
  static void shade(const RenderContext& scene, const RayPacket& rays, const bool tachyon[kPacketSize],
                    const SurfacePoint sps[kPacketSize], int depth, RayCounts& counts, Vec3 colours[kPacketSize]);
};

}  // namespace holoray::shading
