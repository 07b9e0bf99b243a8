// holoray/gpu (private to src/gpu): the Vulkan objects behind GpuRenderer,
// shared by the renderer (gpu_renderer.cpp) and the presenter
// (presenter.cpp), which packs the renderer's frame into a window on the
// same device. Only these two files and shared_functions.cpp (the shared
// shading functions' device check) include Vulkan.
#pragma once

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <cstring>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

// The loader is opened with dlopen (gpu_renderer.cpp), not linked, so that a
// machine without libvulkan.so.1 still runs the CPU path.
#define VULKAN_HPP_NO_CONSTRUCTORS
#define VULKAN_HPP_ENABLE_DYNAMIC_LOADER_TOOL 0
#include <vulkan/vulkan_raii.hpp>

#include "gpu/gpu_renderer.hpp"

namespace holoray::gpu {

/// The system's Vulkan loader (or HOLORAY_VULKAN_LOADER's), opened once.
/// Throws GpuError saying what to install when there is none.
vk::raii::Context open_loader();
/// An instance with `extensions` enabled (a window's surface extensions).
/// Throws GpuError when the loader finds no driver.
vk::raii::Instance make_instance(const vk::raii::Context& context, const std::vector<std::string>& extensions);
/// A Vulkan failure as a GpuError in the user's words, naming `device`.
[[noreturn]] void rethrow_vulkan(const vk::SystemError& e, const std::string& device);

/// The steps of Whitted's wavefront for a band (its largest ray tree's
/// rays: max_depth, or 2^max_depth - 1 where a hit can send two rays on);
/// 0 where that is too many to pay (wavefront.cpp).
int whitted_steps(int max_depth, bool branches);

/// trace.comp's descriptor bindings.
constexpr int kBindings = 31;

// A buffer and its memory; `mapped` when host-visible.
struct Buffer {
  vk::raii::Buffer buffer = nullptr;
  vk::raii::DeviceMemory memory = nullptr;
  vk::DeviceSize size = 0;
  void* mapped = nullptr;
};

struct GpuRenderer::Impl {
  explicit Impl(const std::vector<std::string>& instance_extensions)
      : context(open_loader()), instance(make_instance(context, instance_extensions)) {}

  vk::raii::Context context;
  vk::raii::Instance instance;
  bool window = false;  // made for a window: VK_KHR_swapchain enabled
  vk::raii::PhysicalDevice physical = nullptr;
  DeviceInfo info;
  uint32_t family = 0;
  vk::raii::Device device = nullptr;
  vk::raii::Queue queue = nullptr;
  vk::raii::CommandPool pool = nullptr;
  vk::raii::DescriptorSetLayout set_layout = nullptr;
  vk::raii::PipelineLayout pipeline_layout = nullptr;
  // Indexed by integrator: [0] Whitted's, [1] the path integrator's (trace.comp's kPath).
  vk::raii::ShaderModule module[2] = {nullptr, nullptr};
  vk::raii::ShaderModule shade_module[2] = {nullptr, nullptr};  // the wavefront's shade stage alone (trace.comp)
  vk::raii::ShaderModule traversal_module = nullptr;  // the wavefront's small kernels alone (trace.comp)
  // The kernel's pipelines, made when first needed: by whether it renders
  // panels (display panels, Looking Glass native panels), by what the
  // loaded scene needs (SceneArrays::features: its materials, its
  // hierarchy's width), and whether it counts the work done
  // (GpuRenderer::count_work).
  std::map<uint32_t, vk::raii::Pipeline> pipelines;
  uint32_t features = 0;  // the loaded scene's
  int bvh_width = 4;      // HOLORAY_GPU_BVH_WIDTH: the hierarchy lay_out builds (4 or 8)
  bool count_work = false;
  bool capture_stats = false;
  // HOLORAY_GPU_RAY_LOG's file, where every traced frame's rays are logged
  // (trace.comp, kRayLog), and the log's buffer (binding 18).
  std::string ray_log_path;
  Buffer ray_log;
  // The shadow queue (trace.comp, kShadowQueue and kShadowPass), for
  // measuring: on with HOLORAY_GPU_SHADOW_QUEUE where the device has
  // subgroup ballots and votes and the ray log is off; its room in rays
  // (0: 8 a pixel).
  bool shadow_queue_on = false;
  uint64_t shadow_queue_rays = 0;
  // Invocations a dispatch holds at most (a pixel band's pixels, a shadow
  // pass's lanes, a resolve's pixels): 2^20, well inside a desktop
  // watchdog's seconds; HOLORAY_GPU_BAND=N sets N (the tests' banding).
  uint64_t band_invocations = uint64_t(1) << 20;
  // HOLORAY_GPU_STATS: each frame's passes timed on the device (the pixel
  // kernel, the shadow pass, its resolve), printed on stderr.
  vk::raii::QueryPool timestamps = nullptr;
  double timestamp_ns = 0;
  Buffer queue_head;  // the shadow queue's head, copied back for the same print
  Buffer shadow_queue, shadow_last, shadow_terms;  // bindings 19, 20 and 21
  // Both integrators as a wavefront (wavefront.cpp, shaders/wavefront.glsl
  // and whitted_wavefront.glsl) where the device has subgroup ballots and
  // votes and the ray log is off; HOLORAY_GPU_WAVEFRONT=0 never
  // (measuring). Its buffers, bindings 25 to 30: the paths' (pixels')
  // states, their hits, the queues and their heads, the shadow rays and
  // their queue, and Whitted's pixels' ray stacks.
  bool wavefront_on = false;
  bool wavefront_always = false;  // HOLORAY_GPU_WAVEFRONT=1
  uint32_t rays_per_lane = HR_SHADOW_RAYS_PER_LANE;  // kRaysPerLane: 1 on a GPU (HOLORAY_GPU_RAYS_PER_LANE)
  // Which frames of the loaded scene take the wavefront (wavefront.cpp):
  // `long_paths`, those after a frame of at least kLongPaths rays a pixel a
  // sample; takes_wavefront, whether the next frame does.
  enum class WaveRule { never, long_paths, always };
  static constexpr double kLongPaths = 8;
  WaveRule wave_rule(bool path) const;
  bool takes_wavefront(bool path) const;
  double last_rays_a_sample = 0;  // the frame before's, for wave_rule
  Buffer wave_paths, wave_hits, wave_queues, wave_shadows, wave_shadow_queue, wave_stack;
  bool whitted_branches = false;  // the loaded scene's (SceneArrays)
  // With HOLORAY_GPU_STATS, a timestamp after each of the wavefront's
  // dispatches (the first kWaveStamps of a frame), and the stage each ends
  // (WaveStage), summed by stage and printed (print_wave_times).
  static constexpr uint32_t kWaveStamps = 4096;
  enum WaveStage { kStart, kExtend, kShade, kShadow, kFinish, kWaveStages };
  vk::raii::QueryPool wave_timestamps = nullptr;
  std::vector<WaveStage> wave_stamped;
  void stamp(WaveStage stage);
  void print_wave_times();
  uint64_t max_storage_range = 0;  // bytes (VkPhysicalDeviceLimits)
  vk::raii::DescriptorPool descriptor_pool = nullptr;
  vk::raii::DescriptorSet set = nullptr;
  vk::PhysicalDeviceMemoryProperties memory_types;
  Buffer scene[kBindings];  // by binding: 0 (the frame) to 9, 13 to 17 and 22 to 24 (the others below)
  Buffer colour, aov, counts, staging;
  // The frames' constants (binding 0, scene[0]) and the counters (binding
  // 12, `counts`) live in device memory, which every invocation reads and
  // adds to (the host's would be crossed over the bus on a GPU): the
  // constants copied in from `frames_host` as a frame begins, the counters
  // out to `counts_host` as each submission ends (submit_and_wait).
  Buffer frames_host, counts_host;
  vk::raii::CommandBuffer commands = nullptr;
  vk::raii::Fence fence = nullptr;
  // The readback's own, kept from frame to frame (as `commands` and `fence`).
  vk::raii::CommandBuffer readback_commands = nullptr;
  vk::raii::Fence readback_fence = nullptr;
  uint32_t workgroup[2] = {32, 2};  // shaders/trace.comp says why
  uint64_t scene_bytes = 0;
  // The last frame traced: its size (0 x 0 before any) and whether the AOVs were.
  std::array<int, 2> traced{0, 0};
  bool traced_aovs = false;
  // How long a submission may run before the device counts as stopped
  // (issue 71): 120 s a submission on a GPU (a pass of the path integrator,
  // or a Whitted frame: milliseconds to seconds), no bound on a CPU device
  // such as lavapipe, whose long frames are work, not a hang;
  // HOLORAY_GPU_TIMEOUT=S (seconds) sets it on either.
  double timeout_s = 0;  // 0: no bound
  // A wait ran out: the device may still be running what it was given, so
  // nothing it holds may be freed (GpuRenderer's destructor keeps this Impl
  // whole) and the renderer refuses further work.
  bool stopped = false;

  void check_responding() const {
    if (stopped)
      throw GpuError(fmt::format("the GPU ({}) stopped responding in an earlier render: make a new renderer", info.name));
  }

  // Waits for `f`; past timeout_s, the device counts as stopped: GpuError.
  // HOLORAY_GPU_FAULT=timeout (for the tests: no device hangs on demand,
  // and a tiny timeout alone races a small frame) makes every wait end so.
  void wait(const vk::raii::Fence& f, const char* what) {
    const uint64_t ns = timeout_s > 0 ? uint64_t(timeout_s * 1e9) : UINT64_MAX;
    vk::Result r = device.waitForFences({*f}, VK_TRUE, ns);
    if (const char* fault = std::getenv("HOLORAY_GPU_FAULT"); fault && std::string_view(fault) == "timeout") r = vk::Result::eTimeout;
    if (r == vk::Result::eTimeout) {
      stopped = true;
      // A device that was only slow finishes within a grace: then no driver
      // thread is still running its work when the process ends (lavapipe's,
      // still running at exit, crashed holoray after the message: 3 runs in
      // 30 on a loaded machine, 0 with the grace). A hung one is left.
      constexpr uint64_t kGraceNs = 5'000'000'000;
      (void)device.waitForFences({*f}, VK_TRUE, kGraceNs);
      throw GpuError(fmt::format("the GPU ({}) stopped responding: {} did not finish in {:g} s (HOLORAY_GPU_TIMEOUT sets "
                                 "the wait); nothing was written",
                                 info.name, what, timeout_s));
    }
    if (r != vk::Result::eSuccess) throw GpuError(fmt::format("the GPU ({}) did not finish", info.name));
  }

  uint32_t memory_type(uint32_t allowed, vk::MemoryPropertyFlags want, vk::MemoryPropertyFlags prefer = {}) const {
    std::optional<uint32_t> fallback;
    for (uint32_t t = 0; t < memory_types.memoryTypeCount; ++t) {
      if (!(allowed & (1u << t)) || (memory_types.memoryTypes[t].propertyFlags & want) != want) continue;
      if ((memory_types.memoryTypes[t].propertyFlags & prefer) == prefer) return t;
      if (!fallback) fallback = t;
    }
    if (!fallback) throw GpuError(fmt::format("the device {} offers no memory the GPU path can use", info.name));
    return *fallback;
  }

  size_t buffers_made = 0;  // GpuRenderer::buffers_made
  Buffer make_buffer(vk::DeviceSize size, vk::BufferUsageFlags usage, bool host) {
    ++buffers_made;
    Buffer b;
    b.size = std::max<vk::DeviceSize>(size, 16);
    b.buffer = vk::raii::Buffer(device, vk::BufferCreateInfo{.size = b.size, .usage = usage});
    const vk::MemoryRequirements req = b.buffer.getMemoryRequirements();
    const uint32_t type = host ? memory_type(req.memoryTypeBits, vk::MemoryPropertyFlagBits::eHostVisible | vk::MemoryPropertyFlagBits::eHostCoherent,
                                             vk::MemoryPropertyFlagBits::eHostCached)
                               : memory_type(req.memoryTypeBits, vk::MemoryPropertyFlagBits::eDeviceLocal);
    b.memory = vk::raii::DeviceMemory(device, vk::MemoryAllocateInfo{.allocationSize = req.size, .memoryTypeIndex = type});
    b.buffer.bindMemory(*b.memory, 0);
    if (host) b.mapped = b.memory.mapMemory(0, b.size);
    return b;
  }

  // Runs `record` in a one-time command buffer and waits for it.
  template <class F>
  void run_once(F&& record) {
    vk::raii::CommandBuffers cbs(device, vk::CommandBufferAllocateInfo{.commandPool = *pool, .commandBufferCount = 1});
    vk::raii::CommandBuffer& cb = cbs[0];
    cb.begin(vk::CommandBufferBeginInfo{.flags = vk::CommandBufferUsageFlagBits::eOneTimeSubmit});
    record(cb);
    cb.end();
    vk::raii::Fence fence(device, vk::FenceCreateInfo{});
    vk::CommandBuffer raw = *cb;
    queue.submit(vk::SubmitInfo{.commandBufferCount = 1, .pCommandBuffers = &raw}, *fence);
    // Unbounded, unlike the frames' waits (wait()): the staging buffer and
    // this command buffer are the caller's locals, which an exception would
    // free under a device that may still be copying from them.
    if (device.waitForFences({*fence}, VK_TRUE, UINT64_MAX) != vk::Result::eSuccess)
      throw GpuError(fmt::format("the GPU ({}) did not finish", info.name));
  }

  // A device-local storage buffer holding `bytes` from the host (through a staging buffer).
  Buffer upload(const void* data, size_t bytes) {
    Buffer dst = make_buffer(bytes, vk::BufferUsageFlagBits::eStorageBuffer | vk::BufferUsageFlagBits::eTransferDst, false);
    Buffer staging = make_buffer(bytes, vk::BufferUsageFlagBits::eTransferSrc, true);
    std::memcpy(staging.mapped, data, bytes);
    run_once([&](vk::raii::CommandBuffer& cb) { cb.copyBuffer(*staging.buffer, *dst.buffer, vk::BufferCopy{0, 0, bytes}); });
    return dst;
  }

  // One of the scene's arrays for upload_arrays: `bytes` from `data` into
  // scene[binding].
  struct ArrayUpload {
    int binding;
    const void* data;
    size_t bytes;
  };
  // The scene's arrays copied into their device-local buffers through one
  // staging buffer (scene_staging, kept until release()), in one
  // submission, and bound. `reuse`: a shot's next frame (the same scene
  // moved), whose arrays go into the buffers the frame before left where
  // they fit: such a frame makes no buffer (gpu_renderer.cpp).
  void upload_arrays(const std::vector<ArrayUpload>& arrays, bool reuse);
  Buffer scene_staging;
  // The frames' buffers (their constants, counters, ray log, shadow queue
  // and wavefront) made anew at their smallest and bound, for a new scene:
  // each frame grows them as it needs (prepare_frame, prepare_wavefront).
  void reset_frame_buffers();

  // One frame's work as trace() dispatches it: each camera's rows in bands
  // of about band_invocations pixels (2^20), each its own dispatch (well
  // inside a desktop watchdog's seconds), all in one submission; each band
  // its own 32-bit counters, summed on the host in 64 bits.
  struct Band {
    int32_t row0, rows, frame;
    uint32_t width;
  };
  struct FramePlan {
    std::vector<Band> bands;
    uint64_t pixels = 0;
    uint64_t queue_rays = 0;  // the shadow queue's capacity; 0: no queue
    bool want_aovs = false, panel = false, queue = false, path = false;
    int passes = 1;  // the samples a pixel, one a pass (the path integrator's, or any wavefront's)
    // The wavefront: its bands' most paths (pixels) and the most shadow
    // rays a path makes at a vertex (a Whitted hit: one a light); 0 paths:
    // the megakernel. Whitted's: the rays a pixel's stack holds, and the
    // steps a band takes (its largest ray tree's rays: whitted_steps).
    uint64_t wave_paths = 0;
    uint32_t wave_shadows = 0;
    uint32_t wave_stack = 0;
    int wave_steps = 0;
  };
  // The frame's bands and buffers' sizes, refused (GpuError naming the
  // limit) where the device cannot hold them: gpu_renderer.cpp.
  FramePlan plan_frame(const std::vector<GpuFrame>& frames, int W, int H) const;
  // The frame's buffers grown to the plan, its cameras and cleared counters
  // written, and the shadow queue's reset recorded into `commands`.
  void prepare_frame(const std::vector<GpuFrame>& frames, const FramePlan& plan);
  // Records the pixel kernel's passes from `first_sample` (submitted and
  // waited on every few passes), or the wavefront's.
  void record_pixel_passes(const FramePlan& plan, int first_sample);
  void record_shadow_passes(const FramePlan& plan);
  // The wavefront's buffers grown to the plan (wavefront.cpp), and its
  // stages recorded in place of the pixel kernel's passes.
  void prepare_wavefront(const FramePlan& plan);
  void record_wavefront_passes(const FramePlan& plan, int first_sample);
  // A memory barrier between two dispatches (or a transfer and a dispatch).
  void barrier(vk::PipelineStageFlags from = vk::PipelineStageFlagBits::eComputeShader);
  // A barrier before an indirect dispatch that reads sizes a kernel wrote.
  void indirect_barrier();
  // Ends `commands`, submits it and waits under the timeout (wait()).
  void submit_and_wait(const char* what);
  // The path integrator's passes go in submissions of about 4 bands'
  // pixel-samples (record_pixel_passes says why): how many passes each.
  int passes_per_submission(const FramePlan& plan) const {
    return int(std::max<uint64_t>(1, 4 * band_invocations / std::max<uint64_t>(1, plan.pixels)));
  }
  // One submission of passes waited on and `commands` begun again.
  void next_submission() {
    submit_and_wait("a pass of the path integrator");
    commands.reset();
    commands.begin(vk::CommandBufferBeginInfo{.flags = vk::CommandBufferUsageFlagBits::eOneTimeSubmit});
  }
  // With timestamps (HOLORAY_GPU_STATS=1): each pass's time on the device.
  void print_pass_times(const FramePlan& plan);
  // The bands' counters summed into `stats`.
  void sum_counts(const FramePlan& plan, RenderStats& stats) const;

  // The kernel specialised (shaders/trace.comp): workgroup size, whether
  // shadow rays visit children nearest first (HOLORAY_GPU_SORT_SHADOW=1:
  // they do; for tuning), whether it renders the panels, the materials'
  // features (HR_FEATURE_*), and whether it counts nodes and primitives.
  // With the shadow queue, the pixel kernel queues shadow rays (`queue`), or
  // the pipeline is the shadow pass (`shadow_pass` 1) or its resolve (2).
  // `wave_stage`: a stage of the path integrator's wavefront (HR_WAVE_*).
  vk::raii::Pipeline make_pipeline(bool panel, bool queue, int shadow_pass, int wave_stage);  // gpu_renderer.cpp

  // The pipeline for the loaded scene's features and for count_work, made on
  // first use and kept (`pipelines`). `queue`: the frame has a shadow queue,
  // whose pixel kernel (shadow_pass 0) queues its shadow rays.
  vk::raii::Pipeline& pipeline(bool panel, bool queue, int shadow_pass, int wave_stage = 0);  // gpu_renderer.cpp

  void bind(int binding, const Buffer& b) {
    vk::DescriptorBufferInfo bi{*b.buffer, 0, VK_WHOLE_SIZE};
    device.updateDescriptorSets(vk::WriteDescriptorSet{.dstSet = *set, .dstBinding = uint32_t(binding), .descriptorCount = 1,
                                                       .descriptorType = vk::DescriptorType::eStorageBuffer, .pBufferInfo = &bi},
                                nullptr);
  }
};

}  // namespace holoray::gpu
