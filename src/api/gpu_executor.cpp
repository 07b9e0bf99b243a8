#include "api/gpu_executor.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <map>
#include <mutex>
#include <stdexcept>
#include <string>
#include <string_view>

#include <unistd.h>  // environ

#include "api/internal.hpp"
#ifdef HOLORAY_GPU
#include "gpu/gpu_renderer.hpp"
#endif

namespace holoray::api {

DeviceChoice parse_device(const std::string& device) {
  if (device == "cpu") return {};
  if (device == "gpu") return {true, -1};
  if (device.rfind("gpu:", 0) == 0) {
    int n = -1;
    const char* first = device.data() + 4;
    const char* last = device.data() + device.size();
    const auto [end, ec] = std::from_chars(first, last, n);
    if (ec == std::errc() && end == last && first != last && n >= 0) return {true, n};
  }
  throw std::invalid_argument(fmt::format("`device`: expected cpu, gpu or gpu:N (N from 0), got '{}'", device));
}

void check_device(const std::string& device) { parse_device(device); }

int gpu_of_local_rank(const std::vector<bool>& is_gpu, int local_rank) {
  std::vector<int> gpus;
  for (size_t k = 0; k < is_gpu.size(); ++k)
    if (is_gpu[k]) gpus.push_back(static_cast<int>(k));
  if (gpus.empty()) return -1;
  return gpus[static_cast<size_t>(std::max(0, local_rank)) % gpus.size()];
}

#ifdef HOLORAY_GPU

std::vector<std::string> gpu_devices() {
  std::vector<std::string> out;
  try {
    const auto all = gpu::list_devices();
    for (size_t k = 0; k < all.size(); ++k)
      out.push_back(fmt::format("{}: {}, {}, {}, {:.1f} GiB", k, all[k].name, all[k].is_gpu ? "GPU" : "CPU", all[k].api,
                                all[k].memory_bytes / 1073741824.0));
  } catch (const gpu::GpuError& e) {
    throw std::runtime_error(e.what());
  }
  return out;
}

std::string device_of_local_rank(const std::string& device, int local_rank) {
  if (device != "gpu") return device;
  std::vector<bool> is_gpu;
  try {
    for (const gpu::DeviceInfo& d : gpu::list_devices()) is_gpu.push_back(d.is_gpu);
  } catch (const gpu::GpuError& e) {
    throw std::runtime_error(e.what());
  }
  const int n = gpu_of_local_rank(is_gpu, local_rank);
  return n < 0 ? device : fmt::format("gpu:{}", n);
}

namespace {

class RendererPool;
RendererPool& renderer_pool();

// GPU renderers kept, idle and released (GpuRenderer::release), for the
// process's next render on the same device: a Vulkan device and its compiled
// pipelines cost more than a small frame (on lavapipe about 1.2 s a
// pipeline, on every GpuRenderer), and Python and Blender render one still
// after another. An executor holds its renderer alone, so renderers are
// never shared between threads; one that failed is not kept. The measuring
// knobs (HOLORAY_GPU_*, HOLORAY_VULKAN_LOADER) are read as a renderer is
// made, so while any is set nothing is kept or reused, but for
// HOLORAY_GPU_WAVEFRONT, whose renderers are kept apart by its value (the
// tests run the path integrator's suite under it, and lavapipe compiles a
// pipeline in seconds). The kept ones are
// destroyed at exit by a handler registered after the driver was loaded,
// so it runs while the driver's own state still stands (handlers run in
// reverse order, the shared libraries' destructors last).
class RendererPool {
 public:
  std::unique_ptr<gpu::GpuRenderer> take(int device, bool count_work) {
    if (knobs_set()) return nullptr;
    std::lock_guard<std::mutex> lock(mutex_);
    for (auto it = idle_.begin(); it != idle_.end(); ++it)
      if (it->device == device && it->count_work == count_work && it->wavefront == wavefront()) {
        std::unique_ptr<gpu::GpuRenderer> r = std::move(it->renderer);
        idle_.erase(it);
        return r;
      }
    return nullptr;
  }
  void give(int device, bool count_work, std::unique_ptr<gpu::GpuRenderer> r) {
    if (knobs_set()) return;
    std::lock_guard<std::mutex> lock(mutex_);
    if (!exit_handler_) exit_handler_ = std::atexit([] { renderer_pool().clear(); }) == 0;
    if (exit_handler_) idle_.push_back({device, count_work, wavefront(), std::move(r)});
  }
  // How many were freed. Destroyed outside the lock: a device's teardown
  // waits on the driver.
  int clear() {
    std::vector<Idle> gone;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      gone.swap(idle_);
    }
    return static_cast<int>(gone.size());
  }

 private:
  static bool knobs_set() {
    for (char** e = environ; *e; ++e)
      if ((std::strncmp(*e, "HOLORAY_GPU_", 12) == 0 && std::strncmp(*e, "HOLORAY_GPU_WAVEFRONT=", 22) != 0) ||
          std::strncmp(*e, "HOLORAY_VULKAN_LOADER=", 22) == 0)
        return true;
    return false;
  }
  static std::string wavefront() {
    const char* w = std::getenv("HOLORAY_GPU_WAVEFRONT");
    return w ? w : "";
  }
  struct Idle {
    int device;
    bool count_work;
    std::string wavefront;
    std::unique_ptr<gpu::GpuRenderer> renderer;
  };
  std::mutex mutex_;
  std::vector<Idle> idle_;
  bool exit_handler_ = false;
};

// Made once and never destroyed, so that the exit handler finds it.
RendererPool& renderer_pool() {
  static RendererPool* pool = new RendererPool;
  return *pool;
}

}  // namespace

int release_gpu_devices() noexcept {
  try {
    return renderer_pool().clear();
  } catch (...) {  // the pool's lock failed (std::system_error): nothing was freed
    return 0;
  }
}

struct GpuLayouts::Impl {
  std::mutex lock;
  std::map<int, std::shared_ptr<const gpu::SceneArrays>> by_width;
};
GpuLayouts::GpuLayouts() : impl(std::make_unique<Impl>()) {}
GpuLayouts::~GpuLayouts() = default;
size_t GpuLayouts::size() const {
  const std::lock_guard lock(impl->lock);
  return impl->by_width.size();
}

struct GpuExecutor::Impl {
  std::unique_ptr<gpu::GpuRenderer> renderer;
  GpuLayouts* layouts = nullptr;  // the world's, or null
  gpu::KeptBvh kept;  // an animation's hierarchy, refitted as its objects move
  std::optional<gpu::ScenePose> uploaded;
  bool uploaded_path = false;       // laid out with the path integrator's lights
  bool uploaded_emitters = false;   // ...and emitters (RenderSettings::emitters)
  uint64_t image_bytes = 0;
  bool panel = false;  // the camera's frames are panel images (gpu::renders_panel)
  int device = -1;
  bool count_work = false;
  bool healthy = false;  // the last call on `renderer` returned: it may be kept
  double setup_seconds = 0;
  double compile_seconds = 0;  // of the last follow() that laid the scene out

  ~Impl() {
    if (!renderer || !healthy) return;
    try {
      renderer->release();
      renderer_pool().give(device, count_work, std::move(renderer));
    } catch (...) {  // a renderer that cannot be released is not kept
    }
  }

  // Lays out and uploads `context`'s scene (and the path integrator's
  // lights where its settings ask for it) unless it stands as it did at the
  // last upload, under the same integrator: seconds spent, 0 when nothing
  // changed.
  double follow(const RenderContext& context) {
    const RenderScene& scene = context.scene();
    const bool path = context.settings().integrator == holoray::Integrator::path;
    // The emitters are a function of the pose (an animation builds them
    // again every frame): whether there are any is all that can change.
    const bool emitters = context.settings().emitters != nullptr;
    gpu::ScenePose now(scene.accel());
    if (uploaded && *uploaded == now && uploaded_path == path && uploaded_emitters == emitters) return 0;
    const auto start = std::chrono::steady_clock::now();
    // A scene that moves is built again without spatial splits (a fifth of
    // the time: gears_s4 19 ms a frame against 95, 2 cores, for the same
    // work per ray) and then refitted frame by frame while the refit tree
    // stays within kRefitGrowth of its cost (docs/design/gpu.md).
    if (layouts && !uploaded) {  // a World's scene as it was built: its layout, made once for all its renderers
      GpuLayouts::Impl& kept = *layouts->impl;
      const std::lock_guard lock(kept.lock);
      std::shared_ptr<const gpu::SceneArrays>& arrays = kept.by_width[renderer->bvh_width()];
      if (!arrays) arrays = std::make_shared<const gpu::SceneArrays>(gpu::lay_out(context, BvhQuality::high, renderer->bvh_width()));
      compile_seconds = renderer->load(*arrays, image_bytes, panel);
    } else if (!uploaded) {
      compile_seconds = renderer->load(gpu::lay_out(context, BvhQuality::high, renderer->bvh_width()), image_bytes, panel);
    } else {  // a frame whose objects moved: the hierarchy of the frames before, refitted (gpu::KeptBvh)
      compile_seconds =
          renderer->load(gpu::lay_out(context, BvhQuality::fast, renderer->bvh_width(), &kept), image_bytes, panel, true);
    }
    uploaded = std::move(now);
    uploaded_path = path, uploaded_emitters = emitters;
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
};

GpuExecutor::GpuExecutor(const DeviceChoice& device, const RenderContext& context, const FrameCamera& camera,
                         const RenderOptions& options, GpuLayouts* layouts)
    : impl_(std::make_unique<Impl>()) {
  impl_->layouts = layouts;
  if (options.cache.enabled)
    throw std::invalid_argument("`cache`: the shadow cache is the CPU path's; the GPU path traces every shadow ray");
  try {
    impl_->device = device.index;
    impl_->count_work = options.count_work;
    const auto t0 = std::chrono::steady_clock::now();
    impl_->renderer = renderer_pool().take(device.index, options.count_work);
    if (!impl_->renderer)
      impl_->renderer = std::make_unique<gpu::GpuRenderer>(device.index, std::vector<std::string>{}, options.count_work);
    const double made = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const bool aovs = options.aovs.albedo || options.aovs.depth || options.aovs.normal || options.aovs.id;
    impl_->image_bytes = gpu::GpuRenderer::frame_bytes(camera.width(), camera.height(), aovs);
    impl_->panel = gpu::renders_panel(camera);
    impl_->follow(context);
    impl_->setup_seconds = made + impl_->compile_seconds;
    impl_->healthy = true;
  } catch (const gpu::GpuError& e) {
    throw std::runtime_error(e.what());
  }
}

GpuExecutor::~GpuExecutor() = default;

std::string GpuExecutor::name() const { return impl_->renderer->describe(); }
double GpuExecutor::setup_seconds() const { return impl_->setup_seconds; }

FrameBuffers GpuExecutor::render(const RenderContext& context, const FrameCamera& camera, const AovSet& aovs, int spp,
                                 std::optional<std::array<int, 2>> rows, RenderStats& stats) {
  const int y0 = rows ? (*rows)[0] : 0, y1 = rows ? (*rows)[1] : camera.height();
  if (y0 < 0 || y1 > camera.height() || y0 >= y1)
    throw std::invalid_argument(fmt::format("rows {} to {} are not a band of the {} rows of the image", y0, y1, camera.height()));
  if (camera.get<QuiltCamera>() && (y0 != 0 || y1 != camera.height()))
    throw std::invalid_argument("`device` gpu: a quilt renders whole on the GPU, not in bands of rows");
  FrameBuffers fb = allocate_frame(camera.width(), y1 - y0, aovs);
  holoray::RenderStats g;
  impl_->healthy = false;
  try {
    stats.build_seconds = impl_->follow(context);
    impl_->renderer->render(gpu::camera_frames(context, camera, aovs, spp, y0, y1), camera.width(), y1 - y0, aovs, fb, g);
  } catch (const gpu::GpuError& e) {
    throw std::runtime_error(e.what());
  }
  impl_->healthy = true;
  stats.trace_seconds = g.trace_seconds;
  stats.readback_seconds = g.readback_seconds;
  stats.nodes_visited = g.nodes_visited;
  stats.primitives_tested = g.primitives_tested;
  stats.lane_steps = g.lane_steps;
  stats.rays = to_api(g.rays);
  return fb;
}

#else  // built without the GPU path

namespace {
constexpr const char* kNoGpu =
    "`device` gpu: this holoray was built without the GPU path (CMake found no Vulkan headers or glslc): "
    "install libvulkan-dev and glslc and build again, or use `device` cpu";
}

std::vector<std::string> gpu_devices() { throw std::runtime_error(kNoGpu); }
int release_gpu_devices() noexcept { return 0; }
std::string device_of_local_rank(const std::string& device, int) {
  if (device == "gpu") throw std::runtime_error(kNoGpu);
  return device;
}

struct GpuLayouts::Impl {};
GpuLayouts::GpuLayouts() = default;
GpuLayouts::~GpuLayouts() = default;
size_t GpuLayouts::size() const { return 0; }

struct GpuExecutor::Impl {};
GpuExecutor::GpuExecutor(const DeviceChoice&, const RenderContext&, const FrameCamera&, const RenderOptions&, GpuLayouts*) {
  throw std::runtime_error(kNoGpu);
}
GpuExecutor::~GpuExecutor() = default;
std::string GpuExecutor::name() const { return ""; }
double GpuExecutor::setup_seconds() const { return 0; }
FrameBuffers GpuExecutor::render(const RenderContext&, const FrameCamera&, const AovSet&, int,
                                 std::optional<std::array<int, 2>>, RenderStats&) {
  throw std::runtime_error(kNoGpu);
}

#endif

}  // namespace holoray::api
