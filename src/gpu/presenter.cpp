#include "gpu/presenter.hpp"

#include <algorithm>
#include <cmath>

#include "gpu/vulkan_device.hpp"

namespace holoray::gpu {

namespace {

// SPIR-V of shaders/pack.comp, made by glslc at build time.
const uint32_t kPackSpirv[] = {
#include "pack.spv.inc"
};

// The frame is packed as B8G8R8A8 and blitted into the swapchain's image,
// which converts to the window's byte order where it differs.
constexpr vk::Format kPacked = vk::Format::eB8G8R8A8Unorm;

vk::ImageMemoryBarrier layout_change(vk::Image image, vk::ImageLayout from, vk::ImageLayout to, vk::AccessFlags src,
                                     vk::AccessFlags dst) {
  return vk::ImageMemoryBarrier{.srcAccessMask = src, .dstAccessMask = dst, .oldLayout = from, .newLayout = to,
                                .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED, .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                                .image = image,
                                .subresourceRange = {vk::ImageAspectFlagBits::eColor, 0, 1, 0, 1}};
}

}  // namespace

struct Presenter::Impl {
  GpuRenderer::Impl& r;
  vk::raii::SurfaceKHR surface = nullptr;
  vk::raii::SwapchainKHR swapchain = nullptr;
  std::vector<vk::Image> images;
  vk::Extent2D extent{0, 0};
  std::array<int, 2> window{-1, -1};  // the framebuffer size the swapchain was made for
  vk::raii::DescriptorSetLayout set_layout = nullptr;
  vk::raii::PipelineLayout pipeline_layout = nullptr;
  vk::raii::ShaderModule module = nullptr;
  vk::raii::Pipeline pipeline = nullptr;
  vk::raii::DescriptorPool descriptor_pool = nullptr;
  vk::raii::DescriptorSet set = nullptr;
  Buffer thresholds, packed;
  Buffer host_image;  // show_image's, host-visible
  Buffer shown_copy;  // shown_rgb's, host-visible, kept for the next (--record asks every frame)
  // The packed frame as an image, the blit's source.
  vk::raii::Image frame = nullptr;
  vk::raii::DeviceMemory frame_memory = nullptr;
  std::array<int32_t, 2> frame_size{0, 0};
  std::array<int32_t, 2> shown{0, 0};
  vk::raii::CommandBuffer commands = nullptr;
  vk::raii::Fence fence = nullptr;
  vk::raii::Semaphore acquired = nullptr;
  std::vector<vk::raii::Semaphore> presentable;  // one per swapchain image
  // Offscreen (no surface): the image each frame is copied to in place of
  // the swapchain's, the window's size.
  bool offscreen = false;
  vk::raii::Image target = nullptr;
  vk::raii::DeviceMemory target_memory = nullptr;

  explicit Impl(GpuRenderer::Impl& renderer) : r(renderer) {}

  // A device-local image of `size` pixels in the packed format, the copy's
  // destination and source.
  std::pair<vk::raii::Image, vk::raii::DeviceMemory> make_image(std::array<int32_t, 2> size) {
    vk::raii::Image image(r.device, vk::ImageCreateInfo{.imageType = vk::ImageType::e2D, .format = kPacked,
                                                        .extent = {uint32_t(size[0]), uint32_t(size[1]), 1}, .mipLevels = 1,
                                                        .arrayLayers = 1, .samples = vk::SampleCountFlagBits::e1,
                                                        .tiling = vk::ImageTiling::eOptimal,
                                                        .usage = vk::ImageUsageFlagBits::eTransferDst | vk::ImageUsageFlagBits::eTransferSrc,
                                                        .sharingMode = vk::SharingMode::eExclusive,
                                                        .initialLayout = vk::ImageLayout::eUndefined});
    const vk::MemoryRequirements req = image.getMemoryRequirements();
    vk::raii::DeviceMemory memory(r.device, vk::MemoryAllocateInfo{.allocationSize = req.size,
                                                                   .memoryTypeIndex = r.memory_type(req.memoryTypeBits,
                                                                                                    vk::MemoryPropertyFlagBits::eDeviceLocal)});
    image.bindMemory(*memory, 0);
    return {std::move(image), std::move(memory)};
  }

  // The offscreen target for a `size` window.
  void make_target(std::array<int, 2> size) {
    r.device.waitIdle();
    auto [image, memory] = make_image({size[0], size[1]});
    target = std::move(image), target_memory = std::move(memory);
    extent = vk::Extent2D{uint32_t(size[0]), uint32_t(size[1])};
    window = size;
  }

  // The swapchain for a `size` framebuffer; extent 0 x 0 when there is
  // nothing to show (minimised).
  void make_swapchain(std::array<int, 2> size) {
    r.device.waitIdle();
    window = size;
    const vk::SurfaceCapabilitiesKHR caps = r.physical.getSurfaceCapabilitiesKHR(*surface);
    extent = caps.currentExtent.width != UINT32_MAX
                 ? caps.currentExtent
                 : vk::Extent2D{std::clamp(uint32_t(std::max(0, size[0])), caps.minImageExtent.width, caps.maxImageExtent.width),
                                std::clamp(uint32_t(std::max(0, size[1])), caps.minImageExtent.height, caps.maxImageExtent.height)};
    if (extent.width == 0 || extent.height == 0) return;
    if (!(caps.supportedUsageFlags & vk::ImageUsageFlagBits::eTransferDst))
      throw GpuError(fmt::format("the device {} cannot copy into this window's images (no TRANSFER_DST usage)", r.info.name));
    std::optional<vk::SurfaceFormatKHR> chosen;
    for (const vk::SurfaceFormatKHR& f : r.physical.getSurfaceFormatsKHR(*surface))
      if ((f.format == vk::Format::eB8G8R8A8Unorm || f.format == vk::Format::eR8G8B8A8Unorm) &&
          (!chosen || f.format == kPacked))
        chosen = f;
    if (!chosen)
      throw GpuError(fmt::format("this window offers the device {} no 8-bit UNORM format (B8G8R8A8 or R8G8B8A8)", r.info.name));
    if (!(r.physical.getFormatProperties(chosen->format).optimalTilingFeatures & vk::FormatFeatureFlagBits::eBlitDst))
      throw GpuError(fmt::format("the device {} cannot blit into this window's images", r.info.name));
    uint32_t count = std::max(caps.minImageCount, 2u);
    if (caps.maxImageCount) count = std::min(count, caps.maxImageCount);
    vk::CompositeAlphaFlagBitsKHR alpha = vk::CompositeAlphaFlagBitsKHR::eOpaque;
    if (!(caps.supportedCompositeAlpha & alpha))
      for (auto a : {vk::CompositeAlphaFlagBitsKHR::eInherit, vk::CompositeAlphaFlagBitsKHR::ePreMultiplied,
                     vk::CompositeAlphaFlagBitsKHR::ePostMultiplied})
        if (caps.supportedCompositeAlpha & a) {
          alpha = a;
          break;
        }
    // FIFO: vsync, the one mode every device offers.
    swapchain = vk::raii::SwapchainKHR(
        r.device, vk::SwapchainCreateInfoKHR{.surface = *surface, .minImageCount = count, .imageFormat = chosen->format,
                                             .imageColorSpace = chosen->colorSpace, .imageExtent = extent, .imageArrayLayers = 1,
                                             .imageUsage = vk::ImageUsageFlagBits::eTransferDst,
                                             .imageSharingMode = vk::SharingMode::eExclusive, .preTransform = caps.currentTransform,
                                             .compositeAlpha = alpha, .presentMode = vk::PresentModeKHR::eFifo, .clipped = VK_TRUE,
                                             .oldSwapchain = *swapchain});
    images = swapchain.getImages();
    presentable.clear();
    for (size_t k = 0; k < images.size(); ++k) presentable.emplace_back(r.device, vk::SemaphoreCreateInfo{});
  }

  // The packed buffer and the blit's source image for `size` pixels.
  void make_frame(std::array<int32_t, 2> size) {
    const vk::DeviceSize bytes = vk::DeviceSize(size[0]) * vk::DeviceSize(size[1]) * 4;
    if (packed.size < bytes)
      packed = r.make_buffer(bytes, vk::BufferUsageFlagBits::eStorageBuffer | vk::BufferUsageFlagBits::eTransferSrc, false);
    if (frame_size == size) return;
    auto [image, memory] = make_image(size);
    frame = std::move(image), frame_memory = std::move(memory);
    frame_size = size;
  }

  void bind(uint32_t binding, const Buffer& b) {
    vk::DescriptorBufferInfo bi{*b.buffer, 0, VK_WHOLE_SIZE};
    r.device.updateDescriptorSets(vk::WriteDescriptorSet{.dstSet = *set, .dstBinding = binding, .descriptorCount = 1,
                                                         .descriptorType = vk::DescriptorType::eStorageBuffer, .pBufferInfo = &bi},
                                  nullptr);
  }

  // The pack, its copy to the frame image and the letterboxed blit into
  // `target`, left in `final_layout` (the swapchain's present layout, or
  // the offscreen target's transfer source).
  void record(const PackParams& p, vk::Image target, vk::ImageLayout final_layout) {
    vk::raii::CommandBuffer& cb = commands;
    cb.reset();
    cb.begin(vk::CommandBufferBeginInfo{.flags = vk::CommandBufferUsageFlagBits::eOneTimeSubmit});
    // The trace's writes (an earlier submission on this queue) before the pack reads them.
    cb.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader, vk::PipelineStageFlagBits::eComputeShader, {},
                       vk::MemoryBarrier{.srcAccessMask = vk::AccessFlagBits::eShaderWrite, .dstAccessMask = vk::AccessFlagBits::eShaderRead},
                       nullptr, nullptr);
    cb.bindPipeline(vk::PipelineBindPoint::eCompute, *pipeline);
    cb.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *pipeline_layout, 0, {*set}, nullptr);
    cb.pushConstants<PackParams>(*pipeline_layout, vk::ShaderStageFlagBits::eCompute, 0, p);
    cb.dispatch((uint32_t(p.shown[0]) + 15) / 16, (uint32_t(p.shown[1]) + 15) / 16, 1);
    cb.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader, vk::PipelineStageFlagBits::eTransfer, {},
                       vk::MemoryBarrier{.srcAccessMask = vk::AccessFlagBits::eShaderWrite, .dstAccessMask = vk::AccessFlagBits::eTransferRead},
                       nullptr,
                       layout_change(*frame, vk::ImageLayout::eUndefined, vk::ImageLayout::eTransferDstOptimal, {},
                                     vk::AccessFlagBits::eTransferWrite));
    const vk::ImageSubresourceLayers layers{vk::ImageAspectFlagBits::eColor, 0, 0, 1};
    cb.copyBufferToImage(*packed.buffer, *frame, vk::ImageLayout::eTransferDstOptimal,
                         vk::BufferImageCopy{.imageSubresource = layers, .imageExtent = {uint32_t(p.shown[0]), uint32_t(p.shown[1]), 1}});
    const vk::ImageMemoryBarrier to_blit[2] = {
        layout_change(*frame, vk::ImageLayout::eTransferDstOptimal, vk::ImageLayout::eTransferSrcOptimal,
                      vk::AccessFlagBits::eTransferWrite, vk::AccessFlagBits::eTransferRead),
        layout_change(target, vk::ImageLayout::eUndefined, vk::ImageLayout::eTransferDstOptimal, {}, vk::AccessFlagBits::eTransferWrite)};
    cb.pipelineBarrier(vk::PipelineStageFlagBits::eTransfer, vk::PipelineStageFlagBits::eTransfer, {}, nullptr, nullptr, to_blit);
    cb.clearColorImage(target, vk::ImageLayout::eTransferDstOptimal, vk::ClearColorValue{std::array<float, 4>{0, 0, 0, 1}},
                       vk::ImageSubresourceRange{vk::ImageAspectFlagBits::eColor, 0, 1, 0, 1});
    cb.pipelineBarrier(vk::PipelineStageFlagBits::eTransfer, vk::PipelineStageFlagBits::eTransfer, {},
                       vk::MemoryBarrier{.srcAccessMask = vk::AccessFlagBits::eTransferWrite, .dstAccessMask = vk::AccessFlagBits::eTransferWrite},
                       nullptr, nullptr);
    // Letterboxed: whole multiples of the frame's pixels where it fits,
    // else shrunk to fit, centred.
    const double fit = std::min(double(extent.width) / p.shown[0], double(extent.height) / p.shown[1]);
    const double scale = fit >= 1 ? std::floor(fit) : fit;
    const int32_t w = std::max(1, int32_t(std::lround(p.shown[0] * scale))), h = std::max(1, int32_t(std::lround(p.shown[1] * scale)));
    const int32_t x0 = (int32_t(extent.width) - w) / 2, y0 = (int32_t(extent.height) - h) / 2;
    const vk::ImageBlit blit{.srcSubresource = layers, .srcOffsets = std::array<vk::Offset3D, 2>{vk::Offset3D{0, 0, 0}, vk::Offset3D{p.shown[0], p.shown[1], 1}},
                             .dstSubresource = layers, .dstOffsets = std::array<vk::Offset3D, 2>{vk::Offset3D{x0, y0, 0}, vk::Offset3D{x0 + w, y0 + h, 1}}};
    cb.blitImage(*frame, vk::ImageLayout::eTransferSrcOptimal, target, vk::ImageLayout::eTransferDstOptimal, blit, vk::Filter::eNearest);
    cb.pipelineBarrier(vk::PipelineStageFlagBits::eTransfer, vk::PipelineStageFlagBits::eBottomOfPipe, {}, nullptr, nullptr,
                       layout_change(target, vk::ImageLayout::eTransferDstOptimal, final_layout,
                                     vk::AccessFlagBits::eTransferWrite, {}));
    cb.end();
  }
};

Presenter::Presenter(GpuRenderer& renderer, const std::function<uint64_t(void* instance)>& make_surface,
                     const CodeThresholds& codes)
    : impl_(std::make_unique<Impl>(*renderer.impl_)) {
  Impl& m = *impl_;
  GpuRenderer::Impl& r = m.r;
  m.offscreen = !make_surface;
  if (!m.offscreen && !r.window) throw std::logic_error("Presenter: the renderer was made without a window system's extensions");
  try {
    if (!m.offscreen) {
      const uint64_t raw = make_surface(static_cast<void*>(static_cast<VkInstance>(*r.instance)));
      m.surface = vk::raii::SurfaceKHR(r.instance, reinterpret_cast<VkSurfaceKHR>(raw));
      if (!r.physical.getSurfaceSupportKHR(r.family, *m.surface))
        throw GpuError(fmt::format("the device {} cannot present to this window: choose another device (`device` gpu:N)", r.info.name));
    }
    vk::DescriptorSetLayoutBinding bindings[4];
    for (uint32_t b = 0; b < 4; ++b) bindings[b] = {b, vk::DescriptorType::eStorageBuffer, 1, vk::ShaderStageFlagBits::eCompute};
    m.set_layout = vk::raii::DescriptorSetLayout(r.device, vk::DescriptorSetLayoutCreateInfo{.bindingCount = 4, .pBindings = bindings});
    vk::PushConstantRange push{vk::ShaderStageFlagBits::eCompute, 0, sizeof(PackParams)};
    vk::DescriptorSetLayout raw_layout = *m.set_layout;
    m.pipeline_layout = vk::raii::PipelineLayout(
        r.device, vk::PipelineLayoutCreateInfo{.setLayoutCount = 1, .pSetLayouts = &raw_layout, .pushConstantRangeCount = 1,
                                               .pPushConstantRanges = &push});
    m.module = vk::raii::ShaderModule(r.device, vk::ShaderModuleCreateInfo{.codeSize = sizeof(kPackSpirv), .pCode = kPackSpirv});
    m.pipeline = vk::raii::Pipeline(
        r.device, nullptr,
        vk::ComputePipelineCreateInfo{.stage = {.stage = vk::ShaderStageFlagBits::eCompute, .module = *m.module, .pName = "main"},
                                      .layout = *m.pipeline_layout});
    vk::DescriptorPoolSize size{vk::DescriptorType::eStorageBuffer, 4};
    m.descriptor_pool = vk::raii::DescriptorPool(
        r.device, vk::DescriptorPoolCreateInfo{.flags = vk::DescriptorPoolCreateFlagBits::eFreeDescriptorSet, .maxSets = 1,
                                               .poolSizeCount = 1, .pPoolSizes = &size});
    vk::raii::DescriptorSets sets(r.device, vk::DescriptorSetAllocateInfo{.descriptorPool = *m.descriptor_pool,
                                                                          .descriptorSetCount = 1, .pSetLayouts = &raw_layout});
    m.set = std::move(sets[0]);
    m.thresholds = r.upload(codes.data(), sizeof codes);
    vk::raii::CommandBuffers cbs(r.device, vk::CommandBufferAllocateInfo{.commandPool = *r.pool, .commandBufferCount = 1});
    m.commands = std::move(cbs[0]);
    m.fence = vk::raii::Fence(r.device, vk::FenceCreateInfo{});
    m.acquired = vk::raii::Semaphore(r.device, vk::SemaphoreCreateInfo{});
  } catch (const vk::SystemError& e) {
    rethrow_vulkan(e, r.info.name);
  }
}

Presenter::~Presenter() {
  if (impl_) try {
      impl_->r.device.waitIdle();
    } catch (const vk::SystemError&) {  // a lost device: nothing left to wait for
    }
}

bool Presenter::show(const PackParams& pack, std::array<int, 2> window) {
  GpuRenderer::Impl& r = impl_->r;
  if (r.traced[0] == 0) throw std::logic_error("Presenter::show before a frame was traced");
  if (pack.what != PackParams::colour && !r.traced_aovs) throw std::logic_error("Presenter::show: an AOV of a frame traced without");
  for (int a = 0; a < 2; ++a)
    if (pack.shown[a] < 1 || pack.first[a] < 0 || pack.step[a] < 1 ||
        int64_t(pack.first[a]) + int64_t(pack.shown[a] - 1) * pack.step[a] >= r.traced[a])
      throw std::logic_error("Presenter::show: the pixels shown are not all in the frame traced");
  PackParams p = pack;
  p.source = {r.traced[0], r.traced[1]};
  return present(p, window, r.colour);
}

bool Presenter::show_image(const float* rgb, int width, int height, std::array<int, 2> window) {
  Impl& m = *impl_;
  if (width < 1 || height < 1) throw std::logic_error("Presenter::show_image: an empty image");
  const vk::DeviceSize bytes = vk::DeviceSize(width) * vk::DeviceSize(height) * 12;
  try {
    if (m.host_image.size < bytes) m.host_image = m.r.make_buffer(bytes, vk::BufferUsageFlagBits::eStorageBuffer, true);
  } catch (const vk::SystemError& e) {
    rethrow_vulkan(e, m.r.info.name);
  }
  std::memcpy(m.host_image.mapped, rgb, bytes);
  PackParams p;
  p.source = p.shown = {width, height};
  return present(p, window, m.host_image);
}

bool Presenter::present(const PackParams& p, std::array<int, 2> window, const Buffer& source) {
  Impl& m = *impl_;
  GpuRenderer::Impl& r = m.r;
  try {
    if (m.offscreen) {  // the same work as a shown frame's, but the present
      if (window != m.window) m.make_target(window);
      m.make_frame(p.shown);
      m.bind(0, source), m.bind(1, r.aov), m.bind(2, m.thresholds), m.bind(3, m.packed);
      m.record(p, *m.target, vk::ImageLayout::eTransferSrcOptimal);
      vk::CommandBuffer raw = *m.commands;
      r.queue.submit(vk::SubmitInfo{.commandBufferCount = 1, .pCommandBuffers = &raw}, *m.fence);
      r.wait(m.fence, "a frame's copy to the offscreen window");
      r.device.resetFences({*m.fence});
      m.shown = p.shown;
      return true;
    }
    for (int attempt = 0; attempt < 2; ++attempt) {
      if (window != m.window || !*m.swapchain) m.make_swapchain(window);
      if (m.extent.width == 0 || m.extent.height == 0) return false;
      uint32_t index = 0;
      try {
        const auto [result, i] = m.swapchain.acquireNextImage(UINT64_MAX, *m.acquired);
        index = i;
      } catch (const vk::OutOfDateKHRError&) {
        m.window = {-1, -1};  // made again on the next attempt
        continue;
      }
      m.make_frame(p.shown);
      m.bind(0, source), m.bind(1, r.aov), m.bind(2, m.thresholds), m.bind(3, m.packed);
      m.record(p, m.images[index], vk::ImageLayout::ePresentSrcKHR);
      const vk::PipelineStageFlags wait_stage = vk::PipelineStageFlagBits::eTransfer;
      vk::CommandBuffer raw = *m.commands;
      vk::Semaphore acquired = *m.acquired, presentable = *m.presentable[index];
      r.queue.submit(vk::SubmitInfo{.waitSemaphoreCount = 1, .pWaitSemaphores = &acquired, .pWaitDstStageMask = &wait_stage,
                                    .commandBufferCount = 1, .pCommandBuffers = &raw, .signalSemaphoreCount = 1,
                                    .pSignalSemaphores = &presentable},
                     *m.fence);
      vk::SwapchainKHR chain = *m.swapchain;
      try {
        if (r.queue.presentKHR(vk::PresentInfoKHR{.waitSemaphoreCount = 1, .pWaitSemaphores = &presentable, .swapchainCount = 1,
                                                  .pSwapchains = &chain, .pImageIndices = &index}) == vk::Result::eSuboptimalKHR)
          m.window = {-1, -1};
      } catch (const vk::OutOfDateKHRError&) {
        m.window = {-1, -1};
      }
      r.wait(m.fence, "a frame's copy to the window");
      r.device.resetFences({*m.fence});
      m.shown = p.shown;
      return true;
    }
    return false;
  } catch (const vk::SystemError& e) {
    rethrow_vulkan(e, r.info.name);
  }
}

std::vector<uint8_t> Presenter::shown_rgb() const {
  Impl& m = *impl_;
  GpuRenderer::Impl& r = m.r;
  const uint64_t pixels = uint64_t(m.shown[0]) * uint64_t(m.shown[1]);
  std::vector<uint8_t> rgb(pixels * 3);
  if (pixels == 0) return rgb;
  try {
    if (m.shown_copy.size < pixels * 4) m.shown_copy = r.make_buffer(pixels * 4, vk::BufferUsageFlagBits::eTransferDst, true);
    const Buffer& host = m.shown_copy;
    r.run_once([&](vk::raii::CommandBuffer& cb) { cb.copyBuffer(*m.packed.buffer, *host.buffer, vk::BufferCopy{0, 0, pixels * 4}); });
    const uint8_t* bgra = static_cast<const uint8_t*>(host.mapped);
    for (uint64_t k = 0; k < pixels; ++k)
      rgb[k * 3] = bgra[k * 4 + 2], rgb[k * 3 + 1] = bgra[k * 4 + 1], rgb[k * 3 + 2] = bgra[k * 4];
  } catch (const vk::SystemError& e) {
    rethrow_vulkan(e, r.info.name);
  }
  return rgb;
}

}  // namespace holoray::gpu
