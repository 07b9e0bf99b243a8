// holoray/scene: reading a whole text file for the readers, with one set of
// error messages for every format.
#pragma once

#include <string>

namespace holoray {

/// The file's bytes. Throws std::runtime_error "cannot read '<path>': <reason>"
/// (missing, unreadable, a folder, a read error).
std::string read_text_file(const std::string& path);

}  // namespace holoray
