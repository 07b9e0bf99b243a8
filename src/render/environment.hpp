// holoray/render: the light from around the scene that the path integrator
// sees when a ray leaves it: a constant colour, or an equirectangular image
// (HDR or EXR, linear RGB) mapped as Blender maps an Environment Texture
// (shading/environment.h), times a strength, turned about the up axis.
// Built once per render from a decoded image (files are read by the API);
// importance-sampled by an alias table over the texels, each weighted by
// its luminance times the solid angle it covers.
#pragma once

#include <cstdint>
#include <vector>

#include "image/image.hpp"
#include "math/vec.hpp"
#include "shading/glsl_compat.hpp"

namespace holoray {

/// Which world axis is the environment's up (the image's top row): glTF's
/// and most mesh formats' +y, or +z (Blender's own frame, NFF's SPD scenes).
enum class EnvironmentUp { y, z };

class EnvironmentMap {
 public:
  /// A constant environment: every direction sees `radiance` (linear RGB).
  explicit EnvironmentMap(const Vec3& radiance);
  /// An image environment: `image` (RGB or more channels, rows from the top;
  /// width >= 2, height >= 1) times `strength`, its lookups turned by
  /// `rotation_rad` about the up axis (a Blender Mapping node's Z rotation).
  /// Throws std::invalid_argument for an image without 3 channels or of
  /// fewer than 2x1 texels, or a negative or non-finite strength.
  EnvironmentMap(const ImageBuffer& image, double strength, double rotation_rad, EnvironmentUp up);

  /// Radiance arriving along -`dir` (what a ray travelling along `dir`,
  /// world frame, unit, sees).
  Vec3 radiance(const Vec3& dir) const;
  /// A direction (world, unit) drawn in proportion to the light it brings
  /// (a texel by `u_cell`, a point in it by u0, u1; all in [0, 1)), its
  /// solid-angle density `pdf` and its radiance.
  Vec3 sample(double u_cell, double u0, double u1, Vec3& dir, double& pdf) const;
  /// The density sample() gives `dir` (world, unit).
  double pdf(const Vec3& dir) const;
  /// Whether it lights nothing (a black constant): the integrator then skips it.
  bool black() const { return black_; }
  bool constant() const { return texels_.empty(); }

 // What the GPU path uploads (gpu/gpu_scene.cpp): the image's size (0 x 0
  // for a constant), its texels (RGB, rows from the top, strength
  // applied), the alias table (per texel: the probability of keeping it,
  // its alias, its share of the light), the turn about the up axis and the up axis.
  int width() const { return width_; }
  int height() const { return height_; }
  const Vec3& constant_radiance() const { return constant_; }
  const std::vector<float>& texels() const { return texels_; }
  const std::vector<float>& keep() const { return keep_; }
  const std::vector<uint32_t>& alias() const { return alias_; }
  const std::vector<float>& share() const { return share_; }
  float cos_rotation() const { return cos_rot_; }
  float sin_rotation() const { return sin_rot_; }
  EnvironmentUp up() const { return up_; }

 private:
  shading::vec2 uv_of(const Vec3& world) const;  // the image coordinates (u right, v up) a direction reads
  Vec3 texel(int x, int y) const;

  Vec3 constant_;
  int width_ = 0, height_ = 0;
  std::vector<float> texels_;  // RGB, rows from the top, strength applied
  // The alias table: per texel, the probability of keeping it and its alias;
  // and each texel's share of the total (its sampling probability).
  std::vector<float> keep_;
  std::vector<uint32_t> alias_;
  std::vector<float> share_;
  float cos_rot_ = 1, sin_rot_ = 0;  // float, as the shared mapping (shading/environment.h) takes them
  EnvironmentUp up_ = EnvironmentUp::y;
  bool black_ = false;
};

}  // namespace holoray
