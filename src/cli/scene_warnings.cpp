#include "cli/scene_warnings.hpp"

#include <fmt/core.h>

#include <algorithm>

namespace holoray {

void print_scene_warnings(const SceneDesc& desc) {
  constexpr size_t kShown = 10;  // enough to find the pattern, few enough to still see the summary
  const size_t shown = std::min(kShown, desc.warnings.size());
  for (size_t k = 0; k < shown; ++k) fmt::print(stderr, "{}\n", desc.warnings[k]);
  if (desc.warning_count > shown)
    fmt::print(stderr, "{}: {} more warning{}\n", desc.source, desc.warning_count - shown,
               desc.warning_count - shown == 1 ? "" : "s");
}

}  // namespace holoray
