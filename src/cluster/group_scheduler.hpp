// holoray/cluster: dynamic load balancing of a shot's frame groups over
// workers (issue 15). Pure bookkeeping, no MPI: rank 0 of `mpirun holoray
// animate` runs one for every rank; tests drive it directly.
//
// Each worker starts with one contiguous run of groups, split by weight, and
// walks it in frame order, so that every group after its first starts at the
// keyframe the previous one ended on (reuse stays inside a worker, and that
// keyframe is traced once). A worker whose run is used up takes the back half
// of the run with the most predicted seconds left (work stealing): the cut
// costs one keyframe traced twice, once by each side, and nothing else: no
// point image crosses the network and no rank waits on another. (Sent over
// TCP, a point image moves only when its sender next calls MPI, once per
// group: the receiver waited 249 ms where tracing takes 66 ms;
// bench/mpi_results.md.) Predicted seconds = weight left times
// the owner's measured seconds per weight unit on its latest group (frame
// costs drift along a shot: the tree scene's frames cost 20x the teapot's).
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

namespace holoray {

class GroupScheduler {
 public:
  /// `weights[g]`: the work in group g, e.g. frames left to render (0: none,
  /// never handed out); `workers` >= 1. Throws std::invalid_argument for a
  /// negative weight or no workers.
  GroupScheduler(std::vector<double> weights, int workers);

  /// The next group for `worker`, which finished the group it was last given
  /// (if any) in `seconds`; nullopt when nothing is left anywhere, or after
  /// stop(). Not thread-safe: one caller at a time.
  std::optional<size_t> next(int worker, double seconds);

  /// Hands out nothing more (a rank was interrupted).
  void stop() { stopped_ = true; }

  /// Groups handed out, other than group 0, that did not follow on from the
  /// same worker's previous group: each costs its first keyframe traced a
  /// second time (the previous group's owner traces it too), the price of
  /// the balance.
  int unchained_starts() const { return unchained_; }
  /// Runs taken from another worker.
  int steals() const { return steals_; }

 private:
  struct Worker {
    size_t next = 0, end = 0;         // its run [next, end)
    std::optional<size_t> current;    // the group it is rendering
    double seconds_per_weight = -1;   // measured on its latest group; < 0: none yet
  };
  double weight_left(const Worker& w) const;
  double rate(const Worker& w) const;
  void skip_empty(Worker& w) const;

  std::vector<double> weights_;
  std::vector<Worker> workers_;
  double measured_seconds_ = 0, measured_weight_ = 0;
  int unchained_ = 0, steals_ = 0;
  bool stopped_ = false;
};

}  // namespace holoray
