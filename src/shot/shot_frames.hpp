// holoray/shot: a shot made ready to render frame by frame: its scene files
// read and built into one RenderScene (a moving file, and each node a mesh
// file's animation moves, becomes an Embree instance; each skinned or
// morphed mesh a
// deformable one), and for every frame the objects' transforms, the
// deforming meshes' vertices and the lens array.
#pragma once

#include <memory>
#include <vector>

#include "camera/lens_array.hpp"
#include "render/render_context.hpp"
#include "scene/mesh_reader.hpp"
#include "shot/shot.hpp"

namespace holoray {

class ShotFrames {
 public:
  /// Reads every scene file (NFF, Tachyon, meshes with their node
  /// animation) and builds the scene. Throws what the
  /// readers throw (ParseError, std::runtime_error) and std::invalid_argument
  /// when the array cannot be placed (no camera keys, path or NFF viewpoint;
  /// a path whose first camera looks away from the scene).
  explicit ShotFrames(Shot shot);

  const Shot& shot() const { return shot_; }
  int frame_count() const { return shot_.frames; }
  const RenderScene& scene() const { return *scene_; }
  /// The scene parts: each file's still part, then its animated nodes' parts.
  const std::vector<SceneDesc>& scenes() const { return descs_; }

  /// Object-to-world transform of every scene part at `frame` (may be
  /// fractional): the shot's motion of its file, times, for an animated
  /// node, the file's animation at frame / fps seconds.
  std::vector<Affine> transforms(double frame) const;
  /// The lens array at `frame` (contract placement from the frame's viewpoint).
  LensArrayDesc camera(int frame) const;
  /// The viewpoint the array is placed from at `frame` (world).
  Viewpoint viewpoint(int frame) const;
  /// Moves the scene to `frame` and poses its skinned and morphed meshes there (not
  /// thread-safe against rendering).
  void seek(int frame);
  /// What the shot's renders start from: its scene files' depth limit and
  /// background, the shot's background where it sets one (render_context.hpp).
  RenderSettings settings() const;

 private:
  struct Entry {
    size_t object;  ///< index into shot_.objects
    int part;       ///< -1: the file's still part; else index into its MeshAnimation::parts
  };
  Shot shot_;
  std::vector<SceneDesc> descs_;               // per entry
  std::vector<Entry> entries_;
  std::vector<MeshAnimation> animations_;      // per object (parts' scenes moved to descs_)
  struct DeformingRef {
    size_t entry;   ///< the deforming mesh's part: index into entries_ (its scene group)
    size_t object;  ///< index into shot_.objects (and animations_)
    size_t mesh;    ///< index into that object's MeshAnimation::deforming
  };
  std::vector<DeformingRef> deforming_;
  std::unique_ptr<RenderScene> scene_;
  double default_angle_ = 45;
  bool mirrored_ = false;  // the scene's viewpoint is Tachyon's (Viewpoint::mirrored)
  double path_distance_ = 0;  // camera centre to array, along the view (path cameras)
};

}  // namespace holoray
