#include "cluster/mpi_world.hpp"

#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <string_view>

#ifdef HOLORAY_WITH_MPI
#include <mpi.h>
#endif

namespace holoray::cluster {

std::optional<int> launcher_world_size() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"}) {
    const char* v = std::getenv(name);
    if (!v) continue;
    int n = 0;
    const std::string_view s(v);
    if (std::from_chars(s.data(), s.data() + s.size(), n).ec == std::errc() && n >= 1) return n;
  }
  return std::nullopt;
}

bool built_with_mpi() {
#ifdef HOLORAY_WITH_MPI
  return true;
#else
  return false;
#endif
}

World::World([[maybe_unused]] int& argc, [[maybe_unused]] char**& argv) {
#ifdef HOLORAY_WITH_MPI
  if (!launcher_world_size()) return;
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_SERIALIZED, &provided);
  initialised_ = true;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  MPI_Comm node;
  MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, rank_, MPI_INFO_NULL, &node);
  MPI_Comm_rank(node, &local_rank_);
  MPI_Comm_free(&node);
  if (provided < MPI_THREAD_SERIALIZED && size_ > 1) {
    if (rank_ == 0) std::fprintf(stderr, "holoray: error: this MPI library does not allow calls from a helper thread (MPI_THREAD_SERIALIZED)\n");
    MPI_Abort(MPI_COMM_WORLD, 1);
  }
#endif
}

World::~World() {
#ifdef HOLORAY_WITH_MPI
  if (initialised_) MPI_Finalize();
#endif
}

bool World::agree(bool ok, [[maybe_unused]] const std::string& message) const {
  int first_failing = ok ? size_ : rank_;
#ifdef HOLORAY_WITH_MPI
  if (initialised_) MPI_Allreduce(MPI_IN_PLACE, &first_failing, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
#endif
  if (first_failing == rank_ && !message.empty()) std::fprintf(stderr, "%s\n", message.c_str());
  return first_failing == size_;
}

int World::fail(const std::string& message, bool started) const {
  if (started && distributed()) abort(message);
  agree(false, message);
  return 1;
}

double World::sum(double value) const {
#ifdef HOLORAY_WITH_MPI
  if (initialised_) MPI_Allreduce(MPI_IN_PLACE, &value, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
#endif
  return value;
}

int64_t World::sum(int64_t value) const {
#ifdef HOLORAY_WITH_MPI
  if (initialised_) MPI_Allreduce(MPI_IN_PLACE, &value, 1, MPI_INT64_T, MPI_SUM, MPI_COMM_WORLD);
#endif
  return value;
}

std::vector<unsigned char> World::gather(const std::vector<unsigned char>& bytes) const {
#ifdef HOLORAY_WITH_MPI
  if (initialised_) {
    const int mine = static_cast<int>(bytes.size());
    std::vector<int> counts(rank_ == 0 ? size_ : 0), offsets(rank_ == 0 ? size_ : 0);
    MPI_Gather(&mine, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
    std::vector<unsigned char> all;
    if (rank_ == 0) {
      long long total = 0;
      for (int r = 0; r < size_; ++r) offsets[r] = static_cast<int>(total), total += counts[r];
      all.resize(static_cast<size_t>(total));
    }
    MPI_Gatherv(bytes.data(), mine, MPI_UNSIGNED_CHAR, all.data(), counts.data(), offsets.data(), MPI_UNSIGNED_CHAR, 0,
                MPI_COMM_WORLD);
    return all;
  }
#endif
  return bytes;
}

void World::barrier() const {
#ifdef HOLORAY_WITH_MPI
  if (initialised_) MPI_Barrier(MPI_COMM_WORLD);
#endif
}

void World::abort(const std::string& message, int status) const {
  if (distributed()) std::fprintf(stderr, "%s (rank %d of %d; stopping every rank)\n", message.c_str(), rank_, size_);
  else std::fprintf(stderr, "%s\n", message.c_str());
  std::fflush(stderr);
#ifdef HOLORAY_WITH_MPI
  if (initialised_) MPI_Abort(MPI_COMM_WORLD, status);
#endif
  std::exit(status);
}

}  // namespace holoray::cluster
