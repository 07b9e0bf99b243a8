// holoray/shot: Tachyon camera path files (`.cam`), as shipped with the
// paper's scenes (shared/scenes/tachyon): one frame per line, nine numbers:
// view direction (3), up direction (3), camera centre (3), world frame.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "math/vec.hpp"
#include "scene/scene_desc.hpp"

namespace holoray {

/// One line of a camera path. `view` and `up` are as written (not unit, up
/// not orthogonalised); the reader guarantees view != 0 and up not parallel to it.
struct CameraPathFrame {
  Vec3 view, up, centre;
  SourceLoc loc;
};

/// Parses `.cam` text; `source` names the file in messages. Throws ParseError
/// (file:line:col with a caret) for a non-numeric or non-finite field, a line
/// with other than nine numbers, a zero view direction, an up direction
/// parallel to the view, or a file with no frames. Limit: 10 million lines.
std::vector<CameraPathFrame> parse_camera_path(std::string_view text, const std::string& source);

/// Reads and parses a `.cam` file; std::runtime_error when it cannot be read.
std::vector<CameraPathFrame> read_camera_path(const std::string& path);

}  // namespace holoray
