// holoray/cli: how every command shows a scene's warnings.
#pragma once

#include <string>
#include <vector>

#include "scene/scene_desc.hpp"

namespace holoray {

/// Prints the first 10 of desc's warnings to stderr ("file:line:col:
/// warning: ..."), then "<file>: N more warnings" when there were more.
void print_scene_warnings(const SceneDesc& desc);
/// The same for warnings as the public API gives them (api::Scene, api::Animation).
void print_scene_warnings(const std::vector<std::string>& warnings, size_t count, const std::string& source);

}  // namespace holoray
