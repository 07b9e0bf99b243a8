#include "cluster/band_exchange.hpp"

#include <algorithm>

#ifdef HOLORAY_WITH_MPI
#include <mpi.h>
#endif

namespace holoray::cluster {

namespace {

// The buffers of a frame that carry data, in a fixed order.
template <class Frame>  // FrameBuffers or const FrameBuffers
auto planes(Frame& fb) {
  std::vector<decltype(&fb.colour)> p;
  for (auto* b : {&fb.colour, &fb.albedo, &fb.depth, &fb.normal, &fb.id})
    if (!b->empty()) p.push_back(b);
  return p;
}

#ifdef HOLORAY_WITH_MPI
constexpr int kBandTag = 7200;
// MPI counts are ints: large bands go in pieces of at most 2^30 floats.
constexpr size_t kPiece = size_t{1} << 30;
#endif

}  // namespace

void stream_bands(const World& world, const std::vector<RowBand>& bands, const std::vector<FrameBuffers>& mine,
                  int width, const AovSet& aovs, const std::function<void(const RowBand&, const FrameBuffers&)>& sink,
                  [[maybe_unused]] double& bytes) {
  size_t own = 0;
  for (const RowBand& band : bands) {
    if (band.rank == world.rank()) {
      const FrameBuffers& b = mine.at(own++);
      if (world.rank() == 0) {
        sink(band, b);
        continue;
      }
#ifdef HOLORAY_WITH_MPI
      for (const ImageBuffer* plane : planes(b))
        for (size_t at = 0; at < plane->data.size(); at += kPiece) {
          const size_t n = std::min(kPiece, plane->data.size() - at);
          MPI_Send(plane->data.data() + at, static_cast<int>(n), MPI_FLOAT, 0, kBandTag, MPI_COMM_WORLD);
          bytes += static_cast<double>(n) * sizeof(float);
        }
#endif
      continue;
    }
    if (world.rank() != 0) continue;
    FrameBuffers received = allocate_frame(width, band.y1 - band.y0, aovs);
#ifdef HOLORAY_WITH_MPI
    for (ImageBuffer* plane : planes(received)) {
      float* start = plane->data.data();
      for (size_t at = 0; at < plane->data.size(); at += kPiece) {
        const size_t n = std::min(kPiece, plane->data.size() - at);
        MPI_Recv(start + at, static_cast<int>(n), MPI_FLOAT, band.rank, kBandTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      }
    }
#endif
    sink(band, received);
  }
}

}  // namespace holoray::cluster
