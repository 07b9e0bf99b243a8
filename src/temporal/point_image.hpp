// holoray/temporal: the point image of a keyframe (paper §4): for every
// pixel, what its centre ray met (status, primitive, the hit point in its
// object's own space so it follows the object's motion, the depth t along the
// pixel line) and the shaded colour.
//
// Memory: 36 bytes per pixel (PrimaryHit 24 + RGB float 12), 40 with the
// reverse reprojection's object ids; a 2048x2048 EIA takes 144 (160) MiB per
// keyframe, and reprojection holds two.
#pragma once

#include <vector>

#include "camera/lens_array.hpp"
#include "image/image.hpp"
#include "math/transform.hpp"
#include "render/renderer.hpp"
#include "render/shading.hpp"

namespace holoray {

struct PointImage {
  int frame = 0;
  LensArray camera;               ///< the keyframe's integral camera
  std::vector<PrimaryHit> hits;   ///< W*H, row-major
  ImageBuffer colour;             ///< W x H x 3, linear RGB
  /// Object-to-world transform per scene group at the keyframe's time
  /// (AccelScene::transform); reverse reprojection moves hits back with it.
  std::vector<Affine> to_world;
  /// W*H, what each pixel's shading rays found (reverse reprojection with
  /// ReverseReuse::visibility); empty otherwise.
  std::vector<ShadeParts> parts;
  /// W*H, the object id each pixel saw (-1 background), for the reverse
  /// reprojection's same-surface tests (four per reused hit; reading it is
  /// cheaper than RenderScene::object_of); required there (a keyframe
  /// without is refused), empty in the forward reprojection's keyframes.
  std::vector<int32_t> object;

  static constexpr size_t kBytesPerPixel = sizeof(PrimaryHit) + 3 * sizeof(float);
};

static_assert(sizeof(PrimaryHit) == 24, "the point image record is documented as 24 + 12 bytes per pixel");

}  // namespace holoray
