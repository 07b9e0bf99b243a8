#include "render/models/gltf_model.hpp"

namespace holoray::shading {

Vec3 GltfModel::light(const HitFrame& f, const SurfacePoint& sp, const PointLight& light, const Vec3& to_light,
                       double falloff) {
  return mul(light.intensity * (falloff * (1 - f.m->transmittance)),
             gltf_direct(GltfModel::surface(f, sp), f.ns, f.view, to_light));
}


SecondaryRays GltfModel::secondary_rays(const RenderContext& scene, const Ray& ray, const SurfacePoint& sp,
                                        const HitFrame& f) {
  SecondaryRays s;
  const Material& m = *f.m;
  if (sp.roughness < kMirrorRoughness) {
    s.mirror = true;
    s.mirror_ray = mirror_ray_of(ray, f);
    s.mirror_weight = gltf_mirror_weight(GltfModel::surface(f, sp), dot(f.ns, f.view)) * (1 - m.transmittance);
  }
  // BLEND's uncovered share and KHR_materials_transmission's share of the
  // covered part both go straight through: one ray, their weights summed.
  const Vec3 transmitted = m.transmission > 0 ? gltf_transmit_weight(GltfModel::surface(f, sp), dot(f.ns, f.view)) : Vec3{};
  if (m.transmittance > 0 || m.transmission > 0) {
    s.transmit = true;
    s.transmit_ray = Ray{sp.position - f.ng * scene.epsilon(), ray.dir, 0, INFINITY};
    s.transmit_weight = Vec3{1, 1, 1} * m.transmittance + transmitted * (1 - m.transmittance);
  }
  return s;
}


}  // namespace holoray::shading
