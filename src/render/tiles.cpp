#include "render/tiles.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
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

void for_each_tile(const ElementalTiles& tiles, int threads, const std::function<void(int)>& fn) {
  parallel_for_n(tiles.count(), threads, fn);
}

}  // namespace holoray
