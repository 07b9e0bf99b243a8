// holoray/temporal: where a shot's keyframes go (issue 12,
// `--keyframe-interval auto`). Reuse errs by how far a point image moves
// between a frame and its keyframe (the point is seen along another line,
// through another lens, at another spot on its surface), so keyframes are
// placed by that motion rather than every K frames: sparse where the camera
// and the objects hold still, dense where they move fast, and at every cut.
//
// The measure (image_motion) needs no rendering: probe points on each scene
// part's bounds (3 x 3 x 3 per part, at the part's transforms of each frame)
// seen from nine lens positions of the array (its centre, edge midpoints and
// corners, at each frame's placement); a probe's direction from a lens
// turns by an angle, and angle / (pixel pitch / gap) is how many pixels its
// point image moves under that lens. The motion between two frames is the
// largest over probes and lenses. Probes nearer a lens than one pitch are
// skipped (their direction is not defined at the array plane).
#pragma once

#include <vector>

#include "math/vec.hpp"
#include "shot/shot_frames.hpp"

namespace holoray {

class KeyframePlanner {
 public:
  /// Probes the shot's scene parts (ShotFrames::scenes(), without planes,
  /// lights' spheres or sky domes).
  explicit KeyframePlanner(const ShotFrames& shot);

  /// The largest movement, in pixels of the elemental images, of any probe's
  /// point image between frames a and b (0 when nothing moves).
  double image_motion(int a, int b) const;

  /// Keyframes for the whole shot: frame 0, then from each keyframe k the
  /// farthest frame f such that every frame g in (k, f] has
  /// image_motion(k, g) <= max_pixels and f - k <= max_interval (at least
  /// k + 1), up to the last frame, which is always a keyframe. Throws
  /// std::invalid_argument for max_pixels <= 0 or max_interval < 1.
  std::vector<int> keyframes(double max_pixels, int max_interval) const;

 private:
  struct View {
    std::vector<Vec3> probes;  // world, every part's
    std::vector<Vec3> lenses;  // world, the nine lens positions
    double pixel_angle = 0;    // radians per pixel: pixel pitch / gap
    double pitch = 0;
  };
  View view_at(int frame) const;
  static double motion(const View& a, const View& b);

  const ShotFrames& shot_;
  std::vector<std::vector<Vec3>> probes_;  // per scene part, object space
};

}  // namespace holoray
