#include "cluster/group_dealer.hpp"

#include <chrono>
#include <mutex>
#include <thread>

#include "cluster/group_scheduler.hpp"

#ifdef HOLORAY_WITH_MPI
#include <mpi.h>
#endif

namespace holoray::cluster {

namespace {
using Clock = std::chrono::steady_clock;
[[maybe_unused]] constexpr int kRequestTag = 7101, kReplyTag = 7102;
}  // namespace

struct GroupDealer::State {
  const World& world;
  GroupScheduler scheduler;
  std::mutex mutex;  // the scheduler, between rank 0's main and helper threads
  std::thread helper;
  Clock::time_point last = Clock::now();
  bool stopping = false;
  bool told_done = false;  // this rank got "nothing left": it asks no more
  DealStats stats;
  State(const World& w, std::vector<double> weights) : world(w), scheduler(std::move(weights), w.size()) {}

  std::optional<size_t> deal(int rank, double seconds, bool stop) {
    std::lock_guard lock(mutex);
    if (stop) scheduler.stop();
    const auto g = scheduler.next(rank, seconds);
    if (g) ++stats.groups_dealt;
    return g;
  }

#ifdef HOLORAY_WITH_MPI
  // Rank 0's helper: answers requests until every other rank has been told
  // "nothing left". It polls rather than blocking in MPI_Recv, because a
  // blocked receive spins a core that the renderer needs.
  void serve() {
    int finished = 0;
    while (finished < world.size() - 1) {
      int flag = 0;
      MPI_Status st;
      MPI_Iprobe(MPI_ANY_SOURCE, kRequestTag, MPI_COMM_WORLD, &flag, &st);
      if (!flag) {
        std::this_thread::sleep_for(std::chrono::microseconds(200));
        continue;
      }
      double request[2];  // seconds of the finished group, stop flag
      MPI_Recv(request, 2, MPI_DOUBLE, st.MPI_SOURCE, kRequestTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      const auto g = deal(st.MPI_SOURCE, request[0], request[1] != 0);
      const int64_t reply = g ? static_cast<int64_t>(*g) : -1;
      MPI_Send(&reply, 1, MPI_INT64_T, st.MPI_SOURCE, kReplyTag, MPI_COMM_WORLD);
      stats.request_bytes += sizeof request + sizeof reply;
      if (!g) ++finished;
    }
  }
#endif
};

GroupDealer::GroupDealer(const World& world, std::vector<double> weights)
    : state_(std::make_unique<State>(world, std::move(weights))) {
#ifdef HOLORAY_WITH_MPI
  if (world.distributed() && world.rank() == 0) state_->helper = std::thread([s = state_.get()] { s->serve(); });
#endif
}

GroupDealer::~GroupDealer() {
  if (state_->helper.joinable()) state_->helper.join();
}

std::optional<size_t> GroupDealer::next() {
  if (state_->told_done) return std::nullopt;
  const auto g = ask();
  state_->told_done = !g;
  return g;
}

std::optional<size_t> GroupDealer::ask() {
  const auto now = Clock::now();
  const double seconds = std::chrono::duration<double>(now - state_->last).count();
  state_->last = now;
  if (state_->world.rank() == 0) return state_->deal(0, seconds, state_->stopping);
#ifdef HOLORAY_WITH_MPI
  const double request[2] = {seconds, state_->stopping ? 1.0 : 0.0};
  int64_t reply = -1;
  MPI_Send(request, 2, MPI_DOUBLE, 0, kRequestTag, MPI_COMM_WORLD);
  MPI_Recv(&reply, 1, MPI_INT64_T, 0, kReplyTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  if (reply >= 0) return static_cast<size_t>(reply);
#endif
  return std::nullopt;
}

void GroupDealer::stop() { state_->stopping = true; }

DealStats GroupDealer::finish() {
  // A rank that stopped early (interrupted) has not been told "nothing
  // left" yet: one more request, flagged stopping, says so.
  next();
  if (state_->helper.joinable()) state_->helper.join();
  std::lock_guard lock(state_->mutex);
  state_->stats.unchained_starts = state_->scheduler.unchained_starts();
  state_->stats.steals = state_->scheduler.steals();
  return state_->stats;
}

}  // namespace holoray::cluster
