// holoray/shading (C++ only): the little of GLSL that the shared headers
// use (vec2, vec3, uint and the built-in functions they call), in float, so
// that one text compiles as C++ for the CPU path and as GLSL for the GPU
// kernels (architecture.md, "shading/"; pbrt-v4's PBRT_CPU_GPU functions).
// Every name lives in holoray::shading, where it hides <cmath>'s doubles: a
// shared function computes in float on both devices.
#pragma once

#include <cmath>
#include <cstdint>

namespace holoray::shading {

using uint = uint32_t;

struct vec2 {
  float x = 0, y = 0;
  vec2() = default;
  explicit vec2(float s) : x(s), y(s) {}
  vec2(float x_, float y_) : x(x_), y(y_) {}
};

struct vec3 {
  float x = 0, y = 0, z = 0;
  vec3() = default;
  explicit vec3(float s) : x(s), y(s), z(s) {}
  vec3(float x_, float y_, float z_) : x(x_), y(y_), z(z_) {}
};

struct uvec2 {
  uint x = 0, y = 0;
  uvec2() = default;
  uvec2(uint x_, uint y_) : x(x_), y(y_) {}
};

struct ivec2 {
  int x = 0, y = 0;
  ivec2() = default;
  ivec2(int x_, int y_) : x(x_), y(y_) {}
};

struct ivec4 {
  int x = 0, y = 0, z = 0, w = 0;
  ivec4() = default;
  ivec4(int x_, int y_, int z_, int w_) : x(x_), y(y_), z(z_), w(w_) {}
};

inline vec3 operator+(vec3 a, vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline vec3 operator-(vec3 a, vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline vec3 operator*(vec3 a, vec3 b) { return {a.x * b.x, a.y * b.y, a.z * b.z}; }
inline vec3 operator/(vec3 a, vec3 b) { return {a.x / b.x, a.y / b.y, a.z / b.z}; }
inline vec3 operator*(vec3 a, float s) { return {a.x * s, a.y * s, a.z * s}; }
inline vec3 operator*(float s, vec3 a) { return a * s; }
inline vec3 operator/(vec3 a, float s) { return {a.x / s, a.y / s, a.z / s}; }
inline vec3 operator-(vec3 a) { return {-a.x, -a.y, -a.z}; }
inline vec3& operator+=(vec3& a, vec3 b) { return a = a + b; }
inline vec3& operator*=(vec3& a, vec3 b) { return a = a * b; }
inline vec3& operator*=(vec3& a, float s) { return a = a * s; }
inline vec2 operator*(vec2 a, float s) { return {a.x * s, a.y * s}; }

inline float abs(float x) { return std::fabs(x); }
inline float sqrt(float x) { return std::sqrt(x); }
inline float exp(float x) { return std::exp(x); }
inline float log(float x) { return std::log(x); }
inline float pow(float x, float y) { return std::pow(x, y); }
inline float sin(float x) { return std::sin(x); }
inline float cos(float x) { return std::cos(x); }
inline float acos(float x) { return std::acos(x); }
inline float asin(float x) { return std::asin(x); }
inline float atan(float y, float x) { return std::atan2(y, x); }  // GLSL's two-argument atan
inline float floor(float x) { return std::floor(x); }
inline float fract(float x) { return x - std::floor(x); }
inline float sign(float x) { return x > 0 ? 1.0f : (x < 0 ? -1.0f : 0.0f); }
inline float min(float a, float b) { return b < a ? b : a; }  // GLSL: either operand when one is NaN
inline float max(float a, float b) { return a < b ? b : a; }
inline uint min(uint a, uint b) { return b < a ? b : a; }
inline int min(int a, int b) { return b < a ? b : a; }
inline int max(int a, int b) { return a < b ? b : a; }
inline int clamp(int x, int lo, int hi) { return min(max(x, lo), hi); }
inline float clamp(float x, float lo, float hi) { return min(max(x, lo), hi); }
inline float mix(float a, float b, float t) { return a * (1 - t) + b * t; }
inline vec3 mix(vec3 a, vec3 b, float t) { return a * (1 - t) + b * t; }
inline vec3 max(vec3 a, vec3 b) { return {max(a.x, b.x), max(a.y, b.y), max(a.z, b.z)}; }
inline float dot(vec3 a, vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline vec3 cross(vec3 a, vec3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline float length(vec3 a) { return sqrt(dot(a, a)); }
// Always inlined: left to the inliner, the shared path integrator's bounce
// loop (render/path_integrator.h) called it out of line, 0.7 % of a path's
// instructions; Whitted's count is unchanged (callgrind).
[[gnu::always_inline]] inline vec3 normalize(vec3 a) { return a / length(a); }
inline vec3 reflect(vec3 i, vec3 n) { return i - n * (2 * dot(n, i)); }

}  // namespace holoray::shading
