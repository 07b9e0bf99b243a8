#include "render/environment.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "shading/environment.h"
#include "render/shading_vec.hpp"

namespace holoray {

namespace sh = shading;

EnvironmentMap::EnvironmentMap(const Vec3& radiance)
    : constant_(radiance), black_(!(radiance.x > 0 || radiance.y > 0 || radiance.z > 0)) {}

EnvironmentMap::EnvironmentMap(const ImageBuffer& image, double strength, double rotation_rad, EnvironmentUp up)
    : width_(image.width), height_(image.height), cos_rot_(static_cast<float>(std::cos(rotation_rad))),
      sin_rot_(static_cast<float>(std::sin(rotation_rad))), up_(up) {
  if (image.channels < 3)
    throw std::invalid_argument(fmt::format("an environment image needs RGB, got {} channel(s)", image.channels));
  if (image.width < 2 || image.height < 1)
    throw std::invalid_argument(fmt::format("an environment image needs at least 2x1 texels, got {}x{}", image.width, image.height));
  if (!(strength >= 0) || !std::isfinite(strength))
    throw std::invalid_argument(fmt::format("environment strength: expected a finite value >= 0, got {}", strength));
  const size_t n = static_cast<size_t>(width_) * height_;
  texels_.resize(n * 3);
  std::vector<double> weight(n);
  double total = 0;
  for (int y = 0; y < height_; ++y) {
    // A row's solid angle per texel is proportional to the cosine of its latitude.
    const double lat = (0.5 - (y + 0.5) / height_) * M_PI;
    const double cos_lat = std::cos(lat);
    for (int x = 0; x < width_; ++x) {
      const float* p = image.at(x, y);
      const size_t t = static_cast<size_t>(y) * width_ + x;
      double lum = 0;
      for (int c = 0; c < 3; ++c) {
        const float v = std::isfinite(p[c]) && p[c] > 0 ? static_cast<float>(p[c] * strength) : 0.0f;
        texels_[t * 3 + c] = v;
      }
      lum = sh::hr_luminance(sh::vec3(texels_[t * 3], texels_[t * 3 + 1], texels_[t * 3 + 2]));
      weight[t] = lum * cos_lat;
      total += weight[t];
    }
  }
  black_ = !(total > 0);
  if (black_) return;
  // Vose's alias method: cells under the mean take their deficit from one over it.
  keep_.assign(n, 1.0f);
  alias_.resize(n);
  share_.resize(n);
  std::vector<double> scaled(n);
  std::vector<uint32_t> small, large;
  for (size_t t = 0; t < n; ++t) {
    share_[t] = static_cast<float>(weight[t] / total);
    scaled[t] = weight[t] / total * static_cast<double>(n);
    alias_[t] = static_cast<uint32_t>(t);
    (scaled[t] < 1 ? small : large).push_back(static_cast<uint32_t>(t));
  }
  while (!small.empty() && !large.empty()) {
    const uint32_t s = small.back(), l = large.back();
    small.pop_back();
    keep_[s] = static_cast<float>(scaled[s]);
    alias_[s] = l;
    scaled[l] -= 1 - scaled[s];
    if (scaled[l] < 1) {
      large.pop_back();
      small.push_back(l);
    }
  }
  // What remains holds 1 to rounding: kept whole.
}

Vec3 EnvironmentMap::texel(int x, int y) const {
  const float* p = &texels_[(static_cast<size_t>(y) * width_ + x) * 3];
  return {p[0], p[1], p[2]};
}

sh::vec2 EnvironmentMap::uv_of(const Vec3& dir) const {
  return sh::hr_equirect_uv(sh::hr_env_from_world(to_f(dir), cos_rot_, sin_rot_, up_ == EnvironmentUp::y));
}

Vec3 EnvironmentMap::radiance(const Vec3& dir) const {
  if (texels_.empty()) return constant_;
  // Bilinear, as Blender's Environment Texture (Linear). Sampling draws
  // whole texels; its density (pdf) need only follow the light roughly to
  // stay unbiased.
  sh::ivec4 q;
  sh::vec2 t;
  sh::hr_env_bilinear(uv_of(dir), width_, height_, q, t);
  return (texel(q.x, q.y) * (1 - t.x) + texel(q.z, q.y) * t.x) * (1 - t.y) + (texel(q.x, q.w) * (1 - t.x) + texel(q.z, q.w) * t.x) * t.y;
}

Vec3 EnvironmentMap::sample(double u_cell, double u0, double u1, Vec3& dir, double& pdf) const {
  const sh::vec2 u(static_cast<float>(u0), static_cast<float>(u1));
  if (texels_.empty() || black_) {
    const sh::vec3 d = sh::hr_uniform_sphere(u);
    dir = {d.x, d.y, d.z};
    pdf = 1 / (4 * M_PI);
    return constant_;
  }
  float rest;
  uint32_t cell = sh::hr_alias_cell(static_cast<float>(u_cell), static_cast<uint32_t>(keep_.size()), rest);
  if (rest >= keep_[cell]) cell = alias_[cell];
  const int x = static_cast<int>(cell % static_cast<uint32_t>(width_)), y = static_cast<int>(cell / static_cast<uint32_t>(width_));
  const sh::vec3 e = sh::hr_env_to_world(sh::hr_env_texel_direction(x, y, width_, height_, u), cos_rot_, sin_rot_,
                                         up_ == EnvironmentUp::y);
  dir = normalize(Vec3{e.x, e.y, e.z});
  pdf = share_[cell] / sh::hr_env_texel_solid_angle(y, width_, height_);
  return radiance(dir);
}

double EnvironmentMap::pdf(const Vec3& dir) const {
  if (texels_.empty() || black_) return 1 / (4 * M_PI);
  const sh::ivec2 t = sh::hr_env_texel_of(uv_of(dir), width_, height_);
  return share_[static_cast<size_t>(t.y) * width_ + t.x] / sh::hr_env_texel_solid_angle(t.y, width_, height_);
}

}  // namespace holoray
