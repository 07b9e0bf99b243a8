// holoray public API: text files written whole or not at all, as every
// output of holoray is (reports, sidecars).
#pragma once

#include <string>

#include "holoray/export.hpp"

namespace holoray::api {

/// Writes `text` to a temporary name in `path`'s folder and renames it into
/// place: readers never see half a file. Throws std::system_error naming the
/// path and the reason.
HOLORAY_API void write_text_file(const std::string& path, const std::string& text);

}  // namespace holoray::api
