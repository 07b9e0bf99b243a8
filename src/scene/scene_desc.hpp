// holoray/scene: the scene description as plain structs, exactly what a file
// said, before any rendering object is built (architecture.md: "Parsing never
// builds render objects"). Every item keeps the source location it came from.
#pragma once

#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "math/vec.hpp"

namespace holoray {

/// 1-based line and column in the scene file; 0 when the item was made in code.
struct SourceLoc {
  int line = 0;
  int col = 0;
};

/// NFF `v` (nff-notes §2). World units; `up` as written (not orthogonalised).
struct Viewpoint {
  Vec3 from, at, up;
  double angle_deg = 45;   // full-image field of view (nff-notes §2)
  double hither = 0;       // read and kept; the integral camera ignores it (see README)
  int xres = 0, yres = 0;  // 0 when the file gives no `resolution`
  SourceLoc loc;
};

/// NFF `l`: point light, no falloff, never visible to eye rays (nff-notes §4).
struct Light {
  Vec3 position;
  Vec3 colour{1, 1, 1};  // optional RGB, multiplies the per-light intensity
  SourceLoc loc;
};

/// NFF `f` (nff-notes §5): colour, Kd, Ks (mirror weight and highlight weight),
/// Phong exponent, transmittance T (weight of the refracted ray) and ior.
struct Material {
  Vec3 colour{0.8, 0.8, 0.8};
  double kd = 1, ks = 0, shine = 0, transmittance = 0, ior = 1;
  SourceLoc loc;
};

/// NFF `s`: negative radius means only the inside is visible.
struct SphereDesc {
  Vec3 centre;
  double radius = 1;
};

/// NFF `c`: open truncated cone (no caps) from base to apex. Both radii
/// negative means only the inside is visible; radii otherwise share a sign.
struct ConeDesc {
  Vec3 base, apex;
  double base_radius = 1, apex_radius = 1;
};

/// NFF `p` / `pp`: planar, possibly concave polygon; front side is where the
/// vertices run counter-clockwise. `normals` is empty for `p`, one per vertex for `pp`.
struct PolygonDesc {
  std::vector<Vec3> vertices;
  std::vector<Vec3> normals;
};

/// One primitive of the file; its index in SceneDesc::objects is its object id.
struct ObjectDesc {
  std::variant<SphereDesc, ConeDesc, PolygonDesc> shape;
  int material = -1;  // index into SceneDesc::materials; -1: before any `f` (default grey)
  SourceLoc loc;
};

/// A whole scene as read from one file.
struct SceneDesc {
  std::string source;                 // file name used in messages
  std::optional<Viewpoint> viewpoint; // NFF `v`, when present
  Vec3 background{0, 0, 0};           // NFF `b`; black when absent (nff-notes §3)
  std::vector<Light> lights;
  std::vector<Material> materials;
  std::vector<ObjectDesc> objects;
  /// "file:line:col: warning: ..." for input that was accepted but is
  /// suspect (a polygon with no area, a negative sphere radius), in file
  /// order; only the first NffLimits::max_warnings_kept are kept as text.
  std::vector<std::string> warnings;
  /// Every warning, kept or not.
  size_t warning_count = 0;
};

}  // namespace holoray
