#include "gpu/shared_functions.hpp"

#include <stdexcept>

#include "gpu/vulkan_device.hpp"

namespace holoray::gpu {

namespace {

const uint32_t kSharedSpirv[] = {
#include "shared_functions.spv.inc"
};

}  // namespace

std::vector<float> run_shared_functions(const std::vector<float>& inputs, SharedSuite suite) {
  if (inputs.size() % kSharedCaseInputs)
    throw std::invalid_argument(fmt::format("{} inputs are not whole cases of {}", inputs.size(), kSharedCaseInputs));
  const uint32_t cases = static_cast<uint32_t>(inputs.size() / kSharedCaseInputs);
  vk::raii::Context context = open_loader();
  vk::raii::Instance instance = make_instance(context, {});
  std::vector<vk::raii::PhysicalDevice> all = instance.enumeratePhysicalDevices();
  if (all.empty()) throw GpuError("Vulkan lists no device on this machine");
  size_t pick = 0;
  for (size_t k = 0; k < all.size(); ++k) {
    const auto type = all[k].getProperties().deviceType;
    if (type == vk::PhysicalDeviceType::eDiscreteGpu || type == vk::PhysicalDeviceType::eIntegratedGpu) {
      pick = k;
      break;
    }
  }
  const vk::raii::PhysicalDevice& physical = all[pick];
  const std::string name = physical.getProperties().deviceName.data();
  try {
    const auto families = physical.getQueueFamilyProperties();
    uint32_t family = 0;
    while (family < families.size() && !(families[family].queueFlags & vk::QueueFlagBits::eCompute)) ++family;
    if (family == families.size()) throw GpuError(fmt::format("the device {} has no compute queue", name));
    const float priority = 1;
    vk::DeviceQueueCreateInfo qi{.queueFamilyIndex = family, .queueCount = 1, .pQueuePriorities = &priority};
    vk::raii::Device device(physical, vk::DeviceCreateInfo{.queueCreateInfoCount = 1, .pQueueCreateInfos = &qi});
    vk::raii::Queue queue(device, family, 0);
    const vk::PhysicalDeviceMemoryProperties types = physical.getMemoryProperties();
    // Host-visible storage buffers: the cases are few, the copy is nothing.
    auto make = [&](vk::DeviceSize size, vk::raii::Buffer& buffer, vk::raii::DeviceMemory& memory) {
      buffer = vk::raii::Buffer(device, vk::BufferCreateInfo{.size = size, .usage = vk::BufferUsageFlagBits::eStorageBuffer});
      const vk::MemoryRequirements req = buffer.getMemoryRequirements();
      const vk::MemoryPropertyFlags want = vk::MemoryPropertyFlagBits::eHostVisible | vk::MemoryPropertyFlagBits::eHostCoherent;
      uint32_t t = 0;
      while (t < types.memoryTypeCount && (!(req.memoryTypeBits & (1u << t)) || (types.memoryTypes[t].propertyFlags & want) != want)) ++t;
      if (t == types.memoryTypeCount) throw GpuError(fmt::format("the device {} has no host-visible memory", name));
      memory = vk::raii::DeviceMemory(device, vk::MemoryAllocateInfo{.allocationSize = req.size, .memoryTypeIndex = t});
      buffer.bindMemory(*memory, 0);
      return memory.mapMemory(0, size);
    };
    vk::raii::Buffer in_buffer = nullptr, out_buffer = nullptr;
    vk::raii::DeviceMemory in_memory = nullptr, out_memory = nullptr;
    const vk::DeviceSize in_bytes = inputs.size() * sizeof(float), out_bytes = size_t{cases} * kSharedCaseOutputs * sizeof(float);
    std::memcpy(make(in_bytes, in_buffer, in_memory), inputs.data(), in_bytes);
    void* out_mapped = make(out_bytes, out_buffer, out_memory);

    const vk::DescriptorSetLayoutBinding bindings[2] = {{0, vk::DescriptorType::eStorageBuffer, 1, vk::ShaderStageFlagBits::eCompute},
                                                        {1, vk::DescriptorType::eStorageBuffer, 1, vk::ShaderStageFlagBits::eCompute}};
    vk::raii::DescriptorSetLayout set_layout(device, vk::DescriptorSetLayoutCreateInfo{.bindingCount = 2, .pBindings = bindings});
    const vk::PushConstantRange push{vk::ShaderStageFlagBits::eCompute, 0, 8};
    const vk::DescriptorSetLayout raw_layout = *set_layout;
    vk::raii::PipelineLayout layout(device, vk::PipelineLayoutCreateInfo{.setLayoutCount = 1, .pSetLayouts = &raw_layout,
                                                                         .pushConstantRangeCount = 1, .pPushConstantRanges = &push});
    vk::raii::ShaderModule module(device, vk::ShaderModuleCreateInfo{.codeSize = sizeof(kSharedSpirv), .pCode = kSharedSpirv});
    vk::raii::Pipeline pipeline(device, nullptr,
                                vk::ComputePipelineCreateInfo{.stage = {.stage = vk::ShaderStageFlagBits::eCompute,
                                                                        .module = *module, .pName = "main"},
                                                              .layout = *layout});
    const vk::DescriptorPoolSize pool_size{vk::DescriptorType::eStorageBuffer, 2};
    vk::raii::DescriptorPool pool(device, vk::DescriptorPoolCreateInfo{.flags = vk::DescriptorPoolCreateFlagBits::eFreeDescriptorSet,
                                                                      .maxSets = 1, .poolSizeCount = 1, .pPoolSizes = &pool_size});
    vk::raii::DescriptorSets sets(device, vk::DescriptorSetAllocateInfo{.descriptorPool = *pool, .descriptorSetCount = 1,
                                                                        .pSetLayouts = &raw_layout});
    const vk::DescriptorBufferInfo infos[2] = {{*in_buffer, 0, VK_WHOLE_SIZE}, {*out_buffer, 0, VK_WHOLE_SIZE}};
    for (uint32_t b = 0; b < 2; ++b)
      device.updateDescriptorSets(vk::WriteDescriptorSet{.dstSet = *sets[0], .dstBinding = b, .descriptorCount = 1,
                                                         .descriptorType = vk::DescriptorType::eStorageBuffer, .pBufferInfo = &infos[b]},
                                  nullptr);
    vk::raii::CommandPool command_pool(device, vk::CommandPoolCreateInfo{.queueFamilyIndex = family});
    vk::raii::CommandBuffers cbs(device, vk::CommandBufferAllocateInfo{.commandPool = *command_pool, .commandBufferCount = 1});
    vk::raii::CommandBuffer& cb = cbs[0];
    cb.begin(vk::CommandBufferBeginInfo{.flags = vk::CommandBufferUsageFlagBits::eOneTimeSubmit});
    cb.bindPipeline(vk::PipelineBindPoint::eCompute, *pipeline);
    cb.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *layout, 0, {*sets[0]}, nullptr);
    const uint32_t push_values[2] = {cases, static_cast<uint32_t>(suite)};
    cb.pushConstants<uint32_t>(*layout, vk::ShaderStageFlagBits::eCompute, 0, push_values);
    cb.dispatch((cases + 63) / 64, 1, 1);
    const vk::MemoryBarrier to_host{.srcAccessMask = vk::AccessFlagBits::eShaderWrite, .dstAccessMask = vk::AccessFlagBits::eHostRead};
    cb.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader, vk::PipelineStageFlagBits::eHost, {}, to_host, nullptr, nullptr);
    cb.end();
    vk::raii::Fence fence(device, vk::FenceCreateInfo{});
    const vk::CommandBuffer raw = *cb;
    queue.submit(vk::SubmitInfo{.commandBufferCount = 1, .pCommandBuffers = &raw}, *fence);
    // Ten seconds: the kernel is a few thousand cases; a device that takes
    // longer has stopped.
    if (device.waitForFences({*fence}, VK_TRUE, 10'000'000'000ull) != vk::Result::eSuccess)
      throw GpuError(fmt::format("the GPU ({}) stopped responding", name));
    std::vector<float> out(size_t{cases} * kSharedCaseOutputs);
    std::memcpy(out.data(), out_mapped, out_bytes);
    return out;
  } catch (const vk::SystemError& e) {
    rethrow_vulkan(e, name);
  }
}

}  // namespace holoray::gpu
