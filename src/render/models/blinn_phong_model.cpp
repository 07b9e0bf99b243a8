#include "render/models/blinn_phong_model.hpp"

namespace holoray::shading {

Vec3 BlinnPhongModel::light(const HitFrame& f, const SurfacePoint& sp, const PointLight& light, const Vec3& to_light,
                             double falloff) {
  Vec3 term = NffModel::term(f, to_light);
  const double n_dot_h = dot(f.ns, normalize(to_light + f.view));
  if (n_dot_h > 0) term += f.m->specular * (sp.highlight * std::pow(n_dot_h, f.m->shine));
  return mul(light.intensity * falloff, term);
}


}  // namespace holoray::shading
