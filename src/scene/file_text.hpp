// holoray/scene: whole text files: reading them for the readers, with one
// set of error messages for every format, and writing reports atomically.
#pragma once

#include <fstream>
#include <string>

namespace holoray {

/// The file opened for reading (binary). Throws std::system_error (its errno) "cannot
/// read '<path>': <reason>" (missing, unreadable, a folder): the messages of
/// every reader, also those whose parser opens the file itself (meshes).
std::ifstream open_for_reading(const std::string& path);

/// The file's bytes. Throws std::system_error "cannot read '<path>': <reason>"
/// (missing, unreadable, a folder, a read error).
std::string read_text_file(const std::string& path);

/// Writes `text` to a temporary name in the same folder and renames it into
/// place, so readers never see half a file. Throws std::system_error naming
/// the path and reason.
void write_text_file(const std::string& path, const std::string& text);

}  // namespace holoray
