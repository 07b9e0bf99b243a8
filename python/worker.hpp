// holoray/python: long C++ work off the interpreter. The work runs on a
// worker thread, the GIL released; the calling thread waits in slices of
// 50 ms, and at each takes the GIL to run Python's signal handlers (Ctrl-C
// raises KeyboardInterrupt there: the work is asked to stop and waited for
// before it propagates) and `tick` (progress callbacks run on the calling thread).
#pragma once

#include <pybind11/pybind11.h>

#include <chrono>
#include <condition_variable>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <optional>
#include <stop_token>
#include <thread>

namespace holoray::python {

namespace py = pybind11;

/// Wakes the waiting thread before its slice ends (new progress, a frame).
class Waker {
 public:
  void wake() {
    { const std::lock_guard lock(mutex_); woken_ = true; }
    cv_.notify_all();
  }
  /// Waits up to `slice` or until woken; true when woken.
  bool wait(std::chrono::milliseconds slice) {
    std::unique_lock lock(mutex_);
    const bool w = cv_.wait_for(lock, slice, [&] { return woken_; });
    woken_ = false;
    return w;
  }

 private:
  std::mutex mutex_;
  std::condition_variable cv_;
  bool woken_ = false;
};

/// The threads the module's renders run on, kept for reuse. A thread that
/// has rendered carries per-thread state in oneTBB and Embree; a fresh
/// thread per render added about 9 KB of it for good on every render of a
/// busy machine (1,000 small renders: +9 MiB), a reused one adds none. Never
/// destroyed: idle workers wait until the process ends.
class WorkerPool {
 public:
  /// Runs `job`, then `done`, on an idle worker, or on a new one when none
  /// is idle. The worker counts as idle again before `done` runs, so a
  /// caller that waits for `done` and submits again finds it.
  static void submit(std::function<void()> job, std::function<void()> done) {
    static WorkerPool* pool = new WorkerPool;
    pool->push({std::move(job), std::move(done)});
  }

 private:
  struct Job {
    std::function<void()> work, done;
  };
  void push(Job job) {
    const std::lock_guard lock(mutex_);
    jobs_.push_back(std::move(job));
    if (idle_ >= static_cast<int>(jobs_.size())) cv_.notify_one();
    else std::thread([this] { loop(); }).detach();
  }
  void loop() {
    std::unique_lock lock(mutex_);
    ++idle_;
    for (;;) {
      cv_.wait(lock, [&] { return !jobs_.empty(); });
      --idle_;
      Job job = std::move(jobs_.front());
      jobs_.pop_front();
      lock.unlock();
      job.work();
      lock.lock();
      ++idle_;
      lock.unlock();
      job.done();
      lock.lock();
    }
  }
  std::mutex mutex_;
  std::condition_variable cv_;
  std::deque<Job> jobs_;
  int idle_ = 0;
};

/// Runs work(stop) on a worker (WorkerPool) and waits for it as above;
/// returns its value or rethrows its exception. `tick` (may be empty) runs
/// with the GIL held after each slice and once more at the end; an
/// exception from it (or a signal's) stops the work, waits for it to end and
/// propagates.
template <class R>
R run_off_interpreter(const std::function<R(std::stop_token)>& work, Waker& waker, const std::function<void()>& tick) {
  std::stop_source stop;
  std::optional<R> value;
  std::exception_ptr failure;
  bool finished = false;
  std::mutex done_mutex;
  std::condition_variable done_cv;
  WorkerPool::submit(
      [&] {
        try {
          value.emplace(work(stop.get_token()));
        } catch (...) {
          failure = std::current_exception();
        }
      },
      [&] {
        // All under the lock: the caller leaves (and its variables go) only
        // after taking it and seeing `finished`.
        const std::lock_guard lock(done_mutex);
        finished = true;
        done_cv.notify_all();
        waker.wake();
      });
  // Every way out waits for the work first: nothing of it outlives the call
  // (it refers to this frame's variables).
  auto wait_done = [&] {
    py::gil_scoped_release nogil;
    std::unique_lock lock(done_mutex);
    done_cv.wait(lock, [&] { return finished; });
  };
  try {
    for (;;) {
      {
        py::gil_scoped_release nogil;
        waker.wait(std::chrono::milliseconds(50));
      }
      bool done;
      {
        const std::lock_guard lock(done_mutex);
        done = finished;
      }
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
      if (tick) tick();
      if (done) break;
    }
  } catch (...) {
    stop.request_stop();
    wait_done();
    throw;
  }
  wait_done();
  if (failure) std::rethrow_exception(failure);
  return std::move(*value);
}

}  // namespace holoray::python
