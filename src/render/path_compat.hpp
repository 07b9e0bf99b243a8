// holoray/render (C++ only): what render/path_integrator.h needs to compile
// as C++ for the CPU path: positions, distances, throughput and radiance in
// double (hr_real, hr_vec3: the CPU's Vec3), the BSDF's local directions in
// the shared float vec3, and the conversions between them. The GPU compiles
// the same text with both names float and the conversions the identity.
#pragma once

#include <cmath>

#include "math/vec.hpp"
#include "shading/common.h"  // HR_FN, vec3 and the float forms

namespace holoray::shading {

using hr_real = double;
using hr_vec3 = Vec3;

/// A shared function's float vector in double, and back.
HR_FN Vec3 hr_d3(vec3 v) { return {v.x, v.y, v.z}; }
HR_FN vec3 hr_f3(const Vec3& v) { return {static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z)}; }
/// Component-wise product (GLSL's vec3 * vec3).
HR_FN Vec3 hr_mul3(const Vec3& a, const Vec3& b) { return mul(a, b); }

// The double forms beside glsl_compat.hpp's float ones, which would
// otherwise take a double argument through float.
HR_FN double abs(double x) { return std::fabs(x); }
HR_FN double sqrt(double x) { return std::sqrt(x); }
HR_FN double min(double a, double b) { return std::fmin(a, b); }
HR_FN double max(double a, double b) { return a < b ? b : a; }  // std::max's: a compare, not fmax's call
HR_FN bool isinf(double x) { return std::isinf(x); }

}  // namespace holoray::shading

#define HR_PATH_INF INFINITY
#define HR_PATH_PI M_PI
