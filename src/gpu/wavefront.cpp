// holoray/gpu: both integrators as a wavefront (issue 71), the host's
// half: the stages of shaders/wavefront.glsl (and whitted_wavefront.glsl)
// recorded band by band, sample by sample, in place of the pixel kernel, on
// the frames wave_rule gives it (measured: the wavefront on lavapipe, the
// megakernel on a GPU but for long paths). The kernel also traces for
// devices without subgroup ballots and votes, the ray log, the shadow
// queue, Whitted's trees of more than 63 rays, and HOLORAY_GPU_WAVEFRONT=0.
#include <fmt/format.h>

#include <algorithm>
#include <cstdio>

#include "gpu/vulkan_device.hpp"

namespace holoray::gpu {

// A Whitted pixel's tree walked one ray a step: max_depth steps where no
// hit sends two rays on, else up to 2^max_depth - 1; past kMaxWhittedSteps
// the empty steps' dispatches would cost more than the waits saved, and
// the megakernel traces the frame (0).
int whitted_steps(int max_depth, bool branches) {
  constexpr int kMaxWhittedSteps = 63;
  const int depth = std::clamp(max_depth, 1, HR_MAX_DEPTH);
  const int steps = branches ? (1 << depth) - 1 : depth;
  return steps <= kMaxWhittedSteps ? steps : 0;
}

// As measured (design/gpu.md, "Which schedule a frame takes"), 3840x2160
// EIAs of the SPD scenes and two path-traced scenes: on lavapipe (a CPU
// device) the wavefront rendered every scene faster, both integrators
// (1.04x to 2.75x); on an H200 the megakernel rendered Whitted's every SPD
// scene faster (1.7x to 3.0x), and the path integrator's where paths are
// short (teapot_s6, tree_s11, the Cornell box, swinging_box: 4.4 to 7.7
// rays a pixel, 1.03x to 1.76x), the wavefront where they are long
// (balls_s4 8.3, gears_s4 12.6: 1.75x and 1.47x). A first frame, with no
// count before it, takes the megakernel there.
// (HOLORAY_GPU_SHADOW_QUEUE asks for the megakernel's own queue.)
GpuRenderer::Impl::WaveRule GpuRenderer::Impl::wave_rule(bool path) const {
  if (!wavefront_on || (!path && shadow_queue_on)) return WaveRule::never;
  if (wavefront_always || !info.is_gpu) return WaveRule::always;
  return path ? WaveRule::long_paths : WaveRule::never;
}

bool GpuRenderer::Impl::takes_wavefront(bool path) const {
  const WaveRule rule = wave_rule(path);
  return rule == WaveRule::always || (rule == WaveRule::long_paths && last_rays_a_sample >= kLongPaths);
}

void GpuRenderer::Impl::barrier(vk::PipelineStageFlags from) {
  commands.pipelineBarrier(
      from, vk::PipelineStageFlagBits::eComputeShader | vk::PipelineStageFlagBits::eTransfer, {},
      vk::MemoryBarrier{.srcAccessMask = vk::AccessFlagBits::eShaderWrite | vk::AccessFlagBits::eTransferWrite,
                        .dstAccessMask = vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eShaderWrite |
                                         vk::AccessFlagBits::eTransferWrite},
      nullptr, nullptr);
}

void GpuRenderer::Impl::indirect_barrier() {
  commands.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader,
                           vk::PipelineStageFlagBits::eDrawIndirect | vk::PipelineStageFlagBits::eComputeShader, {},
                           vk::MemoryBarrier{.srcAccessMask = vk::AccessFlagBits::eShaderWrite,
                                             .dstAccessMask = vk::AccessFlagBits::eIndirectCommandRead |
                                                              vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eShaderWrite},
                           nullptr, nullptr);
}

void GpuRenderer::Impl::stamp(WaveStage stage) {
  if (!*wave_timestamps || wave_stamped.size() + 1 >= kWaveStamps) return;
  wave_stamped.push_back(stage);
  commands.writeTimestamp(vk::PipelineStageFlagBits::eBottomOfPipe, *wave_timestamps, uint32_t(wave_stamped.size()));
}

void GpuRenderer::Impl::print_wave_times() {
  if (!*wave_timestamps || wave_stamped.empty()) return;
  const uint32_t n = uint32_t(wave_stamped.size()) + 1;
  const auto got = wave_timestamps.getResults<uint64_t>(0, n, n * sizeof(uint64_t), sizeof(uint64_t),
                                                        vk::QueryResultFlagBits::e64 | vk::QueryResultFlagBits::eWait);
  if (got.first != vk::Result::eSuccess) return;
  double ms[kWaveStages] = {};
  for (uint32_t k = 1; k < n; ++k) ms[wave_stamped[k - 1]] += double(got.second[k] - got.second[k - 1]) * timestamp_ns * 1e-6;
  std::fprintf(stderr, "holoray gpu: wavefront: start %.3f ms, extend %.3f ms, shade %.3f ms, shadow %.3f ms, finish %.3f ms "
               "(%u dispatches timed)\n", ms[kStart], ms[kExtend], ms[kShade], ms[kShadow], ms[kFinish], n - 1);
}

void GpuRenderer::Impl::prepare_wavefront(const FramePlan& plan) {
  const uint64_t paths = plan.wave_paths, shadows = paths * plan.wave_shadows;
  // The queues' buffer also holds the stages' dispatch sizes (wave_args).
  const vk::BufferUsageFlags usage = vk::BufferUsageFlagBits::eStorageBuffer | vk::BufferUsageFlagBits::eTransferDst |
                                     vk::BufferUsageFlagBits::eIndirectBuffer;
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
  grow(27, wave_queues, HR_WAVE_HEADS * 16 + 3 * 16 + 2 * paths * 4, "path queues");
  grow(28, wave_shadows, shadows * sizeof(GpuWaveShadow), "shadow rays");
  grow(29, wave_shadow_queue, shadows * 4, "shadow queue");
  grow(30, wave_stack, paths * plan.wave_stack * 48, "ray stacks");
}

void GpuRenderer::Impl::record_wavefront_passes(const FramePlan& plan, int first_sample) {
  vk::raii::CommandBuffer& cb = commands;
  // The path integrator's vertices 1 to max_depth + 1 (past max_depth a
  // vertex only shows its emission: render/path_integrator.h), or
  // Whitted's steps (whitted_steps).
  const int vertices = plan.wave_steps;
  auto stage = [&](int s) { cb.bindPipeline(vk::PipelineBindPoint::eCompute, *pipeline(plan.panel, false, 0, s)); };
  const int per_submission = passes_per_submission(plan);
  stage(HR_WAVE_SHADING);
  cb.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *pipeline_layout, 0, {*set}, nullptr);
  wave_stamped.clear();
  if (*timestamps) {
    if (!*wave_timestamps)
      wave_timestamps = vk::raii::QueryPool(device, vk::QueryPoolCreateInfo{.queryType = vk::QueryType::eTimestamp, .queryCount = kWaveStamps});
    cb.resetQueryPool(*wave_timestamps, 0, kWaveStamps);
    cb.writeTimestamp(vk::PipelineStageFlagBits::eBottomOfPipe, *wave_timestamps, 0);
  }
  for (int pass = first_sample; pass < plan.passes; ++pass) {
    if (pass > first_sample && (pass - first_sample) % per_submission == 0) {
      next_submission();
      stage(HR_WAVE_SHADING);
      cb.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *pipeline_layout, 0, {*set}, nullptr);
    }
    for (size_t b = 0; b < plan.bands.size(); ++b) {
      const Band& band = plan.bands[b];
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
      stage(HR_WAVE_START);
      push(0);  // start and finish work on no vertex
      over_band();
      stamp(kStart);
      // Each stage of a vertex sized by its queue (wave_dispatch_sizes),
      // read by an indirect dispatch: the deep vertices hold few paths.
      const vk::DeviceSize args = HR_WAVE_HEADS * 16;
      auto size_dispatches = [&] {
        barrier();
        stage(HR_WAVE_ARGS);
        cb.dispatch(1, 1, 1);
        indirect_barrier();
      };
      for (int depth = 1; depth <= vertices; ++depth) {
        push(depth);
        size_dispatches();
        stage(HR_WAVE_EXTEND);
        cb.dispatchIndirect(*wave_queues.buffer, args);
        stamp(kExtend);
        barrier();
        stage(HR_WAVE_SHADING);
        cb.dispatchIndirect(*wave_queues.buffer, args + 16);
        stamp(kShade);
        if (plan.wave_shadows == 0) continue;
        size_dispatches();
        stage(HR_WAVE_SHADOW);
        cb.dispatchIndirect(*wave_queues.buffer, args + 32);
        stamp(kShadow);
      }
      barrier();
      stage(HR_WAVE_FINISH);
      push(0);
      over_band();
      stamp(kFinish);
    }
  }
}

}  // namespace holoray::gpu
