#include "cluster/group_scheduler.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace holoray {

GroupScheduler::GroupScheduler(std::vector<double> weights, int workers) : weights_(std::move(weights)) {
  if (workers < 1) throw std::invalid_argument(fmt::format("the scheduler needs at least one worker, got {}", workers));
  double total = 0;
  for (double w : weights_) {
    if (!(w >= 0)) throw std::invalid_argument(fmt::format("a group's weight must be 0 or more, got {}", w));
    total += w;
  }
  // Contiguous runs of about equal weight: worker r's run ends where the
  // running weight passes (r + 1) / workers of the total.
  workers_.resize(static_cast<size_t>(workers));
  size_t g = 0;
  double sum = 0;
  for (int r = 0; r < workers; ++r) {
    Worker& w = workers_[static_cast<size_t>(r)];
    w.next = g;
    const double target = total * (r + 1) / workers;
    while (g < weights_.size() && (r + 1 == workers || sum + weights_[g] / 2 <= target)) sum += weights_[g++];
    w.end = g;
  }
}

void GroupScheduler::skip_empty(Worker& w) const {
  while (w.next < w.end && weights_[w.next] == 0) ++w.next;
}

double GroupScheduler::weight_left(const Worker& w) const {
  double sum = 0;
  for (size_t g = w.next; g < w.end; ++g) sum += weights_[g];
  return sum;
}

double GroupScheduler::rate(const Worker& w) const {
  if (w.seconds_per_weight >= 0) return w.seconds_per_weight;
  return measured_weight_ > 0 ? measured_seconds_ / measured_weight_ : 1.0;
}

std::optional<size_t> GroupScheduler::next(int worker, double seconds) {
  Worker& me = workers_.at(static_cast<size_t>(worker));
  std::optional<size_t> previous = me.current;
  if (me.current && weights_[*me.current] > 0) {
    me.seconds_per_weight = seconds / weights_[*me.current];
    measured_seconds_ += seconds;
    measured_weight_ += weights_[*me.current];
  }
  me.current.reset();
  if (stopped_) return std::nullopt;
  skip_empty(me);
  if (me.next >= me.end) {
    // Steal the back half (by weight) of the run with the most predicted
    // seconds left; the victim keeps the front, which continues its chain.
    Worker* victim = nullptr;
    double most = 0;
    for (Worker& w : workers_) {
      skip_empty(w);
      const double left = weight_left(w) * rate(w);
      if (&w != &me && w.next < w.end && left > most) most = left, victim = &w;
    }
    if (!victim) return std::nullopt;
    // Groups without work at the back of the run are never dealt: drop
    // them, so that the part taken starts and ends with work.
    while (weights_[victim->end - 1] == 0) --victim->end;
    // The last group of a run goes whole: its owner is busy with another.
    size_t cut = victim->next;
    if (victim->end - victim->next > 1) {
      const double half = weight_left(*victim) / 2;
      double taken = 0;
      cut = victim->end;
      while (cut > victim->next + 1 && taken + weights_[cut - 1] / 2 <= half) taken += weights_[--cut];
    }
    me.next = cut;
    me.end = victim->end;
    victim->end = cut;
    ++steals_;
    skip_empty(me);
  }
  const size_t g = me.next++;
  // Group 0 starts the shot: its first keyframe is nobody else's.
  if (g != 0 && (!previous || *previous + 1 != g)) ++unchained_;
  me.current = g;
  return g;
}

}  // namespace holoray
