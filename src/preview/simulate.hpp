// holoray/preview: what a viewer sees on a display without the display
// (issue 14, item 4). An eye at a point in front of the lens sheet looks at
// each point of the lens plane; the lens there (a thin lens with the panel
// in its focal plane) sends the eye's ray to the panel point where the
// lens's chief ray parallel to it lands, so each lens shows a patch of its
// elemental image magnified by (eye distance / gap), and two eye positions
// show the parallax a viewer would see. A lenticular sheet has this power
// across its lenticules only; along them the ray goes straight on.
//
// Frame and units: the display's array frame in millimetres (origin at the
// panel centre on the lens plane, x right, y up, z toward the viewer).
#pragma once

#include "camera/display_camera.hpp"
#include "display/display_desc.hpp"
#include "image/image.hpp"
#include "math/vec.hpp"

namespace holoray {

struct SimulateOptions {
  Vec3 eye_mm{0, 0, 600};  ///< eye position, display frame, mm; z > 0
  int width = 800;         ///< output pixels across the panel (height keeps the panel's aspect)
  int samples = 3;         ///< samples per output pixel along each axis (the eye's integration)
};

/// The panel point (display frame, mm, z = -gap) an eye at `eye` sees
/// through lens-plane point `q` (z = 0) of `camera` (a display placed with
/// units_per_mm = 1 and the identity frame).
Vec3 seen_panel_point(const DisplayCamera& camera, const Vec3& eye, const Vec3& q);

/// The picture an eye sees on `panel` (the display's native image,
/// width x height pixels of the display file): per output pixel the mean of
/// samples x samples points spread over its part of the lens plane, each
/// reading the panel where seen_panel_point() lands. With subpixels, a point
/// lights only the channel of the stripe it falls on, as the panel does; a
/// point off the panel is black. Throws std::invalid_argument when the
/// image's size is not the display's, the eye is not in front of the lens
/// plane, or the sizes are out of range.
ImageBuffer simulate_view(const ImageBuffer& panel, const DisplayDesc& display, const SimulateOptions& options);

}  // namespace holoray
