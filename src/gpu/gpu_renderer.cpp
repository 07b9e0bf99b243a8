#include "gpu/gpu_renderer.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <optional>
#include <string_view>
#include <utility>

#include <dlfcn.h>
#include <unistd.h>

#include "gpu/vulkan_device.hpp"
#include "scene/file_text.hpp"
#include "util/parallel.hpp"

namespace holoray::gpu {

namespace {

// SPIR-V of shaders/trace.comp, made by glslc at build time: the whole
// kernel, and the wavefront's shade stage alone (HR_SHADE_KERNEL), each
// once per integrator (HR_INTEGRATOR_WHITTED, _PATH); the wavefront's small
// kernels alone (HR_TRAVERSAL_KERNELS), for both.
const uint32_t kTraceWhittedSpirv[] = {
#include "trace_whitted.spv.inc"
};
const uint32_t kTracePathSpirv[] = {
#include "trace_path.spv.inc"
};
const uint32_t kShadeWhittedSpirv[] = {
#include "trace_shade_whitted.spv.inc"
};
const uint32_t kShadePathSpirv[] = {
#include "trace_shade_path.spv.inc"
};
const uint32_t kTraversalSpirv[] = {
#include "trace_traversal.spv.inc"
};

constexpr const char* kFix =
    "install mesa-vulkan-drivers (lavapipe, Vulkan on the CPU) or the GPU's own driver, or render with `device` cpu";

std::string api_version(uint32_t v) { return fmt::format("Vulkan {}.{}", VK_API_VERSION_MAJOR(v), VK_API_VERSION_MINOR(v)); }


// NVIDIA's driver registers libGLX_nvidia.so.0 as its Vulkan driver, and
// in a headless container that library gives no vkCreateInstance (measured
// on an H200, driver 580: "Found no drivers!"), while libEGL_nvidia.so.0,
// the same driver's EGL face, serves Vulkan (a manifest naming it in
// VK_ADD_DRIVER_FILES, set before the process started, found the GPU; set
// by the process after the loader was opened, the loader never saw it).
// So where NVIDIA's manifest is installed and no driver list is given
// (VK_ICD_FILENAMES, VK_DRIVER_FILES, VK_ADD_DRIVER_FILES), holoray writes
// a manifest naming libEGL_nvidia.so.0 and adds it to the loader's search
// before it opens the loader (the file is removed at exit; the loader
// ignores it where that library is missing), and counts a GPU both drivers
// list once (physical_devices, by UUID).
class NvidiaEglManifest {
 public:
  NvidiaEglManifest() {
    for (const char* v : {"VK_ICD_FILENAMES", "VK_DRIVER_FILES", "VK_ADD_DRIVER_FILES"})
      if (std::getenv(v)) return;
    bool nvidia = false;
    for (const char* dir : {"/usr/share/vulkan/icd.d", "/etc/vulkan/icd.d", "/usr/local/share/vulkan/icd.d"})
      nvidia |= ::access((std::string(dir) + "/nvidia_icd.json").c_str(), R_OK) == 0;
    if (!nvidia) return;
    // The loader takes a path for a manifest only when it ends in .json.
    char name[] = "/tmp/holoray-nvidia-egl-XXXXXX.json";
    const int fd = ::mkstemps(name, 5);
    if (fd < 0) return;
    const std::string manifest =
        R"({"file_format_version": "1.0.0", "ICD": {"library_path": "libEGL_nvidia.so.0", "api_version": "1.3.0"}})";
    const bool written = ::write(fd, manifest.data(), manifest.size()) == ssize_t(manifest.size());
    ::close(fd);
    if (!written) {
      ::unlink(name);
      return;
    }
    path_ = name;
    ::setenv("VK_ADD_DRIVER_FILES", name, 1);
  }
  ~NvidiaEglManifest() {
    if (!path_.empty()) ::unlink(path_.c_str());
  }
  NvidiaEglManifest(const NvidiaEglManifest&) = delete;
  NvidiaEglManifest& operator=(const NvidiaEglManifest&) = delete;

 private:
  std::string path_;
};

}  // namespace

vk::raii::Instance make_instance(const vk::raii::Context& context, const std::vector<std::string>& extensions) {
  vk::ApplicationInfo app{.pApplicationName = "holoray", .apiVersion = VK_API_VERSION_1_1};
  std::vector<const char*> names;
  for (const std::string& e : extensions) names.push_back(e.c_str());
  try {
    return vk::raii::Instance(context, vk::InstanceCreateInfo{.pApplicationInfo = &app,
                                                              .enabledExtensionCount = uint32_t(names.size()),
                                                              .ppEnabledExtensionNames = names.data()});
  } catch (const vk::SystemError& e) {
    throw GpuError(fmt::format("the Vulkan loader found no driver ({}): {}", e.what(), kFix));
  }
}

namespace {

// The loader's library: HOLORAY_VULKAN_LOADER names another (a loader
// outside the library path; the tests name a missing one), else the
// system's libvulkan.so.1. Opened once and kept for the process.
PFN_vkGetInstanceProcAddr loader_entry() {
  static void* library = nullptr;
  static std::string opened;
  const char* env = std::getenv("HOLORAY_VULKAN_LOADER");
  const std::string name = env && *env ? env : "libvulkan.so.1";
  if (!library || opened != name) {
    static const NvidiaEglManifest nvidia_egl;  // before the loader reads its environment
    library = ::dlopen(name.c_str(), RTLD_NOW | RTLD_LOCAL);
    opened = name;
  }
  auto entry = library ? reinterpret_cast<PFN_vkGetInstanceProcAddr>(::dlsym(library, "vkGetInstanceProcAddr")) : nullptr;
  if (!entry)
    throw GpuError(fmt::format("the GPU path needs the Vulkan loader ({}), and this machine has none: install libvulkan1 "
                               "with mesa-vulkan-drivers (lavapipe, Vulkan on the CPU) or the GPU's own driver, or render "
                               "with `device` cpu", name));
  return entry;
}

}  // namespace

vk::raii::Context open_loader() { return vk::raii::Context(loader_entry()); }

namespace {

DeviceInfo info_of(const vk::raii::PhysicalDevice& pd) {
  const auto chain = pd.getProperties2<vk::PhysicalDeviceProperties2, vk::PhysicalDeviceSubgroupProperties>();
  const vk::PhysicalDeviceProperties& p = chain.get<vk::PhysicalDeviceProperties2>().properties;
  DeviceInfo d;
  d.name = p.deviceName.data();
  d.api = api_version(p.apiVersion);
  d.is_gpu = p.deviceType == vk::PhysicalDeviceType::eDiscreteGpu || p.deviceType == vk::PhysicalDeviceType::eIntegratedGpu ||
             p.deviceType == vk::PhysicalDeviceType::eVirtualGpu;
  const vk::PhysicalDeviceMemoryProperties m = pd.getMemoryProperties();
  for (uint32_t h = 0; h < m.memoryHeapCount; ++h)
    if (m.memoryHeaps[h].flags & vk::MemoryHeapFlagBits::eDeviceLocal) d.memory_bytes = std::max<uint64_t>(d.memory_bytes, m.memoryHeaps[h].size);
  d.subgroup_size = chain.get<vk::PhysicalDeviceSubgroupProperties>().subgroupSize;
  d.max_storage_buffer_range = p.limits.maxStorageBufferRange;
  return d;
}

std::vector<vk::raii::PhysicalDevice> physical_devices(const vk::raii::Instance& instance) {
  std::vector<vk::raii::PhysicalDevice> all;
  try {
    all = instance.enumeratePhysicalDevices();
  } catch (const vk::SystemError&) {
  }
  if (all.empty()) throw GpuError(fmt::format("Vulkan lists no device on this machine: {}", kFix));
  // One GPU listed by two drivers (NvidiaEglManifest) counts once.
  std::vector<vk::raii::PhysicalDevice> unique;
  std::vector<std::array<uint8_t, VK_UUID_SIZE>> seen;
  for (auto& pd : all) {
    const auto chain = pd.getProperties2<vk::PhysicalDeviceProperties2, vk::PhysicalDeviceIDProperties>();
    std::array<uint8_t, VK_UUID_SIZE> uuid;
    std::copy_n(chain.get<vk::PhysicalDeviceIDProperties>().deviceUUID.data(), VK_UUID_SIZE, uuid.begin());
    if (std::find(seen.begin(), seen.end(), uuid) != seen.end()) continue;
    seen.push_back(uuid);
    unique.push_back(std::move(pd));
  }
  return unique;
}

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

// A Vulkan failure mid-render in the user's words.
[[noreturn]] void rethrow_vulkan(const vk::SystemError& e, const std::string& device) {
  if (e.code() == vk::Result::eErrorDeviceLost)
    throw GpuError(fmt::format("the GPU ({}) was lost during the render (VK_ERROR_DEVICE_LOST): its driver reset it; "
                               "nothing was written", device));
  if (e.code() == vk::Result::eErrorOutOfDeviceMemory || e.code() == vk::Result::eErrorOutOfHostMemory)
    throw GpuError(fmt::format("the GPU ({}) ran out of memory: {}; nothing was written", device, e.what()));
  throw GpuError(fmt::format("the GPU ({}) failed: {}", device, e.what()));
}

namespace {

bool has_extension(const vk::raii::PhysicalDevice& pd, std::string_view name) {
  for (const auto& e : pd.enumerateDeviceExtensionProperties())
    if (name == e.extensionName.data()) return true;
  return false;
}

void print_statistics(const vk::raii::Device& device, const vk::raii::Pipeline& pipeline) {
  const auto executables = device.getPipelineExecutablePropertiesKHR(vk::PipelineInfoKHR{.pipeline = *pipeline});
  for (uint32_t k = 0; k < executables.size(); ++k) {
    std::fprintf(stderr, "holoray gpu: kernel %s\n", executables[k].name.data());
    for (const auto& st : device.getPipelineExecutableStatisticsKHR(vk::PipelineExecutableInfoKHR{.pipeline = *pipeline, .executableIndex = k})) {
      std::string value;
      switch (st.format) {
        case vk::PipelineExecutableStatisticFormatKHR::eBool32: value = st.value.b32 ? "true" : "false"; break;
        case vk::PipelineExecutableStatisticFormatKHR::eInt64: value = std::to_string(st.value.i64); break;
        case vk::PipelineExecutableStatisticFormatKHR::eUint64: value = std::to_string(st.value.u64); break;
        case vk::PipelineExecutableStatisticFormatKHR::eFloat64: value = std::to_string(st.value.f64); break;
      }
      std::fprintf(stderr, "holoray gpu:   %s = %s\n", st.name.data(), value.c_str());
    }
  }
}

// The ray log's buffer, host memory allocated only when logging: a 16-byte
// head and 2^25 records of 16 bytes (512 MiB: a 1920x1088 EIA of gears_s4
// traces 16.8 M rays).
constexpr uint64_t kRayLogBytes = 16 + (uint64_t(1) << 25) * 16;
// The counters' buffer: added to by the kernels, cleared and copied out by transfers.
constexpr vk::BufferUsageFlags kCountUsage =
    vk::BufferUsageFlagBits::eStorageBuffer | vk::BufferUsageFlagBits::eTransferDst | vk::BufferUsageFlagBits::eTransferSrc;

// The frame's ray log (trace.comp, kRayLog) to `path`, written atomically
// (write_text_file): "HRRAYLG1", then uint32 workgroup width and height,
// the image's width and height, the records kept and those past the buffer,
// then the records (bench/ray_schedule_model.py reads them).
void write_ray_log(const Buffer& log, const std::string& path, const uint32_t workgroup[2], int W, int H) {
  const uint32_t* head = static_cast<const uint32_t*>(log.mapped);
  const uint32_t capacity = uint32_t((kRayLogBytes - 16) / 16), taken = head[0];
  const uint32_t kept = std::min(taken, capacity);
  const uint32_t fields[6] = {workgroup[0], workgroup[1], uint32_t(W), uint32_t(H), kept, taken - kept};
  std::string bytes("HRRAYLG1");
  bytes.append(reinterpret_cast<const char*>(fields), sizeof fields);
  bytes.append(reinterpret_cast<const char*>(head + 4), size_t(kept) * 16);
  write_text_file(path, bytes);
}

}  // namespace

vk::raii::Pipeline& GpuRenderer::Impl::pipeline(bool panel, bool queue, int shadow_pass, int wave_stage) {
  const uint32_t key = features << 8 | uint32_t(wave_stage) << 5 | uint32_t(shadow_pass) << 3 | (queue ? 4u : 0u) |
                       (count_work ? 2u : 0u) | (panel ? 1u : 0u);
  auto p = pipelines.find(key);
  if (p == pipelines.end()) p = pipelines.emplace(key, make_pipeline(panel, queue && shadow_pass == 0, shadow_pass, wave_stage)).first;
  return p->second;
}

vk::raii::Pipeline GpuRenderer::Impl::make_pipeline(bool panel, bool queue, int shadow_pass, int wave_stage) {
  const int path = (features & HR_FEATURE_PATH) ? 1 : 0;
  const char* sort_env = std::getenv("HOLORAY_GPU_SORT_SHADOW");
  constexpr uint32_t kConstants = 16;
  const uint32_t spec_values[kConstants] = {workgroup[0], workgroup[1], sort_env && std::string(sort_env) == "1" ? 1u : 0u,
                                            panel ? 1u : 0u, (features & HR_FEATURE_TACHYON) ? 1u : 0u,
                                            (features & HR_FEATURE_GLTF) ? 1u : 0u,
                                            (features & HR_FEATURE_MESH_TEXTURES) ? 1u : 0u,
                                            (features & HR_FEATURE_ALPHA_MASKS) ? 1u : 0u, count_work ? 1u : 0u,
                                            count_work && !ray_log_path.empty() ? 1u : 0u, queue ? 1u : 0u, uint32_t(shadow_pass),
                                            (features & HR_FEATURE_WIDE_BVH) ? 1u : 0u, (features & HR_FEATURE_PATH) ? 1u : 0u,
                                            uint32_t(wave_stage), rays_per_lane};
  vk::SpecializationMapEntry entries[kConstants];
  for (uint32_t k = 0; k < kConstants; ++k) entries[k] = vk::SpecializationMapEntry{k, 4 * k, 4};
  const vk::SpecializationInfo spec{.mapEntryCount = kConstants, .pMapEntries = entries, .dataSize = sizeof spec_values,
                                    .pData = spec_values};
  vk::ComputePipelineCreateInfo pi{
      .flags = capture_stats ? vk::PipelineCreateFlagBits::eCaptureStatisticsKHR : vk::PipelineCreateFlags{},
      .stage = {.stage = vk::ShaderStageFlagBits::eCompute,
                .module = wave_stage >= HR_WAVE_EXTEND ? *traversal_module
                          : wave_stage == HR_WAVE_SHADING ? *shade_module[path]
                                                          : *module[path],
                .pName = "main", .pSpecializationInfo = &spec},
      .layout = *pipeline_layout};
  const auto t0 = std::chrono::steady_clock::now();
  vk::raii::Pipeline p(device, nullptr, pi);
  if (std::getenv("HOLORAY_GPU_STATS"))
    std::fprintf(stderr, "holoray gpu: pipeline (wavefront stage %d, shadow pass %d) compiled in %.2f s\n", wave_stage, shadow_pass,
                 seconds_since(t0));
  if (capture_stats) print_statistics(device, p);
  return p;
}

std::vector<DeviceInfo> list_devices() {
  vk::raii::Context context = open_loader();
  vk::raii::Instance instance = make_instance(context, {});
  std::vector<DeviceInfo> out;
  for (const auto& pd : physical_devices(instance)) out.push_back(info_of(pd));
  return out;
}

GpuRenderer::GpuRenderer(int device_index, const std::vector<std::string>& instance_extensions, bool count_work)
    : impl_(std::make_unique<Impl>(instance_extensions)) {
  Impl& m = *impl_;
  std::vector<vk::raii::PhysicalDevice> all = physical_devices(m.instance);
  size_t pick = 0;
  if (device_index < 0) {
    for (size_t k = 0; k < all.size(); ++k)
      if (info_of(all[k]).is_gpu) {
        pick = k;
        break;
      }
  } else if (size_t(device_index) >= all.size()) {
    std::string names;
    for (size_t k = 0; k < all.size(); ++k) names += fmt::format("{}{} {}", k ? ", " : "", k, info_of(all[k]).name);
    throw GpuError(fmt::format("`device` gpu:{}: this machine has {} Vulkan device{}: {}", device_index, all.size(),
                               all.size() == 1 ? "" : "s", names));
  } else {
    pick = size_t(device_index);
  }
  m.physical = std::move(all[pick]);
  m.info = info_of(m.physical);
  // The kernel sums its counters per subgroup (subgroupAdd).
  const auto subgroups = m.physical.getProperties2<vk::PhysicalDeviceProperties2, vk::PhysicalDeviceSubgroupProperties>()
                             .get<vk::PhysicalDeviceSubgroupProperties>();
  if (!(subgroups.supportedStages & vk::ShaderStageFlagBits::eCompute) ||
      !(subgroups.supportedOperations & vk::SubgroupFeatureFlagBits::eArithmetic))
    throw GpuError(fmt::format("the device {} has no subgroup arithmetic in compute shaders, which the GPU path needs: "
                               "render with `device` cpu, or choose another device (`device` gpu:N)", m.info.name));
  // HOLORAY_GPU_SHADOW_QUEUE=1 (measuring): the shadow queue, with room for
  // 8 rays a pixel; =N for N > 1, room for N rays (the tests' overflow).
  const vk::SubgroupFeatureFlags fetch_ops = vk::SubgroupFeatureFlagBits::eBallot | vk::SubgroupFeatureFlagBits::eVote;
  if (const char* queue_env = std::getenv("HOLORAY_GPU_SHADOW_QUEUE"); queue_env && std::atoll(queue_env) > 0) {
    m.shadow_queue_on = (subgroups.supportedOperations & fetch_ops) == fetch_ops;
    m.shadow_queue_rays = std::atoll(queue_env) > 1 ? uint64_t(std::atoll(queue_env)) : 0;
  }
  // Both integrators as a wavefront on the frames where it was measured
  // faster (wavefront.cpp, wave_rule); HOLORAY_GPU_WAVEFRONT=0 never, =1
  // always (measuring).
  const char* wave_env = std::getenv("HOLORAY_GPU_WAVEFRONT");
  m.wavefront_on = (subgroups.supportedOperations & fetch_ops) == fetch_ops && !(wave_env && std::string_view(wave_env) == "0");
  m.wavefront_always = wave_env && std::string_view(wave_env) == "1";
  // Rays a lane of the wavefront's traversals, as measured (design/gpu.md,
  // "Which schedule a frame takes"): on an H200 one, in queue order (the
  // rays of a subgroup neighbours, their nodes shared: 1.21x to 1.47x the
  // speed of lanes that fetch again, though fewer lanes are busy); on
  // lavapipe, 8 (lanes that fetch again: 1.27x to 1.34x the speed of one).
  m.rays_per_lane = m.info.is_gpu ? 1u : uint32_t(HR_SHADOW_RAYS_PER_LANE);
  if (const char* lane = std::getenv("HOLORAY_GPU_RAYS_PER_LANE"))
    if (const int n = std::atoi(lane); n >= 1 && n <= 64) m.rays_per_lane = uint32_t(n);
  m.timeout_s = m.info.is_gpu ? 120.0 : 0.0;
  if (const char* t = std::getenv("HOLORAY_GPU_TIMEOUT"); t && std::atof(t) > 0) m.timeout_s = std::atof(t);
  if (const char* band_env = std::getenv("HOLORAY_GPU_BAND"); band_env && std::atoll(band_env) > 0)
    m.band_invocations = uint64_t(std::atoll(band_env));
  m.memory_types = m.physical.getMemoryProperties();
  m.max_storage_range = m.physical.getProperties().limits.maxStorageBufferRange;
  const auto families = m.physical.getQueueFamilyProperties();
  auto family = std::find_if(families.begin(), families.end(), [](const vk::QueueFamilyProperties& f) {
    return bool(f.queueFlags & vk::QueueFlagBits::eCompute);
  });
  if (family == families.end()) throw GpuError(fmt::format("the device {} has no compute queue", m.info.name));
  m.family = uint32_t(family - families.begin());
  const float priority = 1;
  vk::DeviceQueueCreateInfo qi{.queueFamilyIndex = m.family, .queueCount = 1, .pQueuePriorities = &priority};
  // HOLORAY_GPU_STATS=1 (for tuning): the driver's statistics of the
  // compiled kernel (registers, local memory) on stderr, where it offers them.
  const bool stats = std::getenv("HOLORAY_GPU_STATS") != nullptr && has_extension(m.physical, "VK_KHR_pipeline_executable_properties");
  std::vector<const char*> extensions;
  if (stats) extensions.push_back("VK_KHR_pipeline_executable_properties");
  // For a window (presenter.hpp): its swapchain, on this same device.
  m.window = !instance_extensions.empty();
  if (m.window) {
    if (!has_extension(m.physical, VK_KHR_SWAPCHAIN_EXTENSION_NAME))
      throw GpuError(fmt::format("the device {} cannot show images in a window (no {}): choose another device (`device` gpu:N)",
                                 m.info.name, VK_KHR_SWAPCHAIN_EXTENSION_NAME));
    extensions.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
  }
  vk::PhysicalDevicePipelineExecutablePropertiesFeaturesKHR stats_feature{.pipelineExecutableInfo = VK_TRUE};
  m.device = vk::raii::Device(m.physical, vk::DeviceCreateInfo{.pNext = stats ? &stats_feature : nullptr,
                                                               .queueCreateInfoCount = 1, .pQueueCreateInfos = &qi,
                                                               .enabledExtensionCount = uint32_t(extensions.size()),
                                                               .ppEnabledExtensionNames = extensions.data()});
  m.queue = vk::raii::Queue(m.device, m.family, 0);
  m.pool = vk::raii::CommandPool(m.device, vk::CommandPoolCreateInfo{.flags = vk::CommandPoolCreateFlagBits::eResetCommandBuffer,
                                                                     .queueFamilyIndex = m.family});
  std::vector<vk::DescriptorSetLayoutBinding> bindings;
  for (uint32_t b = 0; b < kBindings; ++b)
    bindings.push_back({b, vk::DescriptorType::eStorageBuffer, 1, vk::ShaderStageFlagBits::eCompute});
  m.set_layout = vk::raii::DescriptorSetLayout(m.device, vk::DescriptorSetLayoutCreateInfo{
                                                             .bindingCount = uint32_t(bindings.size()), .pBindings = bindings.data()});
  vk::PushConstantRange push{vk::ShaderStageFlagBits::eCompute, 0, 32};
  vk::DescriptorSetLayout raw_layout = *m.set_layout;
  m.pipeline_layout = vk::raii::PipelineLayout(
      m.device, vk::PipelineLayoutCreateInfo{.setLayoutCount = 1, .pSetLayouts = &raw_layout, .pushConstantRangeCount = 1,
                                             .pPushConstantRanges = &push});
  auto module_of = [&](const auto& spirv) {
    return vk::raii::ShaderModule(m.device, vk::ShaderModuleCreateInfo{.codeSize = sizeof spirv, .pCode = spirv});
  };
  m.module[0] = module_of(kTraceWhittedSpirv);
  m.module[1] = module_of(kTracePathSpirv);
  m.shade_module[0] = module_of(kShadeWhittedSpirv);
  m.shade_module[1] = module_of(kShadePathSpirv);
  m.traversal_module = module_of(kTraversalSpirv);
  // Specialization (shaders/trace.comp): the workgroup's size, 32x2 unless
  // HOLORAY_GPU_WORKGROUP=WxH says otherwise (for tuning).
  if (const char* wg = std::getenv("HOLORAY_GPU_WORKGROUP")) {
    unsigned w = 0, h = 0;
    if (std::sscanf(wg, "%ux%u", &w, &h) == 2 && w > 0 && h > 0 && w * h <= 1024) m.workgroup[0] = w, m.workgroup[1] = h;
  }
  if (const char* width = std::getenv("HOLORAY_GPU_BVH_WIDTH"); width && std::string(width) == "8") m.bvh_width = 8;
  m.capture_stats = stats;
  if (std::getenv("HOLORAY_GPU_STATS") && families[m.family].timestampValidBits > 0) {
    m.timestamps = vk::raii::QueryPool(m.device, vk::QueryPoolCreateInfo{.queryType = vk::QueryType::eTimestamp, .queryCount = 4});
    m.timestamp_ns = m.physical.getProperties().limits.timestampPeriod;
  }
  // HOLORAY_GPU_RAY_LOG=FILE: each frame's rays logged for
  // bench/ray_schedule_model.py (measuring; it counts the work to log it).
  if (const char* log = std::getenv("HOLORAY_GPU_RAY_LOG"); log && *log) m.ray_log_path = log, count_work = true;
  m.count_work = count_work;
  if (!m.ray_log_path.empty()) m.shadow_queue_on = m.wavefront_on = false;  // the log models the kernel's own schedule
  vk::raii::CommandBuffers cbs(m.device, vk::CommandBufferAllocateInfo{.commandPool = *m.pool, .commandBufferCount = 1});
  m.commands = std::move(cbs[0]);
  m.fence = vk::raii::Fence(m.device, vk::FenceCreateInfo{});
  vk::raii::CommandBuffers readback(m.device, vk::CommandBufferAllocateInfo{.commandPool = *m.pool, .commandBufferCount = 1});
  m.readback_commands = std::move(readback[0]);
  m.readback_fence = vk::raii::Fence(m.device, vk::FenceCreateInfo{});
  vk::DescriptorPoolSize size{vk::DescriptorType::eStorageBuffer, kBindings};
  m.descriptor_pool = vk::raii::DescriptorPool(
      m.device, vk::DescriptorPoolCreateInfo{.flags = vk::DescriptorPoolCreateFlagBits::eFreeDescriptorSet, .maxSets = 1,
                                             .poolSizeCount = 1, .pPoolSizes = &size});
  vk::raii::DescriptorSets sets(m.device, vk::DescriptorSetAllocateInfo{.descriptorPool = *m.descriptor_pool,
                                                                        .descriptorSetCount = 1, .pSetLayouts = &raw_layout});
  m.set = std::move(sets[0]);
}

GpuRenderer::~GpuRenderer() {
  // A device that stopped responding may still be running what it was
  // given: its buffers and its device are kept, never freed, where they
  // stay reachable (no leak report), rather than freed under it.
  if (impl_ && impl_->stopped) {
    static auto* stopped_devices = new std::vector<std::unique_ptr<Impl>>;
    stopped_devices->push_back(std::move(impl_));
  }
}

const DeviceInfo& GpuRenderer::device() const { return impl_->info; }

std::string GpuRenderer::describe() const { return fmt::format("{} ({})", impl_->info.name, impl_->info.api); }

int GpuRenderer::bvh_width() const { return impl_->bvh_width; }

uint64_t GpuRenderer::frame_bytes(int width, int height, bool aovs) {
  return uint64_t(width) * uint64_t(height) * (aovs ? 12 + 32 : 12);
}

double GpuRenderer::load(const SceneArrays& s, uint64_t image_bytes, bool panel, bool moved) {
  Impl& m = *impl_;
  m.check_responding();
  const uint64_t need = s.bytes() + image_bytes;
  if (m.info.memory_bytes && need > m.info.memory_bytes)
    throw GpuError(fmt::format("the scene needs {:.1f} MiB on the GPU and the image {:.1f} MiB, more than the {:.1f} MiB of {}",
                               s.bytes() / 1048576.0, image_bytes / 1048576.0, m.info.memory_bytes / 1048576.0, m.info.name));
  // Each array is one binding, and a binding reaches maxStorageBufferRange
  // bytes at most: past it the kernel would read what is not there.
  auto fits = [&](const char* what, uint64_t bytes) {
    if (bytes > m.max_storage_range)
      throw GpuError(fmt::format("the scene's {} take {:.1f} MiB, more than the {:.1f} MiB one buffer of {} holds "
                                 "(maxStorageBufferRange): render it on the CPU (`device` cpu)",
                                 what, bytes / 1048576.0, m.max_storage_range / 1048576.0, m.info.name));
  };
  fits("hierarchy nodes", s.nodes.size() * sizeof(GpuNode)), fits("primitive references", s.refs.size() * 4);
  fits("triangles", s.triangles.size() * sizeof(GpuTriangle)), fits("vertex normals", s.patches.size() * sizeof(GpuPatch));
  fits("vertex colours", s.colours.size() * sizeof(GpuPatch)), fits("texture coordinates", s.uvs.size() * sizeof(GpuUv));
  fits("spheres", s.spheres.size() * sizeof(GpuSphere)), fits("cones", s.cones.size() * sizeof(GpuCone));
  fits("texels", s.texels.size() * 4), fits("environment texels", s.environment.size() * sizeof(GpuEnvTexel));
  fits("emissive triangles", s.emitters.size() * sizeof(GpuEmitter));
  try {
    std::vector<Impl::ArrayUpload> arrays;
    auto put = [&](int binding, const auto& v) { arrays.push_back({binding, v.data(), v.size() * sizeof(v[0])}); };
    put(1, s.nodes), put(2, s.refs), put(3, s.triangles), put(4, s.patches), put(5, s.spheres), put(6, s.cones);
    put(7, s.object_material), put(8, s.materials), put(9, s.lights);
    put(13, s.textures), put(14, s.levels), put(15, s.texels), put(16, s.colours), put(17, s.uvs);
    put(22, s.area_lights), put(23, s.environment), put(24, s.emitters);
    m.upload_arrays(arrays, moved);
    m.scene_bytes = s.bytes();
    m.features = s.features;
    m.whitted_branches = s.whitted_branches;
    // A shot's next frame keeps the frames' buffers as the frames before
    // grew them (the same image again); a new scene starts them small.
    if (!moved || !*m.ray_log.buffer) m.reset_frame_buffers();
    if (!moved) m.last_rays_a_sample = 0;  // a new scene: the schedule's rule starts again (wave_rule)
    // The pipelines this scene's frames bind, compiled now (kept from one
    // load to the next with the same features): a frame's time is then its
    // own, and a pipeline for features the scene lacks is never compiled
    // (about 1.3 s each on lavapipe).
    const bool queue = m.shadow_queue_on && !panel && !(s.features & HR_FEATURE_PATH);
    const auto t0 = std::chrono::steady_clock::now();
    // The wavefront's, the kernel's, or both where frames may take either
    // (wave_rule; a frame that cannot take the wavefront takes the kernel).
    const Impl::WaveRule rule = m.wave_rule((s.features & HR_FEATURE_PATH) != 0);
    if (rule != Impl::WaveRule::never)
      for (int stage : {HR_WAVE_SHADING, HR_WAVE_EXTEND, HR_WAVE_SHADOW, HR_WAVE_ARGS, HR_WAVE_START, HR_WAVE_FINISH})
        m.pipeline(panel, false, 0, stage);
    if (rule != Impl::WaveRule::always)
      for (int pass = 0; pass <= (queue ? 2 : 0); ++pass) m.pipeline(panel, queue, pass);
    return seconds_since(t0);
  } catch (const vk::SystemError& e) {
    rethrow_vulkan(e, m.info.name);
  }
}

void GpuRenderer::Impl::upload_arrays(const std::vector<ArrayUpload>& arrays, bool reuse) {
  // Each array at a 16-byte-aligned offset of the staging buffer.
  std::vector<vk::DeviceSize> at;
  vk::DeviceSize total = 0;
  for (const ArrayUpload& a : arrays) at.push_back(total), total += (vk::DeviceSize(a.bytes) + 15) / 16 * 16;
  Buffer& staging = scene_staging;
  if (staging.size < total) staging = make_buffer(total, vk::BufferUsageFlagBits::eTransferSrc, true);
  for (size_t k = 0; k < arrays.size(); ++k) {
    const ArrayUpload& a = arrays[k];
    if (a.bytes) std::memcpy(static_cast<char*>(staging.mapped) + at[k], a.data, a.bytes);
    Buffer& b = scene[a.binding];
    if (reuse && b.size >= a.bytes) continue;
    b = make_buffer(a.bytes, vk::BufferUsageFlagBits::eStorageBuffer | vk::BufferUsageFlagBits::eTransferDst, false);
    bind(a.binding, b);
  }
  run_once([&](vk::raii::CommandBuffer& cb) {
    for (size_t k = 0; k < arrays.size(); ++k)
      if (arrays[k].bytes) cb.copyBuffer(*staging.buffer, *scene[arrays[k].binding].buffer, vk::BufferCopy{at[k], 0, arrays[k].bytes});
  });
}

void GpuRenderer::Impl::reset_frame_buffers() {
  scene[0] = make_buffer(sizeof(GpuFrame), vk::BufferUsageFlagBits::eStorageBuffer | vk::BufferUsageFlagBits::eTransferDst, false);
  bind(0, scene[0]);
  frames_host = make_buffer(sizeof(GpuFrame), vk::BufferUsageFlagBits::eTransferSrc, true);
  counts = make_buffer(32, kCountUsage, false);
  bind(12, counts);
  counts_host = make_buffer(32, vk::BufferUsageFlagBits::eTransferDst, true);
  ray_log = make_buffer(ray_log_path.empty() ? 32 : kRayLogBytes, vk::BufferUsageFlagBits::eStorageBuffer, true);
  bind(18, ray_log);
  shadow_queue = make_buffer(16 + sizeof(GpuShadowRay), vk::BufferUsageFlagBits::eStorageBuffer | vk::BufferUsageFlagBits::eTransferDst, false);
  bind(19, shadow_queue);
  shadow_last = make_buffer(16, vk::BufferUsageFlagBits::eStorageBuffer | vk::BufferUsageFlagBits::eTransferDst, false);
  bind(20, shadow_last);
  shadow_terms = make_buffer(16, vk::BufferUsageFlagBits::eStorageBuffer, false);
  bind(21, shadow_terms);
  const std::pair<int, Buffer*> wave_buffers[] = {{25, &wave_paths}, {26, &wave_hits}, {27, &wave_queues},
                                                  {28, &wave_shadows}, {29, &wave_shadow_queue}, {30, &wave_stack}};
  for (const auto& [binding, buffer] : wave_buffers) {
    *buffer = make_buffer(16, vk::BufferUsageFlagBits::eStorageBuffer | vk::BufferUsageFlagBits::eTransferDst, false);
    bind(binding, *buffer);
  }
}

size_t GpuRenderer::pipelines_compiled() const { return impl_->pipelines.size(); }
size_t GpuRenderer::buffers_made() const { return impl_->buffers_made; }

void GpuRenderer::release() {
  Impl& m = *impl_;
  if (m.stopped) return;  // its buffers may still be in use: kept (the destructor says why)
  for (Buffer& b : m.scene) b = Buffer{};
  for (Buffer* b : {&m.colour, &m.aov, &m.counts, &m.counts_host, &m.frames_host, &m.staging, &m.scene_staging, &m.ray_log, &m.queue_head, &m.shadow_queue, &m.shadow_last,
                    &m.shadow_terms, &m.wave_paths, &m.wave_hits, &m.wave_queues, &m.wave_shadows, &m.wave_shadow_queue,
                    &m.wave_stack})
    *b = Buffer{};
  m.scene_bytes = 0;
  m.traced = {0, 0};
  m.traced_aovs = false;
}

void GpuRenderer::render(const GpuFrame& frame, const AovSet& aovs, FrameBuffers& out, RenderStats& stats) {
  render(std::vector<GpuFrame>{frame}, frame.tile.z, frame.rows.y - frame.rows.x, aovs, out, stats);
}

void GpuRenderer::render(const std::vector<GpuFrame>& frames, int W, int H, const AovSet& aovs, FrameBuffers& out,
                         RenderStats& stats) {
  trace(frames, W, H, stats);
  readback(aovs, out, stats);
}

GpuRenderer::Impl::FramePlan GpuRenderer::Impl::plan_frame(const std::vector<GpuFrame>& frames, int W, int H) const {
  FramePlan plan;
  plan.want_aovs = frames[0].counts.y != 0;
  plan.pixels = uint64_t(W) * uint64_t(H);
  const uint64_t pixels = plan.pixels;
  const uint64_t need = frame_bytes(W, H, plan.want_aovs);
  // The shadow queue holds 8 rays a pixel, at most 2^26 rays (3 GiB) and a
  // quarter of the memory the scene and image leave: a frame that queues
  // more traces the rest where they are made, so it never refuses an image.
  const uint64_t spare = info.memory_bytes > scene_bytes + need ? (info.memory_bytes - scene_bytes - need) / 4 : 0;
  const uint64_t range = (max_storage_range - 16) / sizeof(GpuShadowRay);  // a storage buffer's largest binding
  const uint64_t queue_rays =
      shadow_queue_on ? std::min({shadow_queue_rays ? shadow_queue_rays : pixels * 8, uint64_t(1) << 26,
                                  spare / (sizeof(GpuShadowRay) + 16), range}) : 0;
  if (info.memory_bytes && scene_bytes + need > info.memory_bytes)
    throw GpuError(fmt::format("the scene needs {:.1f} MiB on the GPU and the image {:.1f} MiB, more than the {:.1f} MiB of {}",
                               scene_bytes / 1048576.0, need / 1048576.0, info.memory_bytes / 1048576.0, info.name));
  // The colours and the AOVs are each one binding (the shadow queue is sized under the limit above).
  if (const uint64_t image = pixels * (plan.want_aovs ? 32 : 12); image > max_storage_range)
    throw GpuError(fmt::format("the image's {} take {:.1f} MiB ({}x{} pixels), more than the {:.1f} MiB one buffer of {} "
                               "holds (maxStorageBufferRange): render fewer pixels at a time, or on the CPU (`device` cpu)",
                               plan.want_aovs ? "AOVs" : "colours", image / 1048576.0, W, H, max_storage_range / 1048576.0,
                               info.name));
  plan.panel = frames[0].mode.y == HR_DISPLAY || frames[0].mode.y == HR_LOOKING_GLASS;
  plan.path = (features & HR_FEATURE_PATH) != 0;
  // The wavefront holds a band's paths at once, each with room for the
  // shadow rays of one vertex (and Whitted's, its ray stack): its bands are
  // as many pixels as the device's largest binding (and a quarter of the
  // memory left) take.
  uint64_t band_pixels = band_invocations;
  const GpuFrame& f = frames[0];
  const int steps = plan.path ? std::min(f.counts.z + 1, HR_MAX_DEPTH + 1) : whitted_steps(f.counts.z, whitted_branches);
  const bool wave = steps > 0 && takes_wavefront(plan.path);
  if (wave) {
    plan.wave_steps = steps;
    plan.wave_shadows = plan.path ? uint32_t(f.counts.x + f.path_counts.x + (f.path_flags.w != 0) + (f.path_counts.y > 0))
                                  : uint32_t(f.counts.x);
    plan.wave_stack = plan.path ? 0 : uint32_t(HR_WAVE_STACK_RAYS(std::max(1, f.counts.z)));
    const uint64_t stack_bytes = uint64_t(plan.wave_stack) * 48;
    const uint64_t per_path = sizeof(GpuWavePath) + 32 + 8 + plan.wave_shadows * (sizeof(GpuWaveShadow) + 4) + stack_bytes;
    const uint64_t by_range = std::min({max_storage_range / sizeof(GpuWavePath),
                                        max_storage_range / std::max<uint64_t>(1, plan.wave_shadows * sizeof(GpuWaveShadow)),
                                        max_storage_range / std::max<uint64_t>(1, stack_bytes)});
    const uint64_t by_memory = spare >= per_path ? spare / per_path : band_pixels;
    band_pixels = std::max<uint64_t>(1, std::min({band_pixels, by_range, by_memory}));
  }
  for (size_t f = 0; f < frames.size(); ++f) {
    const int w = frames[f].size.x, y0 = frames[f].rows.x, y1 = frames[f].rows.y;
    const int fit = int(std::min<uint64_t>(band_pixels / uint64_t(std::max(1, w)), 1 << 20));
    const int band_rows = wave ? std::max(1, fit >= 8 ? fit / 8 * 8 : fit) : std::max(8, fit / 8 * 8);
    for (int row0 = y0; row0 < y1; row0 += band_rows) {
      plan.bands.push_back({row0, std::min(band_rows, y1 - row0), int32_t(f), uint32_t(w)});
      if (wave) plan.wave_paths = std::max(plan.wave_paths, uint64_t(w) * uint64_t(plan.bands.back().rows));
    }
  }
  plan.queue = queue_rays > 0 && !plan.panel && !plan.path && !wave;  // a path traces its own, as the wavefront does
  plan.queue_rays = plan.queue ? queue_rays : 0;
  plan.passes = plan.path || wave ? std::max(1, frames[0].mode.w) : 1;
  return plan;
}

void GpuRenderer::Impl::prepare_frame(const std::vector<GpuFrame>& frames, const FramePlan& plan) {
  const uint64_t pixels = plan.pixels;
  const vk::BufferUsageFlags usage = vk::BufferUsageFlagBits::eStorageBuffer | vk::BufferUsageFlagBits::eTransferSrc;
  if (colour.size < pixels * 12) {
    colour = make_buffer(pixels * 12, usage, false);
    bind(10, colour);
  }
  const uint64_t aov_size = plan.want_aovs ? pixels * 32 : 16;
  if (aov.size < aov_size) {
    aov = make_buffer(aov_size, usage, false);
    bind(11, aov);
  }
  const uint64_t count_bytes = uint64_t(plan.bands.size()) * HR_COUNT_SLOTS * 32;
  if (counts.size < count_bytes) {
    counts = make_buffer(count_bytes, kCountUsage, false);
    bind(12, counts);
    counts_host = make_buffer(count_bytes, vk::BufferUsageFlagBits::eTransferDst, true);
  }
  const uint64_t constants = frames.size() * sizeof(GpuFrame);
  if (scene[0].size < constants) {
    scene[0] = make_buffer(constants, vk::BufferUsageFlagBits::eStorageBuffer | vk::BufferUsageFlagBits::eTransferDst, false);
    bind(0, scene[0]);
    frames_host = make_buffer(constants, vk::BufferUsageFlagBits::eTransferSrc, true);
  }
  std::memcpy(frames_host.mapped, frames.data(), constants);
  std::memset(ray_log.mapped, 0, 16);
  vk::raii::CommandBuffer& cb = commands;
  cb.reset();
  cb.begin(vk::CommandBufferBeginInfo{.flags = vk::CommandBufferUsageFlagBits::eOneTimeSubmit});
  cb.copyBuffer(*frames_host.buffer, *scene[0].buffer, vk::BufferCopy{0, 0, constants});
  cb.fillBuffer(*counts.buffer, 0, count_bytes, 0);
  barrier(vk::PipelineStageFlagBits::eTransfer);
  if (plan.wave_paths > 0) prepare_wavefront(plan);
  if (!plan.queue) return;
  const uint64_t queue_rays = plan.queue_rays;
  if (shadow_queue.size < 16 + queue_rays * sizeof(GpuShadowRay)) {
    shadow_queue = make_buffer(16 + queue_rays * sizeof(GpuShadowRay),
                               vk::BufferUsageFlagBits::eStorageBuffer | vk::BufferUsageFlagBits::eTransferDst |
                                   vk::BufferUsageFlagBits::eTransferSrc, false);
    bind(19, shadow_queue);
  }
  if (shadow_terms.size < queue_rays * 16) {
    shadow_terms = make_buffer(queue_rays * 16, vk::BufferUsageFlagBits::eStorageBuffer, false);
    bind(21, shadow_terms);
  }
  if (shadow_last.size < pixels * 4) {
    shadow_last = make_buffer(pixels * 4, vk::BufferUsageFlagBits::eStorageBuffer | vk::BufferUsageFlagBits::eTransferDst, false);
    bind(20, shadow_last);
  }
  cb.fillBuffer(*shadow_queue.buffer, 0, 16, 0);
  cb.fillBuffer(*shadow_queue.buffer, 8, 4, uint32_t(queue_rays));  // its capacity
  cb.fillBuffer(*shadow_last.buffer, 0, VK_WHOLE_SIZE, 0xffffffffu);  // a pixel no dispatch writes has no runs
  cb.pipelineBarrier(vk::PipelineStageFlagBits::eTransfer, vk::PipelineStageFlagBits::eComputeShader, {},
                     vk::MemoryBarrier{.srcAccessMask = vk::AccessFlagBits::eTransferWrite, .dstAccessMask = vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eShaderWrite},
                     nullptr, nullptr);
}

void GpuRenderer::Impl::submit_and_wait(const char* what) {
  // The counters so far copied out for the host (sum_counts).
  commands.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader, vk::PipelineStageFlagBits::eTransfer, {},
                           vk::MemoryBarrier{.srcAccessMask = vk::AccessFlagBits::eShaderWrite,
                                             .dstAccessMask = vk::AccessFlagBits::eTransferRead},
                           nullptr, nullptr);
  commands.copyBuffer(*counts.buffer, *counts_host.buffer, vk::BufferCopy{0, 0, std::min(counts.size, counts_host.size)});
  commands.pipelineBarrier(vk::PipelineStageFlagBits::eTransfer, vk::PipelineStageFlagBits::eHost, {},
                           vk::MemoryBarrier{.srcAccessMask = vk::AccessFlagBits::eTransferWrite,
                                             .dstAccessMask = vk::AccessFlagBits::eHostRead},
                           nullptr, nullptr);
  commands.end();
  vk::CommandBuffer raw = *commands;
  queue.submit(vk::SubmitInfo{.commandBufferCount = 1, .pCommandBuffers = &raw}, *fence);
  wait(fence, what);
  device.resetFences({*fence});
}

void GpuRenderer::Impl::record_pixel_passes(const FramePlan& plan, int first_sample) {
  if (plan.wave_paths > 0) return record_wavefront_passes(plan, first_sample);
  const int from = first_sample;
  vk::raii::CommandBuffer& cb = commands;
  auto bind_kernel = [&] {
    cb.bindPipeline(vk::PipelineBindPoint::eCompute, *pipeline(plan.panel, plan.queue, 0));
    cb.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *pipeline_layout, 0, {*set}, nullptr);
  };
  bind_kernel();
  // The path integrator takes one sample of every pixel a pass, each
  // pass adding to the colours the one before wrote: an invocation's
  // loops then stay inside lavapipe's 65535 iterations whatever the
  // samples per pixel (shared/docs/gpu-notes.md), and no dispatch runs
  // longer for them.
  // The passes go in submissions of about 4 bands' pixel samples (2^22; one
  // pass at least), each waited on under the timeout (wait()): a submission
  // is a bounded piece of work however many samples a pixel the render
  // takes, so a fixed wait can tell a device that stopped from a long
  // render. (A submission a pass cost a 128x128 view 2.5 % of its trace
  // on lavapipe, in waits.)
  const int per_submission = passes_per_submission(plan);
  for (int pass = from; pass < plan.passes; ++pass) {
    if (pass > from && (pass - from) % per_submission == 0) {
      next_submission();
      bind_kernel();
    }
    if (pass > from)
      cb.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader, vk::PipelineStageFlagBits::eComputeShader, {},
                         vk::MemoryBarrier{.srcAccessMask = vk::AccessFlagBits::eShaderWrite,
                                           .dstAccessMask = vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eShaderWrite},
                         nullptr, nullptr);
    for (size_t b = 0; b < plan.bands.size(); ++b) {
      const Band& band = plan.bands[b];
      cb.pushConstants<int32_t>(*pipeline_layout, vk::ShaderStageFlagBits::eCompute, 0,
                                {band.row0, band.rows, int32_t(b), band.frame, pass, first_sample});
      cb.dispatch((band.width + workgroup[0] - 1) / workgroup[0], (uint32_t(band.rows) + workgroup[1] - 1) / workgroup[1], 1);
    }
  }
}

void GpuRenderer::Impl::record_shadow_passes(const FramePlan& plan) {
  vk::raii::CommandBuffer& cb = commands;
  // The queued shadow rays, once every band has queued its own.
  const vk::MemoryBarrier written{.srcAccessMask = vk::AccessFlagBits::eShaderWrite,
                                  .dstAccessMask = vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eShaderWrite};
  cb.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader, vk::PipelineStageFlagBits::eComputeShader, {}, written, nullptr, nullptr);
  // Both passes in bands of at most band_invocations invocations, each its
  // own dispatch, as the pixels' are (issue 71: no dispatch sized by the
  // frame). The shadow pass's lanes fetch from one queue, so its bands need
  // nothing more; the resolve's are told their first pixel.
  const uint64_t group = workgroup[0] * workgroup[1];
  const uint64_t band_groups = std::max<uint64_t>(1, band_invocations / group);
  auto dispatch_over = [&](uint64_t invocations, auto&& before_band) {
    const uint64_t groups = std::max<uint64_t>(1, (invocations + group - 1) / group);
    for (uint64_t first = 0; first < groups; first += band_groups) {
      const uint64_t n = std::min(band_groups, groups - first);
      before_band(first * group);
      const uint32_t gx = uint32_t(std::min<uint64_t>(n, 65535));
      cb.dispatch(gx, uint32_t((n + gx - 1) / gx), 1);
    }
  };
  cb.bindPipeline(vk::PipelineBindPoint::eCompute, *pipeline(plan.panel, plan.queue, 1));
  dispatch_over((plan.queue_rays + HR_SHADOW_RAYS_PER_LANE - 1) / HR_SHADOW_RAYS_PER_LANE, [](uint64_t) {});
  if (*timestamps) cb.writeTimestamp(vk::PipelineStageFlagBits::eBottomOfPipe, *timestamps, 2);
  cb.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader, vk::PipelineStageFlagBits::eComputeShader, {}, written, nullptr, nullptr);
  cb.bindPipeline(vk::PipelineBindPoint::eCompute, *pipeline(plan.panel, plan.queue, 2));
  dispatch_over(plan.pixels, [&](uint64_t first_pixel) {
    cb.pushConstants<int32_t>(*pipeline_layout, vk::ShaderStageFlagBits::eCompute, 0,
                              {int32_t(plan.pixels), int32_t(first_pixel), 0, 0});
  });
  if (!*timestamps) return;
  cb.writeTimestamp(vk::PipelineStageFlagBits::eBottomOfPipe, *timestamps, 3);
  if (!queue_head.mapped) queue_head = make_buffer(16, vk::BufferUsageFlagBits::eTransferDst, true);
  cb.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader, vk::PipelineStageFlagBits::eTransfer, {},
                     vk::MemoryBarrier{.srcAccessMask = vk::AccessFlagBits::eShaderWrite, .dstAccessMask = vk::AccessFlagBits::eTransferRead},
                     nullptr, nullptr);
  cb.copyBuffer(*shadow_queue.buffer, *queue_head.buffer, vk::BufferCopy{0, 0, 16});
}

void GpuRenderer::Impl::print_pass_times(const FramePlan& plan) {
  const uint32_t n = plan.queue ? 4 : 2;
  const auto got = timestamps.getResults<uint64_t>(0, n, n * sizeof(uint64_t), sizeof(uint64_t),
                                                   vk::QueryResultFlagBits::e64 | vk::QueryResultFlagBits::eWait);
  const vk::Result result = got.first;
  const std::vector<uint64_t>& t = got.second;  // not a structured binding: a lambda below reads it (clang 14)
  auto ms = [&](uint32_t a, uint32_t b) { return double(t[b] - t[a]) * timestamp_ns * 1e-6; };
  const uint64_t made = plan.queue ? static_cast<const uint32_t*>(queue_head.mapped)[0] : 0;
  const uint64_t queued = std::min(made, plan.queue_rays), past = made - queued;
  if (result == vk::Result::eSuccess)
    std::fprintf(stderr, "holoray gpu: pixel kernel %.3f ms, shadow pass %.3f ms, resolve %.3f ms; shadow queue of %llu rays: %llu queued, %llu traced where made\n",
                 ms(0, 1), plan.queue ? ms(1, 2) : 0.0, plan.queue ? ms(2, 3) : 0.0, (unsigned long long)plan.queue_rays,
                 (unsigned long long)queued, (unsigned long long)past);
}

void GpuRenderer::Impl::sum_counts(const FramePlan& plan, RenderStats& stats) const {
  const uint32_t* c = static_cast<const uint32_t*>(counts_host.mapped);
  for (size_t b = 0; b < plan.bands.size() * HR_COUNT_SLOTS; ++b, c += 8) {
    stats.nodes_visited += c[0], stats.primitives_tested += c[1], stats.lane_steps += c[2];
    stats.rays.eye += c[4], stats.rays.shadow += c[5], stats.rays.reflected += c[6], stats.rays.refracted += c[7];
  }
}

void GpuRenderer::trace(const std::vector<GpuFrame>& frames, int W, int H, RenderStats& stats, int first_sample) {
  Impl& m = *impl_;
  m.check_responding();
  if (!m.frames_host.mapped) throw std::logic_error("GpuRenderer::render before load");
  if (frames.empty()) throw std::logic_error("GpuRenderer::render without a frame");
  const Impl::FramePlan plan = m.plan_frame(frames, W, H);
  if (first_sample < 0 || (first_sample > 0 && (!plan.path || first_sample >= plan.passes)))
    throw std::logic_error("GpuRenderer::trace: a first sample past the samples per pixel, or without the path integrator");
  try {
    m.prepare_frame(frames, plan);
    stats = RenderStats{};
    vk::raii::CommandBuffer& cb = m.commands;
    if (*m.timestamps) {
      cb.resetQueryPool(*m.timestamps, 0, 4);
      cb.writeTimestamp(vk::PipelineStageFlagBits::eBottomOfPipe, *m.timestamps, 0);
    }
    const auto t0 = std::chrono::steady_clock::now();
    m.record_pixel_passes(plan, first_sample);
    if (*m.timestamps) cb.writeTimestamp(vk::PipelineStageFlagBits::eBottomOfPipe, *m.timestamps, 1);
    if (plan.queue) m.record_shadow_passes(plan);
    m.submit_and_wait("the frame");
    stats.trace_seconds = seconds_since(t0);
    if (*m.timestamps) m.print_pass_times(plan);
    if (plan.wave_paths > 0) m.print_wave_times();
    // HOLORAY_GPU_FAULT=device-lost or out-of-memory (for the tests, where no
    // device fails on demand): the frame ends as that fault would end it.
    if (const char* fault = std::getenv("HOLORAY_GPU_FAULT")) {
      if (std::string_view(fault) == "device-lost") throw vk::DeviceLostError("vkQueueSubmit");
      if (std::string_view(fault) == "out-of-memory") throw vk::OutOfDeviceMemoryError("vkAllocateMemory");
    }
    m.sum_counts(plan, stats);
    const double samples = double(W) * H * (plan.passes - first_sample);
    m.last_rays_a_sample = samples > 0 ? double(stats.rays.total()) / samples : 0;
    if (!m.ray_log_path.empty()) write_ray_log(m.ray_log, m.ray_log_path, m.workgroup, W, H);
    m.traced = {W, H};
    m.traced_aovs = plan.want_aovs;
  } catch (const vk::SystemError& e) {
    rethrow_vulkan(e, m.info.name);
  }
}

void GpuRenderer::readback(const AovSet& aovs, FrameBuffers& out, RenderStats& stats) {
  Impl& m = *impl_;
  m.check_responding();
  const int W = m.traced[0], H = m.traced[1];
  if (W == 0) throw std::logic_error("GpuRenderer::readback before trace");
  const bool want_aovs = m.traced_aovs;
  const uint64_t pixels = uint64_t(W) * uint64_t(H);
  try {
    const auto t1 = std::chrono::steady_clock::now();
    const uint64_t readback = pixels * 12 + (want_aovs ? pixels * 32 : 0);
    if (m.staging.size < readback) m.staging = m.make_buffer(readback, vk::BufferUsageFlagBits::eTransferDst, true);
    Buffer& staging = m.staging;
    vk::raii::CommandBuffer& rc = m.readback_commands;
    rc.reset();
    rc.begin(vk::CommandBufferBeginInfo{.flags = vk::CommandBufferUsageFlagBits::eOneTimeSubmit});
    rc.copyBuffer(*m.colour.buffer, *staging.buffer, vk::BufferCopy{0, 0, pixels * 12});
    if (want_aovs) rc.copyBuffer(*m.aov.buffer, *staging.buffer, vk::BufferCopy{0, pixels * 12, pixels * 32});
    rc.end();
    vk::CommandBuffer raw_readback = *rc;
    m.queue.submit(vk::SubmitInfo{.commandBufferCount = 1, .pCommandBuffers = &raw_readback}, *m.readback_fence);
    m.wait(m.readback_fence, "the image's copy back");
    m.device.resetFences({*m.readback_fence});
    // Out of the staging buffer in bands of rows on every core: the colour
    // as it is, the AOVs' interleaved records split into their images.
    const float* colour = static_cast<const float*>(staging.mapped);
    const float* a = colour + pixels * 3;
    constexpr int kRows = 64;
    parallel_for_n((H + kRows - 1) / kRows, 0, [&](int band) {
      const int j0 = band * kRows, j1 = std::min(H, j0 + kRows);
      std::memcpy(out.colour.at(0, j0), colour + uint64_t(j0) * W * 3, uint64_t(j1 - j0) * W * 12);
      if (!want_aovs) return;
      for (int j = j0; j < j1; ++j)
        for (int i = 0; i < W; ++i) {
          const float* p = a + (uint64_t(j) * W + i) * 8;
          if (aovs.albedo) std::memcpy(out.albedo.at(i, j), p, 12);
          if (aovs.depth) *out.depth.at(i, j) = p[3];
          if (aovs.normal) std::memcpy(out.normal.at(i, j), p + 4, 12);
          if (aovs.id) *out.id.at(i, j) = p[7];
        }
    });
    stats.readback_seconds = seconds_since(t1);
  } catch (const vk::SystemError& e) {
    rethrow_vulkan(e, m.info.name);
  }
}

}  // namespace holoray::gpu
