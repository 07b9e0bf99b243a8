// holoray/render: ray counts by kind, the SPD's "useful counts" (nff-notes §10.13).
#pragma once

#include <cstdint>

namespace holoray {

struct RayCounts {
  uint64_t eye = 0;        ///< primary rays traced (pixels whose line crosses the scene bounds)
  uint64_t shadow = 0;
  uint64_t reflected = 0;  ///< mirror rays, and total-internal-reflection rays
  uint64_t refracted = 0;

  uint64_t total() const { return eye + shadow + reflected + refracted; }
  RayCounts& operator+=(const RayCounts& o) {
    eye += o.eye;
    shadow += o.shadow;
    reflected += o.reflected;
    refracted += o.refracted;
    return *this;
  }
};

}  // namespace holoray
