// holoray/cli: `holoray --version`: the release (CMake's project version), the
// git commit the binary was built from, and the versions of the libraries it
// was built with, for bug reports. The commit comes from holoray_version.hpp,
// which cmake/version_header.cmake rewrites at every build.
#pragma once

#include <string>

namespace holoray::cli {

/// The text `holoray --version` prints, two lines without a final newline:
/// "holoray VERSION (git COMMIT)", COMMIT a short hash with -dirty when
/// tracked files had changes, or "unknown" when not built from git; then
/// "built with: ..." naming each library's version as it reports it.
std::string version_text();

}  // namespace holoray::cli
