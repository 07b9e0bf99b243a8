// holoray/render: ray counts by kind, the SPD's "useful counts" (nff-notes §10.13),
// and what the shadow cache (render/shadow_cache.hpp) answered instead.
#pragma once

#include <cstdint>

namespace holoray {

struct RayCounts {
  uint64_t eye = 0;        ///< primary rays traced (pixels whose line crosses the scene bounds)
  uint64_t shadow = 0;     ///< shadow rays traced through the BVH
  uint64_t reflected = 0;  ///< mirror rays, and total-internal-reflection rays
  uint64_t refracted = 0;
  /// Shadow cache: shadow queries answered by a whole cell (no ray), and the
  /// sample rays that classified cells (traced through the BVH).
  uint64_t shadow_cached = 0, cache_samples = 0;

  /// Rays traced through the BVH.
  uint64_t total() const { return eye + shadow + reflected + refracted + cache_samples; }
  /// Shadow questions asked, however answered.
  uint64_t shadow_queries() const { return shadow + shadow_cached; }
  RayCounts& operator+=(const RayCounts& o) {
    eye += o.eye;
    shadow += o.shadow;
    reflected += o.reflected;
    refracted += o.refracted;
    shadow_cached += o.shadow_cached;
    cache_samples += o.cache_samples;
    return *this;
  }
};

}  // namespace holoray
