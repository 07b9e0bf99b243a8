#include <pybind11/stl.h>

#include <condition_variable>
#include <deque>
#include <exception>
#include <mutex>
#include <thread>

#include "arrays.hpp"
#include "bindings.hpp"
#include "holoray/animate.hpp"
#include "worker.hpp"

namespace holoray::python {

namespace {

py::dict row_dict(const api::FrameRow& r) {
  py::dict d, rays;
  d["frame"] = r.frame;
  d["keyframe"] = r.keyframe;
  d["seconds"] = r.seconds;
  d["reference_seconds"] = r.reference_seconds;
  d["pixels"] = r.pixels;
  d["reprojected"] = r.reprojected;
  d["missed"] = r.missed;
  d["leaks"] = r.leaks;
  d["rejected"] = r.rejected;
  d["traced"] = r.traced;
  d["interpolated"] = r.interpolated;
  rays["eye"] = r.rays.eye;
  rays["shadow"] = r.rays.shadow;
  rays["reflected"] = r.rays.reflected;
  rays["refracted"] = r.rays.refracted;
  rays["total"] = r.rays.total();
  d["rays"] = rays;
  d["psnr"] = r.difference ? py::object(py::float_(r.difference->psnr())) : py::object(py::none());
  d["hold_psnr"] = r.hold ? py::object(py::float_(r.hold->psnr())) : py::object(py::none());
  d["copied_from"] = r.copied_from >= 0 ? py::object(py::int_(r.copied_from)) : py::object(py::none());
  d["rebuilt"] = r.rebuilt;
  return d;
}

// holoray.animate's keyword options, as `holoray animate`'s, underscored.
api::AnimateOptions options_of(const py::dict& kw) {
  api::AnimateOptions o;
  // The light keywords, as render()'s: gathered, then checked together.
  std::string integrator = "whitted";
  py::object environment = py::none();
  double environment_strength = 1, environment_rotation = 0;
  bool blender_principled = false;
  for (const auto& [key, value] : kw) {
    const std::string k = py::str(key);
    if (k == "integrator") integrator = py::str(value);
    else if (k == "environment") environment = py::reinterpret_borrow<py::object>(value);
    else if (k == "environment_strength") environment_strength = value.cast<double>();
    else if (k == "environment_rotation") environment_rotation = value.cast<double>();
    else if (k == "blender_principled") blender_principled = value.cast<bool>();
    else if (k == "seed") o.seed = checked_seed(value.cast<int64_t>());
    else if (k == "animated_seed") o.animated_seed = value.cast<bool>();
    else if (k == "method") {
      const std::string v = py::str(value);
      if (v == "full") o.method = api::Method::full;
      else if (v == "reproject") o.method = api::Method::reproject;
      else if (v == "reverse") o.method = api::Method::reverse;
      else throw py::value_error("method: expected full, reproject or reverse, got '" + v + "'");
    } else if (k == "keyframe_interval") {
      if (py::isinstance<py::str>(value) && std::string(py::str(value)) == "auto") o.keyframe_interval = 0;
      else if (py::isinstance<py::int_>(value) && value.cast<int>() >= 1) o.keyframe_interval = value.cast<int>();
      else throw py::value_error("keyframe_interval: expected a whole number of frames, at least 1, or 'auto'");
    } else if (k == "keyframe_motion") o.keyframe_motion = value.cast<double>();
    else if (k == "max_keyframe_interval") o.max_keyframe_interval = value.cast<int>();
    else if (k == "reuse") o.reuse = py::str(value);
    else if (k == "fill") o.fill = py::str(value);
    else if (k == "reach") o.reach = py::str(value);
    else if (k == "leak_check") o.leak_check = value.cast<bool>();
    else if (k == "rebuild_above") o.rebuild_above_percent = value.cast<double>();
    else if (k == "threads") o.threads = value.is_none() ? 0 : value.cast<int>();
    else if (k == "camera") { if (!value.is_none()) o.camera = camera_of(value, "camera"); }
    else if (k == "report") o.reference = value.cast<bool>();
    else if (k == "cache") o.cache.enabled = value.cast<bool>();
    else if (k == "device") o.device = py::str(value);
    else if (k == "camera_name") o.load.camera_name = py::str(value);
    else if (k == "texture_path") {
      // One folder (a str or a path-like), or a sequence of them.
      const py::object fspath = py::module_::import("os").attr("fspath");
      const bool one = py::isinstance<py::str>(value) || py::hasattr(value, "__fspath__");
      const py::object dirs = one ? py::object(py::make_tuple(value)) : py::reinterpret_borrow<py::object>(value);
      for (const py::handle dir : dirs)
        o.load.texture_paths.push_back(py::str(fspath(dir)));
    }
    else if (k == "encoding") {
      const std::string v = py::str(value);
      if (v == "linear") o.encoding = api::Encoding::linear;
      else if (v == "srgb") o.encoding = api::Encoding::srgb;
      else if (v != "auto") throw py::value_error("encoding: expected linear, srgb or auto, got '" + v + "'");
    } else if (k == "frames") {
      if (py::isinstance<py::int_>(value)) {
        const int f = value.cast<int>();
        o.frames = std::array<int, 2>{f, f};
      } else if (py::isinstance<py::str>(value)) {
        const std::string t = py::str(value);
        const auto colon = t.find(':');
        try {
          o.frames = colon == std::string::npos ? std::array<int, 2>{std::stoi(t), std::stoi(t)}
                                                : std::array<int, 2>{std::stoi(t.substr(0, colon)), std::stoi(t.substr(colon + 1))};
        } catch (const std::exception&) {
          throw py::value_error("frames: expected 'A:B' (first and last frame, from 0) or N, got '" + t + "'");
        }
      } else {
        o.frames = value.cast<std::array<int, 2>>();
      }
    } else {
      throw py::type_error("animate() got an unexpected keyword argument '" + k + "'");
    }
  }
  const api::RenderOptions light =
      light_options(integrator, environment, environment_strength, environment_rotation, blender_principled, std::nullopt);
  o.integrator = light.integrator;
  o.environment = light.environment;
  o.blender_principled = light.blender_principled;
  return o;
}

struct Frame {
  int index;
  api::Image colour;
  api::FrameRow row;
};

// The frames of a shot as a Python iterator: the shot renders on a thread of
// its own, at most two frames ahead of the consumer.
class AnimationIterator {
 public:
  AnimationIterator(const std::string& shot, const py::dict& kw) {
    api::AnimateOptions o = options_of(kw);
    o.stop = [this] { return stop_.stop_requested(); };
    py::gil_scoped_release nogil;
    animation_ = std::make_unique<api::Animation>(shot, o);
  }
  ~AnimationIterator() { close(); }

  py::tuple next() {
    if (!started_) start();
    for (;;) {
      {
        std::unique_lock lock(mutex_);
        if (!queue_.empty()) {
          Frame f = std::move(queue_.front());
          queue_.pop_front();
          lock.unlock();
          space_.notify_all();
          return py::make_tuple(f.index, image_to_numpy(f.colour), row_dict(f.row));
        }
        if (finished_) {
          lock.unlock();
          close();
          if (failure_) std::rethrow_exception(std::exchange(failure_, nullptr));
          throw py::stop_iteration();
        }
      }
      {
        py::gil_scoped_release nogil;
        waker_.wait(std::chrono::milliseconds(50));
      }
      if (PyErr_CheckSignals() != 0) {
        close();
        throw py::error_already_set();
      }
    }
  }

  /// Stops the shot after the frame in progress and joins its thread.
  void close() {
    stop_.request_stop();
    space_.notify_all();
    if (thread_.joinable()) {
      py::gil_scoped_release nogil;
      thread_.join();
    }
  }

  int frame_count() const { return animation_->frame_count(); }
  std::string describe() const { return animation_->describe(); }
  std::string encoding() const { return animation_->encoding() == api::Encoding::srgb ? "srgb" : "linear"; }

 private:
  void start() {
    started_ = true;
    thread_ = std::thread([this] {
      try {
        animation_->run([this](int index, const api::Image& colour, const api::FrameRow& row) {
          std::unique_lock lock(mutex_);
          space_.wait(lock, [&] { return queue_.size() < 2 || stop_.stop_requested(); });
          if (stop_.stop_requested()) return;
          queue_.push_back({index, colour, row});
          lock.unlock();
          waker_.wake();
        });
      } catch (...) {
        const std::lock_guard lock(mutex_);
        failure_ = std::current_exception();
      }
      {
        const std::lock_guard lock(mutex_);
        finished_ = true;
      }
      waker_.wake();
    });
  }

  std::unique_ptr<api::Animation> animation_;
  std::stop_source stop_;
  std::thread thread_;
  std::mutex mutex_;
  std::condition_variable space_;
  std::deque<Frame> queue_;
  Waker waker_;
  std::exception_ptr failure_;
  bool started_ = false, finished_ = false;
};

}  // namespace

void bind_animate(py::module_& m) {
  py::class_<AnimationIterator>(m, "_Animation", "The frames of a shot (use holoray.animate).")
      .def(py::init<const std::string&, const py::dict&>(), py::arg("shot"), py::arg("options"))
      .def("__iter__", [](AnimationIterator& a) -> AnimationIterator& { return a; }, py::return_value_policy::reference_internal)
      .def("__next__", &AnimationIterator::next)
      .def("close", &AnimationIterator::close)
      .def_property_readonly("frame_count", &AnimationIterator::frame_count)
      .def_property_readonly("description", &AnimationIterator::describe)
      .def_property_readonly("encoding", &AnimationIterator::encoding);
}

}  // namespace holoray::python
