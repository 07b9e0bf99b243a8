// holoray/render: the Blinn-Phong shading model of mesh files' Phong
// materials (MTL illumination model 2 and up): NFF's terms plus the
// highlight Ks (N.H)^Ns per light; NFF's ambient and secondary rays.
#pragma once

#include "render/models/nff_model.hpp"

namespace holoray::shading {

struct BlinnPhongModel : NffModel {
  /// A seen light's term: NffModel::term plus MTL's highlight; out of line,
  /// so that NFF's hot path stays as small as it was.
  [[gnu::noinline]] static Vec3 light(const HitFrame& f, const SurfacePoint& sp, const PointLight& light,
                                      const Vec3& to_light, double falloff);
};

}  // namespace holoray::shading
