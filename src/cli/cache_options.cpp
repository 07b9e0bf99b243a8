#include "cli/cache_options.hpp"

#include <fmt/format.h>
#include <cmath>

#include "cli/option_parsing.hpp"
#include "render/render_scene.hpp"

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

std::unique_ptr<ShadowCache> make_cache(const RenderScene& scene, double pitch, const CacheCommandOptions& o) {
  if (!cache_enabled(o)) return nullptr;
  ShadowCacheOptions so;
  so.cell_size = o.cell * pitch;
  so.memory_limit_bytes = static_cast<uint64_t>(o.memory_mib * 1048576.0);
  return std::make_unique<ShadowCache>(scene, so);
}

std::string cache_summary(const ShadowCache& cache, const RayCounts& r, const CacheCommandOptions& o) {
  const double q = static_cast<double>(std::max<uint64_t>(1, r.shadow_queries()));
  const auto& cells = cache.cells();
  return fmt::format(
      "cache      {} cells of {:.4g} units, {:.1f} MiB (bound {:g} MiB){}; shadow queries {}: {:.1f}% by cells, "
      "{:.1f}% traced; {} sample rays\n",
      cells.slot_count(), cells.cell_size(), cache.bytes() / 1048576.0, o.memory_mib,
      cells.uncovered_primitives() ? fmt::format(", {} primitives uncovered", cells.uncovered_primitives()) : "",
      r.shadow_queries(), 100.0 * r.shadow_cached / q, 100.0 * r.shadow / q,
      r.cache_samples);
}

}  // namespace holoray::cli
