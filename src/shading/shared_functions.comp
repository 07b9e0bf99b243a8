#version 450
// holoray/shading: every shared function evaluated on the device, one case
// per invocation, for the tests that hold them equal to their C++ build
// (tests/test_shading.cpp, tests/test_pixel_lines.cpp). It also makes the build compile the shared
// headers as GLSL: a header that is C++ only fails here, at build time.
#extension GL_GOOGLE_include_directive : require

#include "shading/sampler.h"
#include "shading/warp.h"
#include "shading/microfacet.h"
#include "shading/bsdf.h"
#include "shading/lights.h"
#include "shading/environment.h"
#include "shading/gltf_whitted.h"
#include "camera/pixel_lines.h"

layout(local_size_x = 64) in;

// Per case: 16 floats in (two directions, two uniforms, a material), 32 out.
layout(std430, binding = 0) readonly buffer Inputs { float inputs[]; };
layout(std430, binding = 1) writeonly buffer Outputs { float outputs[]; };
// suite 0: the shading functions (shading/shared_cases.h); 1: the cameras'
// pixel lines (camera/line_cases.h).
layout(push_constant) uniform Push { uint cases; uint suite; } push;

#define HR_CASE_IN 16u
#define HR_CASE_OUT 32u
#include "shading/shared_cases.h"
#include "camera/line_cases.h"

void main() {
  uint c = gl_GlobalInvocationID.x;
  if (c >= push.cases) return;
  float a[HR_CASE_IN];
  for (uint k = 0u; k < HR_CASE_IN; ++k) a[k] = inputs[c * HR_CASE_IN + k];
  float r[HR_CASE_OUT];
  if (push.suite == 1u)
    hr_run_line_case(c, a, r);
  else
    hr_run_case(c, a, r);
  for (uint k = 0u; k < HR_CASE_OUT; ++k) outputs[c * HR_CASE_OUT + k] = r[k];
}
