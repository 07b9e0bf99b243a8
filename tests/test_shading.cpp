// The shared shading functions (src/shading/*.h) on both devices: the same
// cases through their C++ build (the CPU path's) and through their GLSL
// build on a Vulkan device (lavapipe in CI; shading/shared_functions.comp),
// equal to float rounding. One text, two compilers: this is what keeps the
// copies from drifting (issue 70).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

#include "gpu/shared_functions.hpp"
#include "shading/shared_cases.h"

namespace holoray {
namespace {

TEST(SharedShading, EveryFunctionGivesTheSameValuesOnTheCpuAndTheGpu) {
  const uint32_t cases = 4096;
  std::mt19937 rng(70);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f), signed_unit(-1.0f, 1.0f);
  std::vector<float> in(size_t{cases} * gpu::kSharedCaseInputs);
  for (uint32_t c = 0; c < cases; ++c) {
    float* a = &in[size_t{c} * gpu::kSharedCaseInputs];
    for (int k = 0; k < 6; ++k) a[k] = signed_unit(rng);  // wo, wi
    for (int k = 6; k < 15; ++k) a[k] = unit(rng);        // uniforms, colour, metallic, roughness, transmission
    a[15] = static_cast<float>(c % 64);                   // a sample index
  }
  const std::vector<float> gpu_out = gpu::run_shared_functions(in);
  ASSERT_EQ(gpu_out.size(), size_t{cases} * gpu::kSharedCaseOutputs);
  int differing_cases = 0;
  double worst[3] = {0, 0, 0};  // the worst error of each kind of output, below
  for (uint32_t c = 0; c < cases; ++c) {
    const float* a_in = &in[size_t{c} * gpu::kSharedCaseInputs];
    const float* g = &gpu_out[size_t{c} * gpu::kSharedCaseOutputs];
    float cpu[gpu::kSharedCaseOutputs];
    shading::hr_run_case(c, a_in, cpu);
    // The sampled direction's pdf and weight, evaluated on the CPU at the
    // direction the GPU drew: the BSDF agrees given the same direction.
    const shading::vec3 wo = shading::normalize(shading::vec3(a_in[0], a_in[1], std::fabs(a_in[2]) + 0.05f));
    const shading::vec3 base(a_in[9], a_in[10], a_in[11]);
    const shading::HrBsdf b = a_in[15] >= 32 ? shading::hr_principled_bsdf(base, a_in[12], a_in[13], 0.04f, a_in[14], wo.z)
                                             : shading::hr_gltf_bsdf(base, a_in[12], a_in[13], 0.04f, a_in[14], wo.z);
    const shading::vec3 wi_gpu(g[4], g[5], g[6]);
    const bool drew = g[10] > 0 && g[11] == 0;  // a non-delta lobe was drawn on the GPU
    bool differs = false;
    for (uint32_t k = 0; k < gpu::kSharedCaseOutputs; ++k) {
      ASSERT_TRUE(std::isfinite(cpu[k])) << "case " << c << " output " << k;
      double err;
      int kind;
      if (k >= 7 && k <= 10) {
        // Relative, against the CPU's own value at the GPU's direction.
        // Below roughness 0.1 GGX's D(h) turns ill-conditioned in float
        // (its peak's width, alpha^2, nears the rounding of h.z): the two
        // compilers' roundings of the same formula then part by percents.
        // Above it the rounding's effect still grows as 1/alpha^2, as the
        // pdf's peak does: the bound grows with the pdf past 100 (an H200,
        // whose compiler fuses multiplies and adds, parted pdfs of 150 to
        // 560 by 1.1e-3 to 3.6e-3; lavapipe stays within 1e-3).
        if (!drew || b.alpha < 0.01f) continue;
        const float pdf = shading::hr_bsdf_pdf(b, wo, wi_gpu);
        const shading::vec3 w = shading::hr_bsdf_eval(b, wo, wi_gpu) / pdf;
        const float cpu_at_gpu = k == 10 ? pdf : (k == 7 ? w.x : k == 8 ? w.y : w.z);
        const double conditioning = std::max(1.0, double(pdf) / 100);
        err = std::fabs(cpu_at_gpu - g[k]) / std::max(1.0, std::fabs(double(cpu_at_gpu))) / (1e-3 * conditioning);
        kind = 2;
      } else if ((k >= 4 && k <= 6) || (k >= 14 && k <= 25)) {
        // Through sin, cos, asin, acos or atan, whose GLSL precision Vulkan
        // bounds only by 2^-11 absolute (lavapipe's are that coarse): 4x it.
        err = std::fabs(cpu[k] - g[k]) / 2e-3;
        kind = 1;
      } else {
        err = std::fabs(cpu[k] - g[k]) / std::max(1.0, std::fabs(double(cpu[k]))) / 1e-4;
        kind = 0;
      }
      if (err > 1) {
        differs = true;
        if (std::getenv("HOLORAY_TEST_VERBOSE")) std::fprintf(stderr, "case %u output %u: cpu %g gpu %g (%g of the bound)\n", c, k, cpu[k], g[k], err);
      } else {
        worst[kind] = std::max(worst[kind], err);
      }
    }
    differing_cases += differs;
  }
  // A uniform a few ulps from a lobe's threshold may pick the other lobe on
  // one device: a whole different sample. Rare; nothing else may differ.
  EXPECT_LE(differing_cases, 4) << "of " << cases;
  std::printf("worst errors as fractions of their bounds: arithmetic %.3f, transcendental %.3f, sampled pdf and weight %.3f\n",
              worst[0], worst[1], worst[2]);
  // The outputs are not all trivial (the test would pass on zeros).
  int sampled = 0;
  for (uint32_t c = 0; c < cases; ++c) sampled += gpu_out[size_t{c} * gpu::kSharedCaseOutputs + 10] > 0;
  EXPECT_GT(sampled, static_cast<int>(cases / 2));
}

}  // namespace
}  // namespace holoray
