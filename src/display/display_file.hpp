// holoray/display: reads a display file (TOML; docs/display-files.md) into
// a DisplayDesc. Every value is checked where it is written: impossible
// values (a non-positive pitch, a slant past 45 degrees, a lens narrower
// than a pixel, a panel too large to address) are refused at their
// file:line:col with the value and its unit named.
#pragma once

#include <string>
#include <string_view>

#include "display/display_desc.hpp"

namespace holoray {

/// Parses display-file text; `source` names it in messages. Throws ParseError.
DisplayDesc parse_display(std::string_view text, const std::string& source);
/// Reads and parses a display file. Throws ParseError (and
/// std::runtime_error when the file cannot be read).
DisplayDesc read_display_file(const std::string& path);

}  // namespace holoray
