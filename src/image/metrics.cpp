#include "image/metrics.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace holoray {

double psnr_from_mse(double mse) { return mse > 0 ? 10 * std::log10(255.0 * 255.0 / mse) : INFINITY; }

double ImageDifference::rmse(int c) const { return std::sqrt(mse[static_cast<size_t>(c)]); }
double ImageDifference::rmse_all() const { return std::sqrt(mse_all); }
double ImageDifference::psnr(int c) const { return psnr_from_mse(mse[static_cast<size_t>(c)]); }
double ImageDifference::psnr_all() const { return psnr_from_mse(mse_all); }

ImageDifference compare_images(const ImageBuffer& a, const ImageBuffer& b) {
  if (a.width != b.width || a.height != b.height)
    throw std::invalid_argument(fmt::format("the images differ in size: {}x{} and {}x{}", a.width, a.height, b.width, b.height));
  if (a.channels < 1 || b.channels < 1) throw std::invalid_argument("an image has no channels");
  ImageDifference d;
  d.pixels = static_cast<int64_t>(a.width) * a.height;
  auto channel = [](const float* p, int channels, int c) { return channels >= 3 ? p[c] : p[0]; };
  std::array<double, 3> sum{};
  std::array<int64_t, 3> count{};
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      const float* pa = a.at(x, y);
      const float* pb = b.at(x, y);
      for (size_t c = 0; c < 3; ++c) {
        const float va = channel(pa, a.channels, static_cast<int>(c)), vb = channel(pb, b.channels, static_cast<int>(c));
        // NaN means "no value" (the depth AOV's background): equal when both
        // have none; a value against none is counted apart, not averaged.
        if (std::isnan(va) || std::isnan(vb)) {
          if (std::isnan(va) && std::isnan(vb)) ++count[c];
          else ++d.nan_mismatches;
          continue;
        }
        const double e = 255.0 * (double(va) - double(vb));
        sum[c] += e * e;
        ++count[c];
      }
    }
  for (size_t c = 0; c < 3; ++c) d.mse[c] = sum[c] / static_cast<double>(std::max<int64_t>(1, count[c]));
  d.mse_all = (sum[0] + sum[1] + sum[2]) / static_cast<double>(std::max<int64_t>(1, count[0] + count[1] + count[2]));
  return d;
}

ImageBuffer quantize_8bit(const ImageBuffer& image, Encoding encoding) {
  ImageBuffer q = image;
  for (float& v : q.data) v = encode_8bit(v, encoding) / 255.0f;
  return q;
}

}  // namespace holoray
