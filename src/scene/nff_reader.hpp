// holoray/scene: reader for NFF, the format of Eric Haines' Standard
// Procedural Databases (nff-notes.md). Token based: line breaks are ordinary
// whitespace, so `c` on one line or three both read.
#pragma once

#include <string>
#include <string_view>

#include "scene/scene_desc.hpp"

namespace holoray {

/// Limits that guard the reader, and everything built from its output,
/// against absurd counts (issue 5): each is checked before the thing is stored.
struct NffLimits {
  long max_polygon_vertices = 1'000'000;  ///< per polygon or patch
  /// Objects per file. A render peaks at ~0.4 GB per million spheres and
  /// ~0.55 GB per million triangles (docs/errors.md), so 20 million fit in
  /// 11 GB; a file over it is refused at the first object too many.
  long max_objects = 20'000'000;
  /// Every light costs a shadow ray at every hit: past this a frame would take
  /// days, so the file is refused instead.
  long max_lights = 10'000;
  /// Warnings kept as text; the rest are only counted (SceneDesc::warning_count).
  long max_warnings_kept = 100;
};

/// Parses NFF text. `source` names the file in error messages.
/// Throws ParseError ("file:line:col: error: ...") on any malformed input:
/// unknown keyword, missing or non-numeric or non-finite field, vertex count
/// < 3 or over the limit, more objects or lights than the limits allow, zero sphere radius, coincident cone ends, mixed-sign
/// cone radii, a second `v`, a truncated file.
SceneDesc parse_nff(std::string_view text, const std::string& source, const NffLimits& limits = {});

/// Reads and parses an NFF file. Throws std::runtime_error when it cannot be
/// read ("cannot read 'x': reason") and ParseError when it is malformed.
SceneDesc read_nff_file(const std::string& path, const NffLimits& limits = {});

}  // namespace holoray
