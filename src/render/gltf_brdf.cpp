#include "render/gltf_brdf.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "shading/gltf_whitted.h"
#include "render/shading_vec.hpp"

namespace holoray {

namespace sh = shading;

double dielectric_f0(double ior) {
  if (!(ior > 0)) return 0.04;
  const double r = (ior - 1) / (ior + 1);
  return r * r;
}

// The terms are the shared text (shading/gltf_whitted.h) the GPU kernel compiles too.
Vec3 gltf_direct(const GltfSurface& s, const Vec3& n, const Vec3& view, const Vec3& to_light) {
  return to_d(sh::hr_gltf_direct(to_f(s.base), static_cast<float>(s.metallic), static_cast<float>(s.roughness),
                                 static_cast<float>(s.f0), static_cast<float>(s.transmission), to_f(n), to_f(view), to_f(to_light)));
}

Vec3 gltf_mirror_weight(const GltfSurface& s, double n_dot_v) {
  return to_d(sh::hr_gltf_mirror_weight(to_f(s.base), static_cast<float>(s.metallic), static_cast<float>(s.f0),
                                        static_cast<float>(n_dot_v)));
}

Vec3 gltf_transmit_weight(const GltfSurface& s, double n_dot_v) {
  return to_d(sh::hr_gltf_transmit_weight(to_f(s.base), static_cast<float>(s.metallic), static_cast<float>(s.f0),
                                          static_cast<float>(s.transmission), static_cast<float>(n_dot_v)));
}

}  // namespace holoray
