#include "util/parallel.hpp"

#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace holoray {

#ifdef HOLORAY_STD_THREADS
// The ThreadSanitizer build (scripts/sanitize.sh thread): oneTBB is not
// instrumented, so TSan cannot see the hand-off of work to its workers and
// would either report false races or, suppressed, hide real ones in our
// lambdas. Plain std::threads pulling indices from an atomic counter give TSan
// every happens-before edge; the per-index work is the same as with oneTBB.
void parallel_for_n(int n, int threads, const std::function<void(int)>& fn) {
  const int workers = std::clamp(threads > 0 ? threads : static_cast<int>(std::thread::hardware_concurrency()), 1, std::max(1, n));
  std::atomic<int> next{0};
  std::mutex failure_lock;
  std::exception_ptr failure;  // the first exception, rethrown like oneTBB does
  auto work = [&] {
    try {
      for (int k = next.fetch_add(1); k < n; k = next.fetch_add(1)) fn(k);
    } catch (...) {
      next = n;
      const std::lock_guard lock(failure_lock);
      if (!failure) failure = std::current_exception();
    }
  };
  {
    std::vector<std::jthread> pool;
    for (int w = 1; w < workers; ++w) pool.emplace_back(work);
    work();
  }
  if (failure) std::rethrow_exception(failure);
}

void run_isolated(const std::function<void()>& fn) { fn(); }
#else
void parallel_for_n(int n, int threads, const std::function<void(int)>& fn) {
  auto run = [&] {
    tbb::parallel_for(tbb::blocked_range<int>(0, n, 1), [&](const tbb::blocked_range<int>& r) {
      for (int k = r.begin(); k != r.end(); ++k) fn(k);
    });
  };
  if (threads > 0) {
    tbb::task_arena arena(threads);
    arena.execute(run);
  } else {
    run();
  }
}

void run_isolated(const std::function<void()>& fn) { tbb::this_task_arena::isolate(fn); }
#endif

}  // namespace holoray
