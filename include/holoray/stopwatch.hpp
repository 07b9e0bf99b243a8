// holoray public API: wall-clock seconds, the one clock every timing in the
// library's results and the front ends' summaries and reports reads.
#pragma once

#include <chrono>

namespace holoray {

using Clock = std::chrono::steady_clock;

/// Seconds elapsed since `start` (steady clock: never goes back).
inline double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace holoray
