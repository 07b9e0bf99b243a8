#include "cluster/band_exchange.hpp"

#include <algorithm>
#include <climits>
#include <cstring>

#ifdef HOLORAY_WITH_MPI
#include <mpi.h>
#endif

namespace holoray::cluster {

namespace {

// The buffers of a frame that carry data, in a fixed order.
std::vector<ImageBuffer*> planes(FrameBuffers& fb) {
  std::vector<ImageBuffer*> p;
  for (ImageBuffer* b : {&fb.colour, &fb.albedo, &fb.depth, &fb.normal, &fb.id})
    if (!b->empty()) p.push_back(b);
  return p;
}

#ifdef HOLORAY_WITH_MPI
constexpr int kBandTag = 7200;
// MPI counts are ints: large bands go in pieces of at most 2^30 floats.
constexpr size_t kPiece = size_t{1} << 30;
#endif

}  // namespace

FrameBuffers gather_bands(const World& world, const std::vector<RowBand>& bands, std::vector<FrameBuffers>& mine,
                          int width, int height, const AovSet& aovs, double& bytes) {
  FrameBuffers whole;
  if (world.rank() == 0) whole = allocate_frame(width, height, aovs);
  size_t own = 0;
  for (const RowBand& band : bands) {
    if (band.rank == world.rank()) {
      std::vector<ImageBuffer*> src = planes(mine.at(own++));
      if (world.rank() == 0) {
        std::vector<ImageBuffer*> dst = planes(whole);
        for (size_t p = 0; p < src.size(); ++p)
          std::memcpy(dst[p]->at(0, band.y0), src[p]->data.data(), src[p]->data.size() * sizeof(float));
        continue;
      }
#ifdef HOLORAY_WITH_MPI
      for (ImageBuffer* b : src)
        for (size_t at = 0; at < b->data.size(); at += kPiece) {
          const size_t n = std::min(kPiece, b->data.size() - at);
          MPI_Send(b->data.data() + at, static_cast<int>(n), MPI_FLOAT, 0, kBandTag, MPI_COMM_WORLD);
          bytes += static_cast<double>(n) * sizeof(float);
        }
#endif
      continue;
    }
#ifdef HOLORAY_WITH_MPI
    if (world.rank() != 0) continue;
    // Straight into place: a band is whole rows, contiguous in every plane.
    for (ImageBuffer* b : planes(whole)) {
      float* start = b->at(0, band.y0);
      const size_t count = static_cast<size_t>(band.y1 - band.y0) * width * b->channels;
      for (size_t at = 0; at < count; at += kPiece) {
        const size_t n = std::min(kPiece, count - at);
        MPI_Recv(start + at, static_cast<int>(n), MPI_FLOAT, band.rank, kBandTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      }
    }
#endif
  }
  return whole;
}

}  // namespace holoray::cluster
