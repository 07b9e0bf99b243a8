// holoray/python: long C++ work off the interpreter. The work runs on a
// thread of its own, the GIL released; the calling thread waits in slices of
// 50 ms, and at each takes the GIL to run Python's signal handlers (Ctrl-C
// raises KeyboardInterrupt there: the work is asked to stop and joined before
// it propagates) and `tick` (progress callbacks run on the calling thread).
#pragma once

#include <pybind11/pybind11.h>

#include <chrono>
#include <condition_variable>
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

/// Runs work(stop) on a new thread and waits for it as above; returns its
/// value or rethrows its exception. `tick` (may be empty) runs with the GIL
/// held after each slice and once more at the end; an exception from it (or
/// a signal's) stops the work, joins it and propagates.
template <class R>
R run_off_interpreter(const std::function<R(std::stop_token)>& work, Waker& waker, const std::function<void()>& tick) {
  std::stop_source stop;
  std::optional<R> value;
  std::exception_ptr failure;
  bool finished = false;
  std::mutex done_mutex;
  std::thread thread([&] {
    try {
      value.emplace(work(stop.get_token()));
    } catch (...) {
      failure = std::current_exception();
    }
    { const std::lock_guard lock(done_mutex); finished = true; }
    waker.wake();
  });
  // Every way out joins the thread first: nothing of the work outlives the call.
  auto stop_and_join = [&] {
    stop.request_stop();
    py::gil_scoped_release nogil;
    thread.join();
  };
  try {
    for (;;) {
      {
        py::gil_scoped_release nogil;
        waker.wait(std::chrono::milliseconds(50));
      }
      bool done;
      { const std::lock_guard lock(done_mutex); done = finished; }
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
      if (tick) tick();
      if (done) break;
    }
  } catch (...) {
    stop_and_join();
    throw;
  }
  {
    py::gil_scoped_release nogil;
    thread.join();
  }
  if (failure) std::rethrow_exception(failure);
  return std::move(*value);
}

}  // namespace holoray::python
