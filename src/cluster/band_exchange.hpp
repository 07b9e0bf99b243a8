// holoray/cluster: the bands of a still rendered over MPI ranks, streamed to
// rank 0 in order (issue 15, giant stills), which writes them to the file as
// they come (api::ImageWriter). No rank holds the whole image: each
// holds its own bands (1/N of it), rank 0 one band more.
#pragma once

#include <functional>
#include <vector>

#include "cluster/mpi_world.hpp"
#include "cluster/row_bands.hpp"
#include "holoray/render.hpp"

namespace holoray::cluster {

/// Collective. `mine[k]` is the render of this rank's k-th band of
/// `bands` (bands where rank == world.rank(), in order). On rank 0, calls
/// `sink(band, buffers)` for every band in order, top to bottom (its own from
/// `mine`, the others as they are received, one at a time, so rank 0 holds
/// its own bands and one more, never the whole image); elsewhere sends its
/// bands. Bytes sent over MPI are added to `bytes`.
void stream_bands(const World& world, const std::vector<RowBand>& bands, const std::vector<api::Result>& mine,
                  int width, const api::Aovs& aovs, const std::function<void(const RowBand&, const api::Result&)>& sink,
                  double& bytes);

}  // namespace holoray::cluster
