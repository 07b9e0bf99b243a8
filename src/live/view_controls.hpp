// holoray/live: where the live window looks from, and how input moves it
// (docs/guide/live.md, "Controls"). Plain math on a Viewpoint: the camera
// is placed from it exactly as `holoray render` places it from a scene
// file's viewpoint, so a frame shown equals the still rendered from the
// viewpoint live prints.
#pragma once

#include <optional>
#include <string>

#include "scene/scene_desc.hpp"

namespace holoray::live {

/// The view the window shows. World frame, scene units.
struct LiveView {
  Viewpoint viewpoint;     ///< eye (from), the point looked at, up, the field of view
  /// The array's (or panel's, or focal) plane, from the eye along the view,
  /// once set (the camera's focus distance, a key); nullopt: |eye - at|,
  /// as `holoray render` places it without --focus-distance.
  std::optional<double> focus_distance;
  std::optional<double> lens_fov_deg;  ///< a lens array's field of view, once a key changed it
};

/// The focal plane's distance from the eye.
double focus(const LiveView& view);

/// Turns the eye about the point looked at: a drag across the window's
/// whole width (`width` pixels, dx > 0 rightward) turns it 180 degrees about
/// `up`, one down its whole height 90 degrees about the view's right axis,
/// the eye kept 1 degree from either pole. |eye - at| is kept.
void orbit(LiveView& view, double dx, double dy, int width, int height);
/// Moves eye and point looked at together, so that what lies on the focal
/// plane follows the pointer (`height`: the window's, for the vertical
/// field of view's span there).
void pan(LiveView& view, double dx, double dy, int height);
/// The wheel: the eye moves toward the point looked at (clicks > 0) or
/// away, |eye - at| and a set focus distance both scaled by 0.9^clicks, so
/// a plane through the point looked at stays there.
void dolly(LiveView& view, double clicks);
/// The plane nearer (steps < 0) or farther: focus distance times 1.05^steps.
void move_plane(LiveView& view, double steps);
/// The lens field of view `degrees` more, kept within [1, 120]; `current`
/// is the placed array's, before any key changed it.
void widen_lenses(LiveView& view, double degrees, double current);

/// "eye X,Y,Z at X,Y,Z up X,Y,Z fov F [focus D] [lens-fov L]", every
/// number to 17 significant digits (round trips to the same doubles); focus
/// and lens-fov only once set.
std::string describe(const LiveView& view);

}  // namespace holoray::live
