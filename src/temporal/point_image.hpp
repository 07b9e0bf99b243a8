// holoray/temporal: the point image of a keyframe (paper §4): for every
// pixel, what its centre ray met (status, primitive, the hit point in its
// object's own space so it follows the object's motion, the depth t along the
// pixel line) and the shaded colour.
//
// Memory: 36 bytes per pixel (PrimaryHit 24 + RGB float 12), 44 with the
// reverse reprojection's object ids and depths, 68 with its visibility
// reuse's shading records (16) and edges (8); a 2048x2048 EIA takes 144
// (176, 272) MiB per keyframe, and reprojection holds two.
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
  /// Per scene group, its pose tag (AccelScene::pose: which vertices a
  /// deforming mesh had) and its bounds (world) at the keyframe's time. A
  /// group whose pose differs now cannot be mapped by a transform: reuse
  /// traces what it covers afresh.
  std::vector<uint64_t> pose;
  std::vector<Bounds3> bounds;
  /// W*H, what each pixel's shading rays found (reverse reprojection with
  /// ReverseReuse::visibility); empty otherwise.
  std::vector<ShadeParts> parts;
  /// Where a pixel's shading may cross an edge (its neighbours in its
  /// elemental image on the same primitive disagree, temporal/reverse.cpp):
  /// the lights whose visibility changes there, and whether the light of
  /// its mirror and refraction rays does. 8 bytes.
  struct Edges {
    uint32_t shadow = 0;
    bool secondary = false;
  };
  /// W*H beside `parts` (required with them), computed once when the
  /// keyframe is traced: reverse reprojection looks each pixel up from up
  /// to 14 frames.
  std::vector<Edges> edges;
  /// What the reverse reprojection's same-surface test reads of a pixel:
  /// the object id it saw (-1 background) and its line parameter t (as
  /// hits[p].t). One 8-byte record, so a lookup's four neighbours cost one
  /// cache line a row (reading the 24-byte hits and a separate id array
  /// were a lookup's cache misses), and no RenderScene::object_of.
  struct Seen {
    int32_t object = -1;
    float t = 0;
  };
  /// W*H, row-major; required by the reverse reprojection (a keyframe
  /// without is refused), empty in the forward reprojection's keyframes.
  std::vector<Seen> seen;

  static constexpr size_t kBytesPerPixel = sizeof(PrimaryHit) + 3 * sizeof(float);

  /// Records every scene group as the keyframe sees it: to_world, pose, bounds.
  void record_groups(const AccelScene& accel) {
    to_world.clear(), pose.clear(), bounds.clear();
    for (uint32_t g = 0; g < accel.group_count(); ++g) {
      to_world.push_back(accel.transform(g));
      pose.push_back(accel.pose(g));
      bounds.push_back(accel.group_bounds(g, accel.transform(g)));
    }
  }
  /// Group `g` has the keyframe's vertices in `accel` (not deformed since).
  bool same_pose(const AccelScene& accel, uint32_t g) const { return pose[g] == accel.pose(g); }
};

static_assert(sizeof(PrimaryHit) == 24, "the point image record is documented as 24 + 12 bytes per pixel");

}  // namespace holoray
