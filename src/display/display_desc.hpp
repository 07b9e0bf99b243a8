// holoray/display: a physical display as its display file describes it
// (docs/display-files.md, issue 14): the panel, the lens array on it in
// millimetres, and where the scene sits. Plain data; display_file.hpp reads
// and validates it, camera/display_camera.hpp turns it into lines.
#pragma once

#include <numbers>
#include <cmath>
#include <optional>
#include <string>

#include "camera/lens_array.hpp"

namespace holoray {

/// How a panel pixel is addressed: as one sample (`none`), or as three
/// colour subpixels side by side in vertical stripes, left to right R, G, B
/// (`rgb`) or B, G, R (`bgr`), each traced along its own line.
enum class SubpixelOrder { none, rgb, bgr };

const char* to_string(SubpixelOrder o);

/// A display file, in its own units (millimetres, degrees). Every value has
/// been range-checked by the reader (display_file.hpp).
struct DisplayDesc {
  std::string source;  ///< the file, for messages
  // [panel]
  int width = 0, height = 0;      ///< pixels
  double pixel_pitch_mm = 0;      ///< square pixels, centre to centre
  SubpixelOrder subpixels = SubpixelOrder::rgb;
  // [lens]
  Grid grid = Grid::lenticular;
  double pitch_mm = 0;            ///< lens pitch across the lenses (perpendicular to a lenticule's axis)
  double slant_deg = 0;           ///< lenticular: the axes' angle from vertical, positive leaning right at the top
  double gap_mm = 0;              ///< lens plane to panel (the lens focal length for a display focused at infinity)
  double offset_mm = 0;           ///< the lens grid shifted right of the panel's left edge
  double view_distance_mm = INFINITY;  ///< lenticular vertical perspective distance V
  // [scene]
  RecordingMode mode = RecordingMode::orthoscopic;
  std::optional<double> units_per_mm;  ///< default: the panel spans the scene viewpoint's field
  double depth = 0;  ///< the lens plane moved this far along its normal z (scene units): toward the viewer when orthoscopic, into the scene when pseudoscopic

  /// Samples across one panel row: 3 per pixel with subpixels, else 1.
  int samples_per_pixel() const { return subpixels == SubpixelOrder::none ? 1 : 3; }
  /// Pixels per lens along a row, P = pitch / pixel pitch (lenticular: horizontal pitch / pixel pitch).
  double pixels_per_lens() const { return pitch_mm / std::cos(slant_deg * std::numbers::pi / 180) / pixel_pitch_mm; }
};

}  // namespace holoray
