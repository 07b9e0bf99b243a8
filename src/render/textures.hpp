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

 private:
  struct Level {
    int width, height, depth;
    std::vector<unsigned char> rgb;
  };
  static Vec3 trilinear(const Level& l, double u, double v, double w);
  template <class Lookup>
  Vec3 blend_levels(double d, Lookup lookup) const;
  std::vector<Level> levels_;
};

/// The colour of `tex` at `p_world` seen at `optic_dist` (world units along
/// the ray path from the eye; it sets an image map's MIP level), for a
/// material of colour `base` (the checkers and wood ignore it, as in
/// Tachyon). `mip` is the texture's image map (null for procedural ones).
Vec3 texture_colour(const TextureDesc& tex, const MipMap* mip, const Vec3& base, const Vec3& p_world,
                    double optic_dist);

}  // namespace holoray
