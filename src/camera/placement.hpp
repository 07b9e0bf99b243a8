// holoray/camera: where the lens array sits, from the user's settings and the
// scene's NFF viewpoint (contract: "Placement from an NFF viewpoint").
#pragma once

#include <optional>

#include "camera/lens_array.hpp"
#include "scene/scene_desc.hpp"

namespace holoray {

/// What the user chose (command line), before placement. Unset optionals take
/// the contract's defaults.
struct ArraySettings {
  Grid grid = Grid::square;
  RecordingMode mode = RecordingMode::orthoscopic;
  int lenses_x = 64, lenses_y = 64;
  int pixels_per_lens = 8;
  int rows = 0;                          ///< 0: contract default for hex / lenticular
  std::optional<double> pitch;           ///< default: viewpoint width / Nx
  std::optional<double> gap;             ///< exclusive with fov_lens_deg
  std::optional<double> fov_lens_deg;    ///< default 20 degrees when gap is unset
  double view_distance = INFINITY;       ///< lenticular V
  std::optional<Vec3> origin, normal, up;  ///< explicit placement (all three together)
};

/// The default lens field of view, degrees (contract: "Placement").
inline constexpr double kDefaultLensFovDeg = 20.0;

/// The contract's placement of an array by a viewpoint ("Placement from an
/// NFF viewpoint"): orthoscopic O = at, z = normalize(from - at);
/// pseudoscopic O = from, z = normalize(at - from); a mirrored (Tachyon)
/// viewpoint flips x. `width` = 2|from - at| tan(angle/2), the field the
/// array spans. Throws std::invalid_argument when from = at or up is parallel.
struct ViewPlacement {
  Frame frame;
  double width = 0;
};
ViewPlacement place_by_viewpoint(RecordingMode mode, const Viewpoint& viewpoint);

/// The frame --origin, --normal and --up place something in (a lens array,
/// a display's panel): nullopt when none of them is given. Throws
/// std::invalid_argument when only some are.
std::optional<Frame> explicit_frame(const ArraySettings& settings);

/// Resolves settings into a camera description. Explicit placement needs
/// origin, normal, up and pitch; otherwise the viewpoint places the array:
/// orthoscopic O = at, z = normalize(from - at); pseudoscopic O = from,
/// z = normalize(at - from); width 2|from - at| tan(angle/2); pitch = width/Nx.
/// `up` is orthogonalised. Throws std::invalid_argument with the reason (no
/// viewpoint and no explicit placement, lens fov outside (0, 180), gap and fov
/// both given, ...). The result still goes through LensArray's validation.
LensArrayDesc place_array(const ArraySettings& settings, const std::optional<Viewpoint>& viewpoint);

}  // namespace holoray
