// holoray/camera (C++ only): what camera/pixel_lines.h needs to compile as
// C++ in double, the precision of the CPU cameras (camera-model.md,
// property 2: a line and its projection are inverses to ~1e-12). The GPU
// compiles the same text in float.
#pragma once

#include <algorithm>
#include <cmath>

#include "math/vec.hpp"
#include "shading/common.h"  // HR_FN, HR_OUT, ivec2

namespace holoray::camera_lines {

using hr_real = double;
using hr_vec3 = Vec3;
using HrFrame = Frame;
using shading::ivec2;
using shading::uint;
// Declared here so that they hide math/vec.hpp's Vec3 min and max.
using std::ceil;
using std::clamp;
using std::floor;
using std::max;
using std::min;
using std::sqrt;
using std::tan;

/// std::lround, as the CPU cameras have always rounded.
HR_FN int hr_round(double x) { return static_cast<int>(std::lround(x)); }

}  // namespace holoray::camera_lines

#define HR_LINE_INF INFINITY
