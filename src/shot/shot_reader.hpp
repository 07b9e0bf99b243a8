// holoray/shot: reads shot files (TOML, docs/shot-format.md) into a Shot.
#pragma once

#include <string>
#include <string_view>

#include "shot/shot.hpp"

namespace holoray {

/// Parses shot text. `source` names the file in messages and is the folder
/// that relative scene and path names are resolved against; camera path
/// files are read here too. Throws ParseError (file:line:col, the line and a
/// caret) on a TOML syntax error, an unknown key, a value of the wrong type or
/// out of range (frames in 1..1e6, lens counts, keys not increasing), a path
/// shorter than start + frames; std::runtime_error when a path file cannot be read.
Shot parse_shot(std::string_view text, const std::string& source);

/// Reads and parses a shot file; std::runtime_error when it cannot be read.
Shot read_shot_file(const std::string& path);

}  // namespace holoray
