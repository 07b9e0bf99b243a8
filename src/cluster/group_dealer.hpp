// holoray/cluster: frame groups dealt to the ranks of `mpirun holoray
// animate` (issue 15). Rank 0 keeps the GroupScheduler; a helper thread on
// rank 0 answers the other ranks' requests (a few bytes each, once per
// group) while its main thread renders like any other rank. One rank: the
// groups in order, no thread, no MPI.
#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <vector>

#include "cluster/mpi_world.hpp"

namespace holoray::cluster {

/// What the dealing cost, known on rank 0 once finish() returns.
struct DealStats {
  int groups_dealt = 0;
  int unchained_starts = 0;  ///< groups not following their rank's previous one: extra keyframe traces
  int steals = 0;
  int64_t request_bytes = 0;  ///< bytes of requests and replies over MPI
};

class GroupDealer {
 public:
  /// `weights[g]`: the work in group g (frames left to render; 0: none).
  /// Collective: every rank constructs it with the same weights.
  GroupDealer(const World& world, std::vector<double> weights);
  ~GroupDealer();
  GroupDealer(const GroupDealer&) = delete;
  GroupDealer& operator=(const GroupDealer&) = delete;

  /// This rank's next group (SequenceOptions::next_group); the time since the
  /// previous call is the cost of the group it finished. nullopt: done.
  std::optional<size_t> next();
  /// This rank stops early (SIGINT, SIGTERM): no rank is given another group.
  void stop();
  /// Collective, after this rank's last next(): rank 0 waits until every
  /// rank has been told there is nothing left.
  DealStats finish();

 private:
  std::optional<size_t> ask();
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace holoray::cluster
