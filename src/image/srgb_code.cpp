#include "image/srgb_code.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>

namespace holoray {

uint8_t srgb_code_by_formula(float v) {
  if (std::isnan(v)) return 0;
  v = std::clamp(v, 0.0f, 1.0f);
  const float e = v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
  const double code = std::floor(255.0 * static_cast<double>(e) + 0.5);
  return static_cast<uint8_t>(std::clamp(code, 0.0, 255.0));
}

namespace {

// Buckets of [0, 1] by v * kBuckets (exact for a power of two): each holds
// the code at its lower end, from which at most a couple of steps remain.
constexpr int kBuckets = 4096;

struct Steps {
  std::array<float, 257> step{};                  // step[c]: least v of code c (c = 1..255); step[256] = +inf
  std::array<uint8_t, kBuckets + 1> bucket_code{};  // the code of b / kBuckets

  Steps() {
    step[0] = 0;
    for (int c = 1; c <= 255; ++c) {
      // Non-negative floats order as their bit patterns: bisect the bits.
      uint32_t lo = 0, hi = std::bit_cast<uint32_t>(1.0f);  // code(lo) < c <= code(hi)
      while (hi - lo > 1) {
        const uint32_t mid = lo + (hi - lo) / 2;
        (srgb_code_by_formula(std::bit_cast<float>(mid)) >= c ? hi : lo) = mid;
      }
      step[static_cast<size_t>(c)] = std::bit_cast<float>(hi);
    }
    step[256] = INFINITY;
    for (int b = 0; b <= kBuckets; ++b)
      bucket_code[static_cast<size_t>(b)] = srgb_code_by_formula(static_cast<float>(b) / kBuckets);
  }
};

const Steps& steps() {
  static const Steps s;
  return s;
}

}  // namespace

uint8_t srgb_code(float v) {
  if (!(v > 0)) return 0;  // NaN, zero and below
  if (v >= 1) return 255;
  const Steps& s = steps();
  int c = s.bucket_code[static_cast<size_t>(v * kBuckets)];
  while (v >= s.step[static_cast<size_t>(c) + 1]) ++c;
  return static_cast<uint8_t>(c);
}

float srgb_code_step(int c) { return steps().step[static_cast<size_t>(std::clamp(c, 0, 256))]; }

}  // namespace holoray
