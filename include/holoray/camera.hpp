// holoray public API: the cameras an image is rendered through, as plain
// data. Each is placed by the scene's viewpoint (or, for lens arrays and
// panels, an explicit frame) when a Renderer is made, exactly as the CLI
// places it (docs/camera-model.md, "Placement from an NFF viewpoint").
#pragma once

#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <variant>

namespace holoray::api {

enum class Grid { square, hex, lenticular };
/// orthoscopic: display-ready (the viewer sees depth right way round);
/// pseudoscopic: a direct pickup (camera-model.md).
enum class Mode { orthoscopic, pseudoscopic };

/// An explicit frame for a lens array or a panel (world): its centre, its
/// normal toward the viewer, and up (orthogonalised).
struct Placement {
  std::array<double, 3> origin, normal, up;
};

/// The integral camera: a grid of lenses, each with P x P pixels behind it
/// (hex: P across; lenticular: P across each lenticule, `rows` tall). The
/// EIA is lenses_x P x lenses_y P pixels (square grid). Lens field of view
/// sets the gap (default 20 degrees); pitch defaults to the viewpoint's
/// width / lenses_x. Units: the scene's.
struct LensArray {
  Grid grid = Grid::square;
  int lenses_x = 64, lenses_y = 64;
  int pixels_per_lens = 8;
  int rows = 0;                        ///< hex and lenticular: image rows; 0 the contract's
  std::optional<double> fov_lens_deg;  ///< exclusive with gap
  std::optional<double> pitch, gap;
  Mode mode = Mode::orthoscopic;
  double view_distance = INFINITY;     ///< lenticular: vertical perspective distance V
  std::optional<Placement> placement;  ///< needs pitch; default: the viewpoint's
  /// Orthoscopic: the array stands this far from the eye along the view
  /// (pseudoscopic: at the eye, the field measured there); scene units,
  /// > 0. Default: the viewpoint's |eye - at| (a mesh file's camera: the
  /// depth of the scene's centre). Exclusive with placement.
  std::optional<double> focus_distance;
};

/// The viewpoint's ordinary perspective view. 0 x 0: the scene's resolution,
/// else 512 x 512.
struct Pinhole {
  int width = 0, height = 0;
  /// One sample at each pixel's upper-right corner, where Tachyon samples.
  bool tachyon_samples = false;
  /// Lens shift: the window moved right and up by these fractions of its
  /// larger side (Blender's shift_x and shift_y).
  double shift_x = 0, shift_y = 0;
};

/// A Looking Glass quilt: columns x rows sheared views on the viewpoint's
/// focal plane, view 0 (the leftmost) bottom left.
struct Quilt {
  int columns = 8, rows = 6;
  int view_width = 420, view_height = 560;
  double view_cone_deg = 40;  ///< leftmost to rightmost view
  int view = -1;              ///< >= 0: only that view, as a plain image
  /// The views' focal (zero-parallax) plane's distance from the viewpoint,
  /// scene units; default: the viewpoint's |eye - at| (a mesh file's camera:
  /// the depth of the scene's centre).
  std::optional<double> focus_distance;
};

/// A physical panel and its lens sheet (docs/display-files.md): its native
/// image, each subpixel along its own line.
struct Display {
  std::string path;                    ///< the display file (TOML)
  std::optional<Placement> placement;  ///< default: the viewpoint's
  std::optional<double> focus_distance;  ///< as LensArray's: where the panel's lens sheet stands
};

/// A Looking Glass's native panel image from its calibration (visual.json).
struct LookingGlass {
  std::string path;
  int views = 48;  ///< the quilt the image is the continuous version of
  std::optional<double> focus_distance;  ///< as Quilt's
};

using Camera = std::variant<LensArray, Pinhole, Quilt, Display, LookingGlass>;

}  // namespace holoray::api
