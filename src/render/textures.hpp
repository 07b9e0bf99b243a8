// holoray/render: Tachyon's texture functions (texture.c, imap.c of Tachyon
// 0.99; docs/tachyon-notes.md §3): the colour of a surface at a world-space
// hit point. Image maps are MIP-mapped as Tachyon does (2x2 box
// decimation in 8 bits, linear blend between two levels chosen from the
// optical distance), so that holoray's pixels match Tachyon's.
#pragma once

#include <vector>

#include "scene/scene_desc.hpp"

namespace holoray {

/// An image map's MIP levels; level 0 is the image, row 0 at the bottom.
/// Each level halves the last by 2x2 means: of the codes (Tachyon's), or of
/// the decoded light for an sRGB image (ImageMap::srgb, mesh textures).
/// A volume image (depth > 1) keeps its one level: Tachyon's decimation is
/// two-dimensional, so CreateMIPMap clamps volumes to a single level.
class MipMap {
 public:
  explicit MipMap(const ImageMap& image);
  /// Tachyon's MIPMap(u, v, d): black outside [0,1]^2; d in [0,1] picks the
  /// level (0 the finest), bilinear within a level.
  Vec3 sample(double u, double v, double d) const;
  /// Tachyon's VolMIPMap(u, v, w, d): black outside [0,1]^3; the level as in
  /// sample(), trilinear within it (a flat image is its slice 0).
  Vec3 sample_volume(double u, double v, double w, double d) const;
  int levels() const { return static_cast<int>(levels_.size()); }
  int width() const { return levels_.front().width; }
  int height() const { return levels_.front().height; }
  /// A mesh's image texture (TextureDesc::uv_image) at (u, v), v up from
  /// row 0, each axis wrapped by its mode: bilinear within a level (nearest
  /// texel when `nearest` and magnified), linear between the two levels
  /// around `level` (0 the finest; log2 of the footprint in level-0 texels,
  /// clamped to the levels there are). Texel codes pass through `decode`
  /// (256 linear values) before any filtering. Linear RGB.
  Vec3 sample_uv(double u, double v, double level, TextureWrap wrap_u, TextureWrap wrap_v, bool nearest,
                 const float decode[256]) const;
  /// The image's alpha at (u, v), bilinear on level 0 with sample_uv's
  /// wrapping, in [0, 1]; 1 for an image without alpha.
  double alpha_uv(double u, double v, TextureWrap wrap_u, TextureWrap wrap_v) const;
  /// The image has an alpha channel (alpha_uv reads it; else it is 1).
  bool has_alpha() const { return !alpha_.empty(); }
  /// Level 0's alpha codes (width x height), or empty.
  const std::vector<unsigned char>& alpha() const { return alpha_; }

  /// One level: width x height x depth texels of 8-bit RGB, x fastest.
  struct Level {
    int width, height, depth;
    std::vector<unsigned char> rgb;
  };
  /// Level k (0 the finest), for an executor that samples elsewhere (the GPU path).
  const Level& level(int k) const { return levels_[static_cast<size_t>(k)]; }

 private:
  static Vec3 trilinear(const Level& l, double u, double v, double w);
  template <class Lookup>
  Vec3 blend_levels(double d, Lookup lookup) const;
  std::vector<Level> levels_;
  std::vector<unsigned char> alpha_;  // level 0's alpha codes, or empty
};

/// The 256 linear values of 8-bit codes: sRGB-decoded (IEC 61966-2-1) or code / 255.
const float* decode_table(bool srgb);

/// The colour of `tex` at `p_world` seen at `optic_dist` (world units along
/// the ray path from the eye; it sets an image map's MIP level), for a
/// material of colour `base` (the checkers and wood ignore it, as in
/// Tachyon). `mip` is the texture's image map (null for procedural ones).
Vec3 texture_colour(const TextureDesc& tex, const MipMap* mip, const Vec3& base, const Vec3& p_world,
                    double optic_dist);

}  // namespace holoray
