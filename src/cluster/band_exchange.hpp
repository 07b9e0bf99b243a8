// holoray/cluster: the bands of a still rendered over MPI ranks, brought to
// rank 0 (issue 15, giant stills). Rank 0 holds the whole image: the limit
// is the EIA (colour and AOVs, 4-byte floats) in rank 0's memory, the other
// ranks hold only their own bands.
#pragma once

#include <vector>

#include "cluster/mpi_world.hpp"
#include "cluster/row_bands.hpp"
#include "render/renderer.hpp"

namespace holoray::cluster {

/// Collective. `mine[k]` are the buffers of this rank's k-th band of
/// `bands` (bands where rank == world.rank(), in order). On rank 0, returns
/// the whole width x height frame with every band in place (its own copied,
/// the others received); elsewhere sends its bands and returns empty
/// buffers. Bytes sent over MPI are added to `bytes`.
FrameBuffers gather_bands(const World& world, const std::vector<RowBand>& bands, std::vector<FrameBuffers>& mine,
                          int width, int height, const AovSet& aovs, double& bytes);

}  // namespace holoray::cluster
