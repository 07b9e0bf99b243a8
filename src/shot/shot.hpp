// holoray/shot: an animated shot as plain structs, exactly what the shot file
// said (docs/shot-format.md), before anything is loaded or built: the scene
// files with their motion, the lens array's settings and its placement over
// time, the frame count and rate.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "camera/placement.hpp"
#include "math/transform.hpp"
#include "scene/mesh_reader.hpp"
#include "scene/scene_desc.hpp"
#include "shot/camera_path.hpp"

namespace holoray {

/// One scene file placed in the shot with a keyframed transform (object
/// space = the file's coordinates; the transform maps it to the world).
struct ShotObject {
  std::string scene;  ///< path, resolved against the shot file's folder
  TransformTrack motion;
  SourceLoc loc;
};

/// A key of the array's placement, given as an NFF-style viewpoint (the
/// contract's "Placement from an NFF viewpoint" applies at every frame).
struct ViewKey {
  double frame = 0;
  Vec3 from, at, up;
  std::optional<double> angle_deg;  ///< unset: the shot's / scene's angle
};

/// Where the array is over time: keys, a Tachyon path, or (neither) the
/// first scene's NFF viewpoint for every frame.
struct ShotCamera {
  std::vector<ViewKey> keys;
  Interpolation interpolation = Interpolation::linear;
  std::string path_file;                   ///< .cam path ("" when none), resolved like scenes
  std::vector<CameraPathFrame> path;       ///< its frames, read with the shot
  int path_start = 0;                      ///< path line (0-based) used for frame 0
  std::optional<double> distance;          ///< camera centre to array origin along the view; unset: scene centre depth
  std::optional<double> angle_deg;         ///< field width; unset: the scene's NFF angle, else 45
};

struct Shot {
  std::string source;  ///< the shot file (messages)
  int frames = 1;
  double fps = 24;
  int spp = 1;
  std::optional<Vec3> background;  ///< overrides the scenes' background
  ArraySettings array;             ///< as `holoray render` takes them (no explicit placement)
  ShotCamera camera;
  std::vector<ShotObject> objects;
  /// How its scene files are read: the mesh files' camera by name (top-level
  /// `camera_name`) and the folders textures are looked for in
  /// (`texture_path`, a string or an array, resolved against the shot file's
  /// folder; `holoray animate --texture-path` adds to them).
  SceneReadOptions read;
};

}  // namespace holoray
