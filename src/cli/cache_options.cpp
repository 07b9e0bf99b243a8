#include "cli/cache_options.hpp"

#include <fmt/format.h>
#include <cmath>

#include "cli/option_parsing.hpp"

namespace holoray::cli {

void add_cache_options(CLI::App& cmd, CacheCommandOptions& o) {
  cmd.add_option("--cache", o.cache, "Shadow cache: on (reuse light visibility per surface cell across lenses and still frames) or off (trace every shadow ray)")->capture_default_str();
  cmd.add_option("--cache-cell", o.cell, "Shadow-cache cell size, in lens pitches")->capture_default_str();
  cmd.add_option("--cache-memory", o.memory_mib, "Shadow-cache memory bound, MiB (primitives past it trace their shadow rays)")->capture_default_str();
}

bool cache_enabled(const CacheCommandOptions& o) {
  const bool on = pick<bool>("--cache", o.cache, {{"on", true}, {"off", false}});
  if (!(o.cell > 0) || !std::isfinite(o.cell))
    throw std::invalid_argument(fmt::format("--cache-cell: must be a positive number of lens pitches, got {}", o.cell));
  if (!(o.memory_mib >= 0) || !std::isfinite(o.memory_mib))
    throw std::invalid_argument(fmt::format("--cache-memory: must be 0 MiB or more, got {}", o.memory_mib));
  return on;
}

api::ShadowCacheOptions cache_options(const CacheCommandOptions& o) { return {cache_enabled(o), o.cell, o.memory_mib}; }

}  // namespace holoray::cli
