// holoray/display: a display file placed in a scene. The panel's millimetres
// become scene units (the file's units_per_mm, or the scale at which the
// panel spans the scene viewpoint's field), and the lens plane takes the
// contract's placement ("Placement from an NFF viewpoint"), moved toward the
// viewer by the file's depth.
#pragma once

#include <optional>

#include "camera/display_camera.hpp"
#include "display/display_desc.hpp"
#include "scene/scene_desc.hpp"

namespace holoray {

/// The display's lines in the scene. `explicit_frame` (from --origin
/// --normal --up) replaces the viewpoint's placement and needs the file's
/// units_per_mm. Throws std::invalid_argument when neither a viewpoint nor
/// an explicit frame places the array, or the scale is missing.
DisplayGeometry place_display(const DisplayDesc& d, const std::optional<Viewpoint>& viewpoint,
                              const std::optional<Frame>& explicit_frame = std::nullopt);

/// When the display is an ordinary EIA (no subpixel addressing, no slant, no
/// offset, a square or lenticular grid with a whole number of pixels per
/// lens and of lenses across the panel, and down it for the square grid):
/// the lens array of holoray's integral camera for it, so that it renders
/// with every integral-camera feature (styles, the shadow cache, reuse).
/// Its settings are those of `render --grid G --lenses NXxNY
/// --pixels-per-lens P --gap G` (and --pitch when the file sets
/// units_per_mm), the EIA bit for bit that command's. std::nullopt otherwise.
std::optional<LensArrayDesc> as_lens_array(const DisplayDesc& d, const std::optional<Viewpoint>& viewpoint,
                                           const std::optional<Frame>& explicit_frame = std::nullopt);

}  // namespace holoray
