#include "cluster/row_bands.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

namespace holoray {

std::vector<RowBand> row_bands(int height, int pixels_per_lens, int ranks, int bands_per_rank) {
  if (height < 1 || pixels_per_lens < 1 || ranks < 1 || bands_per_rank < 1)
    throw std::invalid_argument(fmt::format("row bands need positive sizes, got height {}, {} px per lens, {} ranks, {} bands per rank",
                                            height, pixels_per_lens, ranks, bands_per_rank));
  const long long lens_rows = (height + pixels_per_lens - 1) / pixels_per_lens;
  const long long count = std::min<long long>(lens_rows, static_cast<long long>(ranks) * bands_per_rank);
  std::vector<RowBand> bands;
  for (long long b = 0; b < count; ++b) {
    const long long r0 = b * lens_rows / count, r1 = (b + 1) * lens_rows / count;
    bands.push_back({static_cast<int>(r0 * pixels_per_lens),
                     static_cast<int>(std::min<long long>(height, r1 * pixels_per_lens)), static_cast<int>(b % ranks)});
  }
  return bands;
}

}  // namespace holoray
