// holoray/gpu: the shared shading functions (src/shading/*.h) run on a
// Vulkan device, for the test that holds them equal to their C++ build
// (tests/test_shading.cpp): shading/shared_functions.comp evaluates
// hr_run_case (shading/shared_cases.h) once per case.
#pragma once

#include <cstdint>
#include <vector>

namespace holoray::gpu {

/// Inputs per case and outputs per case (shading/shared_cases.h).
inline constexpr uint32_t kSharedCaseInputs = 16, kSharedCaseOutputs = 32;

/// Which shared functions a run evaluates: the shading functions
/// (hr_run_case, shading/shared_cases.h) or the cameras' pixel lines
/// (hr_run_line_case, camera/line_cases.h).
enum class SharedSuite : uint32_t { shading = 0, camera_lines = 1 };

/// The suite's case function (c, inputs[16 c ..], outputs[32 c ..]) for every case c on
/// the first Vulkan device that is a GPU, else the first device (lavapipe).
/// `inputs` holds 16 floats a case. Throws GpuError when there is no
/// loader or device, std::invalid_argument when inputs.size() is not a
/// multiple of 16.
std::vector<float> run_shared_functions(const std::vector<float>& inputs, SharedSuite suite = SharedSuite::shading);

}  // namespace holoray::gpu
