// holoray/cli: how every command shows a scene's warnings.
#pragma once

#include <string>
#include <vector>

namespace holoray::cli {

/// Prints the first 10 of a scene's warnings (api::Scene, api::Animation) to
/// stderr ("file:line:col: warning: ..."), then "<file>: N more warnings"
/// when there were more.
void print_scene_warnings(const std::vector<std::string>& warnings, size_t count, const std::string& source);

}  // namespace holoray::cli
