// The cameras' pixel lines (camera/pixel_lines.h) on both devices: the same
// cameras and samples through the C++ build in double (what the CPU cameras
// call) and through the GLSL build in float on a Vulkan device (lavapipe in
// CI; the second suite of shading/shared_functions.comp), equal to float
// rounding: one text of every camera's ray generation (issue 70).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

#include "camera/line_cases.h"
#include "gpu/shared_functions.hpp"

namespace holoray {
namespace {

TEST(SharedLines, EveryCameraKindGivesTheSameLineOnTheCpuAndTheGpu) {
  const uint32_t cases = HR_LINE_CASE_KINDS * 1024;
  std::mt19937 rng(71);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<float> in(size_t{cases} * gpu::kSharedCaseInputs);
  for (float& a : in) a = unit(rng);
  const std::vector<float> gpu_out = gpu::run_shared_functions(in, gpu::SharedSuite::camera_lines);
  ASSERT_EQ(gpu_out.size(), size_t{cases} * gpu::kSharedCaseOutputs);
  int other_lens[HR_LINE_CASE_KINDS] = {};
  double worst_position = 0, worst_direction = 0;
  for (uint32_t c = 0; c < cases; ++c) {
    const float* g = &gpu_out[size_t{c} * gpu::kSharedCaseOutputs];
    float cpu[gpu::kSharedCaseOutputs];
    camera_lines::hr_run_line_case(c, &in[size_t{c} * gpu::kSharedCaseInputs], cpu);
    const double length = std::sqrt(double(cpu[3]) * cpu[3] + double(cpu[4]) * cpu[4] + double(cpu[5]) * cpu[5]);
    ASSERT_NEAR(length, 1.0, 1e-6) << "case " << c << ": the CPU's direction is not unit";
    // A sample within float rounding of a lens's edge may fall under the
    // neighbouring lens on one device: a whole other line, rare. (A Looking
    // Glass's cell is integer arithmetic: never.)
    if (cpu[6] != g[6] || cpu[7] != g[7]) {
      ++other_lens[c % HR_LINE_CASE_KINDS];
      continue;
    }
    // Positions to float rounding of the panel's size (tens of units);
    // directions a difference of two such positions over a lens's width.
    // Through a tangent, Vulkan's bound on GLSL's (2^-11 absolute), 4x it.
    const double loose = c % HR_LINE_CASE_KINDS == HR_LINE_CASE_TANGENT ? 20.0 : 1.0;
    for (int k = 0; k < 11; ++k) {
      if (k == 6 || k == 7) continue;
      const bool direction = k >= 3 && k <= 5;
      const double err = std::fabs(double(cpu[k]) - g[k]) /
                         (loose * (direction ? 2e-4 : 2e-5 * std::max(1.0, std::fabs(double(cpu[k])))));
      double& worst = direction ? worst_direction : worst_position;
      worst = std::max(worst, err);
      EXPECT_LE(err, 1.0) << "case " << c << " (kind " << c % HR_LINE_CASE_KINDS << ") output " << k << ": cpu "
                          << cpu[k] << ", gpu " << g[k];
    }
  }
  for (uint32_t kind = 0; kind < HR_LINE_CASE_KINDS; ++kind)
    EXPECT_LE(other_lens[kind], kind == HR_LINE_CASE_TANGENT ? 0 : 3) << "kind " << kind << " of 1024 cases";
  std::printf("worst errors as fractions of their bounds: positions %.3f, directions %.3f\n", worst_position,
              worst_direction);
}

}  // namespace
}  // namespace holoray
