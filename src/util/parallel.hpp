// holoray/util: the one parallel loop every layer uses (oneTBB; plain
// std::threads in the ThreadSanitizer build, HOLORAY_STD_THREADS).
#pragma once

#include <functional>

namespace holoray {

/// Runs fn(k) for k in [0, n) on `threads` threads (0: all cores), each k
/// once, in no set order; the first exception fn throws stops the loop and
/// is rethrown on the calling thread.
void parallel_for_n(int n, int threads, const std::function<void(int)>& fn);

}  // namespace holoray
