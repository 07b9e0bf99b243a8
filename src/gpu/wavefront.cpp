// holoray/gpu: the path integrator as a wavefront (issue 71), the host's
// half: the stages of shaders/wavefront.glsl recorded band by band, sample
// by sample, in place of the path integrator's pixel kernel. For measuring
// (HOLORAY_GPU_WAVEFRONT=1): a GPU is needed to say which is faster.
#include <fmt/format.h>

#include <algorithm>

#include "gpu/vulkan_device.hpp"

namespace holoray::gpu {

void GpuRenderer::Impl::barrier(vk::PipelineStageFlags from) {
  commands.pipelineBarrier(
      from, vk::PipelineStageFlagBits::eComputeShader | vk::PipelineStageFlagBits::eTransfer, {},
      vk::MemoryBarrier{.srcAccessMask = vk::AccessFlagBits::eShaderWrite | vk::AccessFlagBits::eTransferWrite,
                        .dstAccessMask = vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eShaderWrite |
                                         vk::AccessFlagBits::eTransferWrite},
      nullptr, nullptr);
}

void GpuRenderer::Impl::dispatch_fetching(uint64_t invocations) {
  const uint64_t group = workgroup[0] * workgroup[1];
  const uint64_t groups = std::max<uint64_t>(1, (invocations + group - 1) / group);
  const uint64_t band_groups = std::max<uint64_t>(1, band_invocations / group);
  for (uint64_t first = 0; first < groups; first += band_groups) {
    const uint64_t n = std::min(band_groups, groups - first);
    const uint32_t gx = uint32_t(std::min<uint64_t>(n, 65535));
    commands.dispatch(gx, uint32_t((n + gx - 1) / gx), 1);
  }
}

void GpuRenderer::Impl::prepare_wavefront(const FramePlan& plan) {
  const uint64_t paths = plan.wave_paths, shadows = paths * plan.wave_shadows;
  const vk::BufferUsageFlags usage = vk::BufferUsageFlagBits::eStorageBuffer | vk::BufferUsageFlagBits::eTransferDst;
  auto grow = [&](int binding, Buffer& b, uint64_t bytes, const char* what) {
    if (bytes > max_storage_range)
      throw GpuError(fmt::format("the wavefront's {} take {:.1f} MiB, more than the {:.1f} MiB one buffer of {} holds "
                                 "(maxStorageBufferRange): render with fewer lights, or without HOLORAY_GPU_WAVEFRONT",
                                 what, bytes / 1048576.0, max_storage_range / 1048576.0, info.name));
    if (b.size >= bytes) return;
    b = make_buffer(bytes, usage, false);
    bind(binding, b);
  };
  grow(25, wave_paths, paths * sizeof(GpuWavePath), "paths");
  grow(26, wave_hits, paths * 32, "hits");
  grow(27, wave_queues, HR_WAVE_HEADS * 16 + 2 * paths * 4, "path queues");
  grow(28, wave_shadows, shadows * sizeof(GpuWaveShadow), "shadow rays");
  grow(29, wave_shadow_queue, shadows * 4, "shadow queue");
}

void GpuRenderer::Impl::record_wavefront_passes(const FramePlan& plan, int first_sample) {
  vk::raii::CommandBuffer& cb = commands;
  const GpuFrame* frames = static_cast<const GpuFrame*>(scene[0].mapped);
  // Vertices 1 to max_depth + 1: past max_depth a vertex only shows its
  // emission (render/path_integrator.h).
  const int vertices = std::min(frames[0].counts.z + 1, HR_MAX_DEPTH + 1);
  auto stage = [&](int s) { cb.bindPipeline(vk::PipelineBindPoint::eCompute, *pipeline(plan.panel, false, 0, s)); };
  // Submissions as the pixel kernel's passes go (record_pixel_passes says why).
  const int passes_per_submission = int(std::max<uint64_t>(1, 4 * band_invocations / std::max<uint64_t>(1, plan.pixels)));
  stage(HR_WAVE_SHADING);
  cb.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *pipeline_layout, 0, {*set}, nullptr);
  for (int pass = first_sample; pass < plan.passes; ++pass) {
    if (pass > first_sample && (pass - first_sample) % passes_per_submission == 0) {
      submit_and_wait("a pass of the path integrator");
      cb.reset();
      cb.begin(vk::CommandBufferBeginInfo{.flags = vk::CommandBufferUsageFlagBits::eOneTimeSubmit});
      stage(HR_WAVE_SHADING);
      cb.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *pipeline_layout, 0, {*set}, nullptr);
    }
    for (size_t b = 0; b < plan.bands.size(); ++b) {
      const Band& band = plan.bands[b];
      const uint64_t pixels = uint64_t(band.width) * uint64_t(band.rows);
      auto push = [&](int depth) {
        cb.pushConstants<int32_t>(*pipeline_layout, vk::ShaderStageFlagBits::eCompute, 0,
                                  {band.row0, band.rows, int32_t(b), band.frame, pass, first_sample, depth,
                                   int32_t(plan.wave_paths)});
      };
      auto over_band = [&] {
        cb.dispatch((band.width + workgroup[0] - 1) / workgroup[0], (uint32_t(band.rows) + workgroup[1] - 1) / workgroup[1], 1);
      };
      barrier();  // the band before done with the heads
      cb.fillBuffer(*wave_queues.buffer, 0, HR_WAVE_HEADS * 16, 0);
      barrier(vk::PipelineStageFlagBits::eTransfer);
      stage(HR_WAVE_SHADING);
      push(HR_WAVE_START_DEPTH);
      over_band();
      for (int depth = 1; depth <= vertices; ++depth) {
        push(depth);
        barrier();
        stage(HR_WAVE_EXTEND);
        dispatch_fetching((pixels + HR_SHADOW_RAYS_PER_LANE - 1) / HR_SHADOW_RAYS_PER_LANE);
        barrier();
        stage(HR_WAVE_SHADING);
        over_band();
        if (plan.wave_shadows == 0) continue;
        barrier();
        stage(HR_WAVE_SHADOW);
        dispatch_fetching((pixels * plan.wave_shadows + HR_SHADOW_RAYS_PER_LANE - 1) / HR_SHADOW_RAYS_PER_LANE);
      }
      barrier();
      stage(HR_WAVE_SHADING);
      push(HR_WAVE_FINISH_DEPTH);
      over_band();
    }
  }
}

}  // namespace holoray::gpu
