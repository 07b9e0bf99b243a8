// holoray/cluster: an EIA cut into bands of whole lens rows for `mpirun
// holoray render` (issue 15, giant stills). Pure arithmetic, no MPI.
#pragma once

#include <vector>

namespace holoray {

/// Pixel rows [y0, y1) of the EIA, rendered by `rank`.
struct RowBand {
  int y0 = 0, y1 = 0, rank = 0;
};

/// The rows of an EIA `height` pixels tall, with `pixels_per_lens` rows per
/// lens row, as bands of whole lens rows: `bands_per_rank` per rank (fewer
/// when there are fewer lens rows), dealt round robin so that each rank gets
/// some of the top, the middle and the bottom (an EIA's cost varies down it:
/// sky above, the floor's shadow rays below). Bands cover every row once, in
/// order. Throws std::invalid_argument for sizes < 1.
std::vector<RowBand> row_bands(int height, int pixels_per_lens, int ranks, int bands_per_rank = 4);

}  // namespace holoray
