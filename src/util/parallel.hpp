// holoray/util: the one parallel loop every layer uses (oneTBB; plain
// std::threads in the ThreadSanitizer build, HOLORAY_STD_THREADS).
#pragma once

#include <functional>

namespace holoray {

/// Runs fn(k) for k in [0, n) on `threads` threads (0: all cores), each k
/// once, in no set order; the first exception fn throws stops the loop and
/// is rethrown on the calling thread.
void parallel_for_n(int n, int threads, const std::function<void(int)>& fn);

/// Runs fn() so that, while it waits on parallel work of its own, the
/// calling thread takes no task of an enclosing loop (oneTBB's
/// this_task_arena::isolate): fn may then hold a lock that such a task
/// would take. Plain call in the std::threads build.
void run_isolated(const std::function<void()>& fn);

}  // namespace holoray
