#include "cluster/band_exchange.hpp"

#include <algorithm>

#ifdef HOLORAY_WITH_MPI
#include <mpi.h>
#endif

namespace holoray::cluster {

namespace {

// The planes of a band that carry data, in a fixed order.
template <class Band>  // api::Result or const api::Result
auto planes(Band& r) {
  std::vector<decltype(&r.colour)> p;
  for (auto* b : {&r.colour, &r.albedo, &r.depth, &r.normal, &r.id})
    if (!b->empty()) p.push_back(b);
  return p;
}

// The planes of a band of `rows` rows, as the renderer gives them: colour
// and the requested AOVs.
api::Result allocate_band(int width, int rows, const api::Aovs& aovs) {
  api::Result r;
  r.colour = api::Image(width, rows, 3);
  if (aovs.albedo) r.albedo = api::Image(width, rows, 3);
  if (aovs.depth) r.depth = api::Image(width, rows, 1);
  if (aovs.normal) r.normal = api::Image(width, rows, 3);
  if (aovs.id) r.id = api::Image(width, rows, 1);
  return r;
}

#ifdef HOLORAY_WITH_MPI
constexpr int kBandTag = 7200;
// MPI counts are ints: large bands go in pieces of at most 2^30 floats.
constexpr size_t kPiece = size_t{1} << 30;
#endif

}  // namespace

void stream_bands(const World& world, const std::vector<RowBand>& bands, const std::vector<api::Result>& mine,
                  int width, const api::Aovs& aovs, const std::function<void(const RowBand&, const api::Result&)>& sink,
                  [[maybe_unused]] double& bytes) {
  size_t own = 0;
  for (const RowBand& band : bands) {
    if (band.rank == world.rank()) {
      const api::Result& b = mine.at(own++);
      if (world.rank() == 0) {
        sink(band, b);
        continue;
      }
#ifdef HOLORAY_WITH_MPI
      for (const api::Image* plane : planes(b))
        for (size_t at = 0; at < plane->size(); at += kPiece) {
          const size_t n = std::min(kPiece, plane->size() - at);
          MPI_Send(plane->data() + at, static_cast<int>(n), MPI_FLOAT, 0, kBandTag, MPI_COMM_WORLD);
          bytes += static_cast<double>(n) * sizeof(float);
        }
#endif
      continue;
    }
    if (world.rank() != 0) continue;
    api::Result received = allocate_band(width, band.y1 - band.y0, aovs);
#ifdef HOLORAY_WITH_MPI
    for (api::Image* plane : planes(received)) {
      float* start = plane->data();
      for (size_t at = 0; at < plane->size(); at += kPiece) {
        const size_t n = std::min(kPiece, plane->size() - at);
        MPI_Recv(start + at, static_cast<int>(n), MPI_FLOAT, band.rank, kBandTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      }
    }
#endif
    sink(band, received);
  }
}

}  // namespace holoray::cluster
