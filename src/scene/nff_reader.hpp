// holoray/scene: reader for NFF, the format of Eric Haines' Standard
// Procedural Databases (nff-notes.md). Token based: line breaks are ordinary
// whitespace, so `c` on one line or three both read.
#pragma once

#include <string>
#include <string_view>

#include "scene/scene_desc.hpp"

namespace holoray {

/// Limits that guard the reader against absurd counts before it allocates.
struct NffLimits {
  long max_polygon_vertices = 1'000'000;
};

/// Parses NFF text. `source` names the file in error messages.
/// Throws ParseError ("file:line:col: error: ...") on any malformed input:
/// unknown keyword, missing or non-numeric or non-finite field, vertex count
/// < 3 or over the limit, zero sphere radius, coincident cone ends, mixed-sign
/// cone radii, a second `v`, a truncated file.
SceneDesc parse_nff(std::string_view text, const std::string& source, const NffLimits& limits = {});

/// Reads and parses an NFF file. Throws std::runtime_error when it cannot be
/// read ("cannot read 'x': reason") and ParseError when it is malformed.
SceneDesc read_nff_file(const std::string& path, const NffLimits& limits = {});

}  // namespace holoray
