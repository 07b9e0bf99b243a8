#include "live/shown_codes.hpp"

#include <bit>

namespace holoray::live {

gpu::CodeThresholds code_thresholds(Encoding encoding) {
  gpu::CodeThresholds t{};
  // Non-negative floats ascend with their bit patterns.
  const uint32_t zero = std::bit_cast<uint32_t>(0.0f), one = std::bit_cast<uint32_t>(1.0f);
  for (int k = 1; k <= 255; ++k) {
    uint32_t lo = zero, hi = one;  // encode(lo) < k <= encode(hi)
    while (hi - lo > 1) {
      const uint32_t mid = lo + (hi - lo) / 2;
      (encode_8bit(std::bit_cast<float>(mid), encoding) >= k ? hi : lo) = mid;
    }
    t[size_t(k - 1)] = std::bit_cast<float>(hi);
  }
  return t;
}

ImageBuffer image_of_codes(const std::vector<uint8_t>& rgb, int width, int height, const gpu::CodeThresholds& thresholds) {
  ImageBuffer image(width, height, 3);
  for (size_t k = 0; k < rgb.size() && k < image.data.size(); ++k) image.data[k] = rgb[k] ? thresholds[rgb[k] - 1u] : 0.0f;
  return image;
}

}  // namespace holoray::live
