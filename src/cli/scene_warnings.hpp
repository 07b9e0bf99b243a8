// holoray/cli: how every command shows a scene's warnings.
#pragma once

#include "scene/scene_desc.hpp"

namespace holoray {

/// Prints the first 10 of desc's warnings to stderr ("file:line:col:
/// warning: ..."), then "<file>: N more warnings" when there were more.
void print_scene_warnings(const SceneDesc& desc);

}  // namespace holoray
