#include "render/tiles.hpp"

#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <exception>
#include <mutex>
#include <numeric>
#include <thread>
#include <vector>

namespace holoray {

ElementalTiles::ElementalTiles(const LensArray& camera, TileOrder order, int y0, int y1, int min_lenses)
    : width_(camera.width()), height_((y1 < 0 ? camera.height() : y1) - y0), y0_(y0), order_(order) {
  const int P = camera.desc().pixels_per_lens;
  const int lenses_per_tile = std::max(min_lenses, static_cast<int>(std::lround(64.0 / P)));
  tile_w_ = tile_h_ = P * lenses_per_tile;
  tiles_x_ = (width_ + tile_w_ - 1) / tile_w_;
  tiles_y_ = (height_ + tile_h_ - 1) / tile_h_;
  if (order_ == TileOrder::strided) {
    stride_ = std::max(1, count() / 2 + 1);
    while (std::gcd(stride_, count()) != 1) ++stride_;
  }
}

TileRect ElementalTiles::rect(int k) const {
  const int n = count();
  const int tile = order_ == TileOrder::reversed ? n - 1 - k
                   : order_ == TileOrder::strided ? static_cast<int>(static_cast<int64_t>(k) * stride_ % n)
                                                  : k;
  const int x0 = (tile % tiles_x_) * tile_w_, y0 = (tile / tiles_x_) * tile_h_;
  return {x0, y0_ + y0, std::min(width_, x0 + tile_w_), y0_ + std::min(height_, y0 + tile_h_)};
}

int packet_order(const TileRect& b, PixelXY px[]) {
  int n = 0;
  for (int y4 = b.y0; y4 < b.y1; y4 += 4)
    for (int x4 = b.x0; x4 < b.x1; x4 += 4)
      for (int j = y4; j < std::min(y4 + 4, b.y1); ++j)
        for (int i = x4; i < std::min(x4 + 4, b.x1); ++i) px[n++] = {i, j};
  return n;
}

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
#endif

void for_each_tile(const ElementalTiles& tiles, int threads, const std::function<void(int)>& fn) {
  parallel_for_n(tiles.count(), threads, fn);
}

}  // namespace holoray
