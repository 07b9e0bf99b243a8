#include "cli/scene_warnings.hpp"

#include <fmt/core.h>

#include <algorithm>

namespace holoray::cli {

void print_scene_warnings(const std::vector<std::string>& warnings, size_t count, const std::string& source) {
  constexpr size_t kShown = 10;  // enough to find the pattern, few enough to still see the summary
  const size_t shown = std::min(kShown, warnings.size());
  for (size_t k = 0; k < shown; ++k) fmt::print(stderr, "{}\n", warnings[k]);
  if (count > shown) fmt::print(stderr, "{}: {} more warning{}\n", source, count - shown, count - shown == 1 ? "" : "s");
}

}  // namespace holoray::cli
