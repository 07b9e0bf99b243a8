#include "render/tiles.hpp"

#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>

namespace holoray {

ElementalTiles::ElementalTiles(const LensArray& camera, TileOrder order)
    : width_(camera.width()), height_(camera.height()), order_(order) {
  const int P = camera.desc().pixels_per_lens;
  const int lenses_per_tile = std::max(1, static_cast<int>(std::lround(64.0 / P)));
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
  return {x0, y0, std::min(width_, x0 + tile_w_), std::min(height_, y0 + tile_h_)};
}

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

void for_each_tile(const ElementalTiles& tiles, int threads, const std::function<void(int)>& fn) {
  parallel_for_n(tiles.count(), threads, fn);
}

}  // namespace holoray
