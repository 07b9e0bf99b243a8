// holoray/cli: the shadow-cache options shared by `render` and `animate`
// (issue 12; render/shadow_cache.hpp): --cache, --cache-cell, --cache-memory.
#pragma once

#include <CLI/CLI.hpp>
#include <memory>
#include <string>

#include "render/ray_counts.hpp"
#include "render/shadow_cache.hpp"

namespace holoray::cli {

struct CacheCommandOptions {
  std::string cache = "off";  // not yet faster on the bench stills (README, "Shadow cache")
  double cell = 1;          ///< cell size in lens pitches
  double memory_mib = 512;  ///< bound on the cache's storage
};

/// Registers --cache, --cache-cell and --cache-memory on `cmd`.
void add_cache_options(CLI::App& cmd, CacheCommandOptions& o);

/// Checks the options (std::invalid_argument naming the option); true when
/// the cache is on.
bool cache_enabled(const CacheCommandOptions& o);

/// The cache for `scene`, cells of o.cell lens pitches (`pitch`, scene
/// units); null when --cache off. The caller attaches it to the scene
/// (RenderScene::set_shadow_cache) and keeps it alive while the scene renders.
std::unique_ptr<ShadowCache> make_cache(const RenderScene& scene, double pitch, const CacheCommandOptions& o);

/// One line for the render summary: cells, memory, how the shadow questions
/// were answered.
std::string cache_summary(const ShadowCache& cache, const RayCounts& rays, const CacheCommandOptions& o);

}  // namespace holoray::cli
