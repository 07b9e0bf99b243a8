// holoray/cli: the shadow-cache options shared by `render` and `animate`
// (issue 12; api::ShadowCacheOptions): --cache, --cache-cell, --cache-memory.
#pragma once

#include <CLI/CLI.hpp>
#include <memory>
#include <string>

#include "holoray/render.hpp"

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

/// The options as the API takes them (checked as cache_enabled checks).
api::ShadowCacheOptions cache_options(const CacheCommandOptions& o);

}  // namespace holoray::cli
