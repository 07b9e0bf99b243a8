// holoray/render: the render layer's double vectors to the shared shading
// functions' float ones (shading/glsl_compat.hpp) and back: what every
// caller of src/shading/ on the CPU converts through.
#pragma once

#include "math/vec.hpp"
#include "shading/glsl_compat.hpp"

namespace holoray {

/// `v` in float, for a shared function.
inline shading::vec3 to_f(const Vec3& v) { return {static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z)}; }
/// A shared function's float vector back in double.
inline Vec3 to_d(const shading::vec3& v) { return {v.x, v.y, v.z}; }

}  // namespace holoray
