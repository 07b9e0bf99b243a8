// api::BackgroundWriter (include/holoray/image.hpp): one thread, one queue.
#include <fmt/format.h>

#include <chrono>
#include <condition_variable>
#include <deque>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "holoray/image.hpp"

namespace holoray::api {

struct BackgroundWriter::Queue {
  struct Job {
    std::string path;
    Image image;
    Encoding encoding;
    ExrCompression exr;
  };
  size_t depth;
  std::mutex mutex;
  std::condition_variable changed;  // a job queued or taken, a write done, closing
  std::deque<Job> jobs;
  bool writing = false, closing = false;
  std::exception_ptr error;
  double seconds = 0;
  std::thread thread;

  explicit Queue(size_t d) : depth(d), thread([this] { run(); }) {}

  void run() {
    std::unique_lock lock(mutex);
    for (;;) {
      changed.wait(lock, [&] { return closing || !jobs.empty(); });
      if (jobs.empty() || error) return;
      Job job = std::move(jobs.front());
      jobs.pop_front();
      writing = true;
      changed.notify_all();
      lock.unlock();
      const auto t0 = std::chrono::steady_clock::now();
      std::exception_ptr failed;
      try {
        write_image(job.path, job.image, job.encoding, job.exr);
      } catch (...) {
        failed = std::current_exception();
      }
      job.image = {};  // the samples go before the caller is told there is room
      lock.lock();
      seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      writing = false;
      if (failed) {
        error = failed;
        jobs.clear();
      }
      changed.notify_all();
      if (error) return;
    }
  }

  // Called with the lock held: every call after a failed write throws its error.
  void rethrow() const {
    if (error) std::rethrow_exception(error);
  }
};

BackgroundWriter::BackgroundWriter(int depth) {
  if (depth < 1) throw std::invalid_argument(fmt::format("BackgroundWriter: depth must be at least 1, got {}", depth));
  queue_ = std::make_unique<Queue>(size_t(depth));
}

BackgroundWriter::~BackgroundWriter() {
  {
    std::lock_guard lock(queue_->mutex);
    queue_->closing = true;
  }
  queue_->changed.notify_all();
  queue_->thread.join();
}

void BackgroundWriter::submit(std::string path, Image image, Encoding encoding, ExrCompression exr) {
  Queue& q = *queue_;
  std::unique_lock lock(q.mutex);
  q.changed.wait(lock, [&] { return q.error || q.jobs.size() < q.depth; });
  q.rethrow();
  q.jobs.push_back({std::move(path), std::move(image), encoding, exr});
  q.changed.notify_all();
}

void BackgroundWriter::finish() {
  Queue& q = *queue_;
  std::unique_lock lock(q.mutex);
  q.changed.wait(lock, [&] { return q.error || (q.jobs.empty() && !q.writing); });
  q.rethrow();
}

double BackgroundWriter::write_seconds() const {
  std::lock_guard lock(queue_->mutex);
  return queue_->seconds;
}

}  // namespace holoray::api
