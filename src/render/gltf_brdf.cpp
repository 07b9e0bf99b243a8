#include "render/gltf_brdf.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace holoray {

namespace {

double schlick_weight(double cos_theta) {
  const double m = 1 - std::clamp(cos_theta, 0.0, 1.0);
  const double m2 = m * m;
  return m2 * m2 * m;
}

// Smith's G1 term for GGX as Appendix B.3.2 writes it, times 1 / (2 |N.X|):
// the two factors multiply to V = G / (4 |N.L| |N.V|).
double smith_half(double n_dot_x, double a2) {
  return 1 / (n_dot_x + std::sqrt(a2 + (1 - a2) * n_dot_x * n_dot_x));
}

}  // namespace

double dielectric_f0(double ior) {
  if (!(ior > 0)) return 0.04;
  const double r = (ior - 1) / (ior + 1);
  return r * r;
}

Vec3 gltf_direct(const GltfSurface& s, const Vec3& n, const Vec3& view, const Vec3& to_light) {
  const double n_dot_l = dot(n, to_light);
  if (!(n_dot_l > 0)) return {};
  // An interpolated normal may face away from the viewer: the specification's
  // implementation takes |N.V| there.
  const double n_dot_v = std::fmax(std::fabs(dot(n, view)), 1e-6);
  const Vec3 h = normalize(to_light + view);
  const double n_dot_h = std::fmax(dot(n, h), 0.0);
  const double v_dot_h = std::fabs(dot(view, h));
  const double a = s.roughness * s.roughness;
  const double a2 = std::fmax(a * a, 1e-12);  // a perfect mirror's highlight: a point light's is a point
  const double d_denom = n_dot_h * n_dot_h * (a2 - 1) + 1;
  const double d = a2 / (std::numbers::pi * d_denom * d_denom);
  const double vis = smith_half(n_dot_l, a2) * smith_half(n_dot_v, a2);
  const double specular = d * vis;
  const double w = schlick_weight(v_dot_h);
  const double f_d = s.f0 + (1 - s.f0) * w;
  const Vec3 f_m = s.base + (Vec3{1, 1, 1} - s.base) * w;
  const double m = std::clamp(s.metallic, 0.0, 1.0);
  // pi * f: the Lambertian 1/pi cancels.
  const Vec3 dielectric = s.base * ((1 - f_d) * (1 - std::clamp(s.transmission, 0.0, 1.0))) +
                          Vec3{1, 1, 1} * (f_d * specular * std::numbers::pi);
  const Vec3 metal = f_m * (specular * std::numbers::pi);
  return (dielectric * (1 - m) + metal * m) * n_dot_l;
}

Vec3 gltf_mirror_weight(const GltfSurface& s, double n_dot_v) {
  const double w = schlick_weight(std::fabs(n_dot_v));
  const double f_d = s.f0 + (1 - s.f0) * w;
  const Vec3 f_m = s.base + (Vec3{1, 1, 1} - s.base) * w;
  const double m = std::clamp(s.metallic, 0.0, 1.0);
  return Vec3{f_d, f_d, f_d} * (1 - m) + f_m * m;
}

Vec3 gltf_transmit_weight(const GltfSurface& s, double n_dot_v) {
  const double f_d = s.f0 + (1 - s.f0) * schlick_weight(std::fabs(n_dot_v));
  return s.base * ((1 - std::clamp(s.metallic, 0.0, 1.0)) * std::clamp(s.transmission, 0.0, 1.0) * (1 - f_d));
}

}  // namespace holoray
