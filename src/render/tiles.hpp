// holoray/render: the tile schedule shared by every per-pixel pass (full
// tracing, reprojection, filling): tiles of whole elemental images, about
// 4096 pixels each, run on oneTBB. Every pixel is computed independently of
// the schedule, so results do not depend on the thread count.
#pragma once

#include <algorithm>
#include <functional>
#include <vector>

#include "camera/lens_array.hpp"
#include "util/parallel.hpp"

namespace holoray {

/// Pixel rectangle [x0, x1) x [y0, y1).
struct TileRect {
  int x0, y0, x1, y1;
};

/// The order tiles are handed out in. Results never depend on it; the other
/// orders exist so that tests can prove that (issue 5, determinism).
enum class TileOrder {
  row_major,  ///< left to right, top to bottom
  reversed,   ///< bottom-right first
  strided,    ///< a fixed permutation far from both (tile k -> k * stride mod n)
};

/// The EIA cut into tiles of whole elemental images (square grid; hex and
/// lenticular tiles are P-aligned pixel blocks).
class ElementalTiles {
 public:
  /// Tiles of rows [y0, y1) only (y1 < 0: to the bottom), cut from y0: a
  /// band of the EIA (mpirun render); rect() stays in EIA pixels. Tiles are
  /// about 64 pixels across and at least `min_lenses` lenses.
  explicit ElementalTiles(const LensArray& camera, TileOrder order = TileOrder::row_major, int y0 = 0, int y1 = -1,
                          int min_lenses = 1);
  int count() const { return tiles_x_ * tiles_y_; }
  /// The rectangle of the tile handed out k-th, k in [0, count()).
  TileRect rect(int k) const;

 private:
  int width_, height_, y0_, tile_w_, tile_h_, tiles_x_, tiles_y_;
  TileOrder order_;
  int stride_ = 1;  // coprime with count()
};

/// A pixel (i, j): column, row.
struct PixelXY {
  int i, j;
};

/// The pixels of `block` (at most P x P, within one elemental image) in 4x4
/// micro-tiles, row-major inside each, so that each run of 16 is a compact
/// patch whose rays are the most alike (TraceStyle::packet). Writes them to
/// px (room for the block's area) and returns the count.
int packet_order(const TileRect& block, PixelXY px[]);

/// Lenses across (and down) a sub-aperture packet: 4x4 lenses, 16 rays.
inline constexpr int kSubapertureLenses = 4;

/// The 16-ray packets of a P-aligned tile, in order: fn(px, n) with n <= 16
/// pixels. Sub-aperture packets (`subaperture`) take one pixel (u, v) of
/// each of 4x4 neighbouring lenses, whose lines are parallel on a square
/// grid; otherwise packet_order's 4x4 pixels of one lens. Fewer than 16 only
/// where the tile or the lens ends.
template <class Fn>
void for_each_packet_of(const TileRect& r, int P, bool subaperture, Fn&& fn) {
  if (!subaperture) {
    thread_local std::vector<PixelXY> px;
    px.resize(static_cast<size_t>(P) * P);
    for (int by = r.y0; by < r.y1; by += P)
      for (int bx = r.x0; bx < r.x1; bx += P) {
        const int m = packet_order({bx, by, std::min(bx + P, r.x1), std::min(by + P, r.y1)}, px.data());
        for (int start = 0; start < m; start += 16) fn(px.data() + start, std::min(16, m - start));
      }
    return;
  }
  constexpr int L = kSubapertureLenses;
  for (int gy = r.y0; gy < r.y1; gy += L * P)
    for (int gx = r.x0; gx < r.x1; gx += L * P)
      for (int dv = 0; dv < P; ++dv)
        for (int du = 0; du < P; ++du) {
          PixelXY px[16];
          int m = 0;
          for (int ly = 0; ly < L; ++ly)
            for (int lx = 0; lx < L; ++lx) {
              const int i = gx + lx * P + du, j = gy + ly * P + dv;
              if (i < r.x1 && j < r.y1) px[m++] = {i, j};
            }
          if (m > 0) fn(px, m);
        }
}

/// Runs fn(tile) for every tile on `threads` threads (0: all cores).
void for_each_tile(const ElementalTiles& tiles, int threads, const std::function<void(int)>& fn);


}  // namespace holoray
