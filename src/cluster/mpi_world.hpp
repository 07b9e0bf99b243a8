// holoray/cluster: this process's place in an `mpirun` launch (issue 15).
// MPI is optional (CMake's HOLORAY_MPI); built without it, World is always
// one rank and every call here is a no-op, so the commands read the same
// either way. Only the command line links this: the library never calls MPI.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace holoray::cluster {

/// True when this holoray was built with MPI.
bool built_with_mpi();

/// The number of processes a launcher started this one among, read from the
/// launchers' environment (OpenMPI's OMPI_COMM_WORLD_SIZE, MPICH's and
/// Slurm's PMI_SIZE); std::nullopt when not launched by one.
std::optional<int> launcher_world_size();

/// The ranks of the launch. MPI is initialised (MPI_THREAD_SERIALIZED: rank
/// 0 answers the others from a helper thread while its main thread renders,
/// never both at once) only when built with MPI and started by a launcher;
/// otherwise one rank of one. The destructor finalises.
class World {
 public:
  World(int& argc, char**& argv);
  /// One rank of one; MPI untouched.
  World() = default;
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }
  /// This rank among the ranks on its machine (MPI_COMM_TYPE_SHARED), from
  /// 0: which of the machine's GPUs it takes.
  int local_rank() const { return local_rank_; }
  bool distributed() const { return size_ > 1; }

  /// Collective: true when every rank reached this point ok. After a failed
  /// setup (bad option, unreadable scene, ...), the lowest failing rank
  /// prints `message` and every rank returns 1: one message, not N.
  bool agree(bool ok, const std::string& message) const;
  /// A command's error, reported once and its exit status (1) returned:
  /// before the work has `started`, through agree() (every rank returns 1,
  /// the message printed once); after, through abort() (the other ranks may
  /// be mid-frame: every rank stops).
  int fail(const std::string& message, bool started) const;
  /// Collective sums over the ranks, returned on every rank.
  double sum(double value) const;
  int64_t sum(int64_t value) const;
  /// Collective: every rank's `bytes`, concatenated in rank order, on rank
  /// 0 (empty elsewhere).
  std::vector<unsigned char> gather(const std::vector<unsigned char>& bytes) const;
  /// Collective: waits for every rank.
  void barrier() const;
  /// Prints `message` (with the rank when distributed) and ends every rank
  /// with `status` (MPI_Abort): an error in the middle of the work, where
  /// the other ranks cannot be told to stop otherwise.
  [[noreturn]] void abort(const std::string& message, int status = 1) const;

 private:
  int rank_ = 0, size_ = 1, local_rank_ = 0;
  bool initialised_ = false;
};

}  // namespace holoray::cluster
