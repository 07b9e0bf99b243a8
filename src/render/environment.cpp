#include "render/environment.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "shading/environment.h"

namespace holoray {

namespace sh = shading;

EnvironmentMap::EnvironmentMap(const Vec3& radiance)
    : constant_(radiance), black_(!(radiance.x > 0 || radiance.y > 0 || radiance.z > 0)) {}

EnvironmentMap::EnvironmentMap(const ImageBuffer& image, double strength, double rotation_rad, EnvironmentUp up)
    : width_(image.width), height_(image.height), cos_rot_(std::cos(rotation_rad)), sin_rot_(std::sin(rotation_rad)), up_(up) {
  if (image.channels < 3)
    throw std::invalid_argument(fmt::format("an environment image needs RGB, got {} channel(s)", image.channels));
  if (image.width < 2 || image.height < 1)
    throw std::invalid_argument(fmt::format("an environment image needs at least 2x1 texels, got {}x{}", image.width, image.height));
  if (!(strength >= 0) || !std::isfinite(strength))
    throw std::invalid_argument(fmt::format("environment strength: expected a finite value >= 0, got {}", strength));
  const size_t n = static_cast<size_t>(width_) * height_;
  // Row y spans latitudes from asin(row_sin_[y + 1]) up to asin(row_sin_[y]).
  row_sin_.resize(static_cast<size_t>(height_) + 1);
  for (int y = 0; y <= height_; ++y) row_sin_[static_cast<size_t>(y)] = std::sin((0.5 - static_cast<double>(y) / height_) * M_PI);
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

Vec3 EnvironmentMap::to_env(const Vec3& w) const {
  // glTF's frame to Blender's (the exporter's +Y up = Blender's +Z), then
  // the Mapping node's rotation about z.
  const Vec3 b = up_ == EnvironmentUp::y ? Vec3{w.x, -w.z, w.y} : w;
  return {cos_rot_ * b.x - sin_rot_ * b.y, sin_rot_ * b.x + cos_rot_ * b.y, b.z};
}

Vec3 EnvironmentMap::to_world(const Vec3& e) const {
  const Vec3 b{cos_rot_ * e.x + sin_rot_ * e.y, -sin_rot_ * e.x + cos_rot_ * e.y, e.z};
  return up_ == EnvironmentUp::y ? Vec3{b.x, b.z, -b.y} : b;
}

Vec3 EnvironmentMap::texel(int x, int y) const {
  const float* p = &texels_[(static_cast<size_t>(y) * width_ + x) * 3];
  return {p[0], p[1], p[2]};
}

sh::vec2 EnvironmentMap::uv_of(const Vec3& dir) const {
  const Vec3 e = to_env(dir);
  return sh::hr_equirect_uv(sh::vec3(static_cast<float>(e.x), static_cast<float>(e.y), static_cast<float>(e.z)));
}

double EnvironmentMap::texel_solid_angle(int y) const {
  return (2 * M_PI / width_) * (row_sin_[static_cast<size_t>(y)] - row_sin_[static_cast<size_t>(y) + 1]);
}

Vec3 EnvironmentMap::radiance(const Vec3& dir) const {
  if (texels_.empty()) return constant_;
  const sh::vec2 uv = uv_of(dir);
  // Bilinear, as Blender's Environment Texture (Linear): wrapping across
  // the seam, clamped at the poles. Sampling draws whole texels; its
  // density (pdf) need only follow the light roughly to stay unbiased.
  const double fx = uv.x * width_ - 0.5, fy = (1 - uv.y) * height_ - 0.5;
  const int x0 = static_cast<int>(std::floor(fx)), y0 = static_cast<int>(std::floor(fy));
  const double tx = fx - x0, ty = fy - y0;
  auto at = [&](int x, int y) { return texel((x % width_ + width_) % width_, std::clamp(y, 0, height_ - 1)); };
  return (at(x0, y0) * (1 - tx) + at(x0 + 1, y0) * tx) * (1 - ty) + (at(x0, y0 + 1) * (1 - tx) + at(x0 + 1, y0 + 1) * tx) * ty;
}

Vec3 EnvironmentMap::sample(double u_cell, double u0, double u1, Vec3& dir, double& pdf) const {
  const size_t n = static_cast<size_t>(width_) * height_;
  if (texels_.empty() || black_) {
    // Constant: uniform over the sphere.
    const double z = 1 - 2 * u0, r = std::sqrt(std::fmax(0.0, 1 - z * z)), phi = 2 * M_PI * u1;
    dir = {r * std::cos(phi), r * std::sin(phi), z};
    pdf = 1 / (4 * M_PI);
    return constant_;
  }
  float rest;
  uint32_t cell = sh::hr_alias_cell(static_cast<float>(u_cell), static_cast<uint32_t>(n), rest);
  if (rest >= keep_[cell]) cell = alias_[cell];
  const int x = static_cast<int>(cell % static_cast<uint32_t>(width_)), y = static_cast<int>(cell / static_cast<uint32_t>(width_));
  // Uniform in the texel's u, and in its sin(latitude) so that the density
  // is constant over its solid angle.
  const double u = (x + u0) / width_;
  const double bottom = row_sin_[static_cast<size_t>(y) + 1], top = row_sin_[static_cast<size_t>(y)];
  const double lat = std::asin(std::clamp(bottom + u1 * (top - bottom), -1.0, 1.0));
  const sh::vec3 e = sh::hr_equirect_direction(sh::vec2(static_cast<float>(u), static_cast<float>(0.5 + lat / M_PI)));
  dir = normalize(to_world(Vec3{e.x, e.y, e.z}));
  pdf = share_[cell] / texel_solid_angle(y);
  return radiance(dir);
}

double EnvironmentMap::pdf(const Vec3& dir) const {
  if (texels_.empty() || black_) return 1 / (4 * M_PI);
  const sh::vec2 uv = uv_of(dir);
  const int x = std::min(width_ - 1, static_cast<int>(uv.x * width_));
  const int y = std::clamp(static_cast<int>((1 - uv.y) * height_), 0, height_ - 1);
  return share_[static_cast<size_t>(y) * width_ + x] / texel_solid_angle(y);
}

}  // namespace holoray
