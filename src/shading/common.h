// holoray/shading: what every shared header starts with. The shared headers
// (this folder, *.h) compile both as C++ (the CPU path, through
// glsl_compat.hpp, in namespace holoray::shading) and as GLSL 4.50 (the GPU
// kernels, through glslc's #include): one text of every sampling and
// shading function for both devices, in float. Written in the subset both
// languages share: no references or pointers (HR_OUT / HR_INOUT say what a
// parameter returns), no default member values, literals with their `f` and
// `u` suffixes, structs built member by member, no `const` locals
// (GLSL's must be constant expressions), HR_FN before every function
// (`inline` in C++).
#ifndef HOLORAY_SHADING_COMMON_H
#define HOLORAY_SHADING_COMMON_H

#ifdef __cplusplus
#include "shading/glsl_compat.hpp"
#define HR_OUT(T) T&
#define HR_INOUT(T) T&
// Inlined whatever the compiler's estimate: the sampler's few dozen integer
// operations are called per ray and cost a third of a path as calls.
#define HR_FN [[gnu::always_inline]] inline
#define HR_BEGIN namespace holoray::shading {
#define HR_END }
#else
#define HR_OUT(T) out T
#define HR_INOUT(T) inout T
#define HR_FN
#define HR_BEGIN
#define HR_END
#endif

// A float array parameter (the tests' cases: shared_cases.h,
// camera/line_cases.h): a pointer in C++, a sized array in GLSL.
#ifdef __cplusplus
#define HR_ARRAY_IN(name, n) const float* name
#define HR_ARRAY_OUT(name, n) float* name
#define HR_ARRAY_INOUT(name, n) float* name
#else
#define HR_ARRAY_IN(name, n) float name[n]
#define HR_ARRAY_OUT(name, n) out float name[n]
#define HR_ARRAY_INOUT(name, n) inout float name[n]
#endif

#define HR_PI 3.14159265358979f
#define HR_INV_PI 0.318309886183791f

HR_BEGIN

/// Rec. 709 luminance of linear RGB: the weight that picks among colours.
HR_FN float hr_luminance(vec3 c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

/// An orthonormal frame around unit `n` (Duff et al. 2017, "Building an
/// Orthonormal Basis, Revisited"): t and b complete it, right-handed.
HR_FN void hr_frame(vec3 n, HR_OUT(vec3) t, HR_OUT(vec3) b) {
  float s = n.z >= 0.0f ? 1.0f : -1.0f;
  float a = -1.0f / (s + n.z);
  float c = n.x * n.y * a;
  t = vec3(1.0f + s * n.x * n.x * a, s * c, -s * n.x);
  b = vec3(c, s + n.y * n.y * a, -n.y);
}

/// `v` (world) in the frame (t, b, n), and back.
HR_FN vec3 hr_to_local(vec3 v, vec3 t, vec3 b, vec3 n) { return vec3(dot(v, t), dot(v, b), dot(v, n)); }
HR_FN vec3 hr_to_world(vec3 v, vec3 t, vec3 b, vec3 n) { return t * v.x + b * v.y + n * v.z; }

HR_END

#endif
