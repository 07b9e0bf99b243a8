#include "image/metrics.hpp"

#include <fmt/format.h>

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
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      const float* pa = a.at(x, y);
      const float* pb = b.at(x, y);
      for (int c = 0; c < 3; ++c) {
        const double e = 255.0 * (double(channel(pa, a.channels, c)) - double(channel(pb, b.channels, c)));
        sum[static_cast<size_t>(c)] += e * e;
      }
    }
  const double n = static_cast<double>(std::max<int64_t>(1, d.pixels));
  for (size_t c = 0; c < 3; ++c) d.mse[c] = sum[c] / n;
  d.mse_all = (sum[0] + sum[1] + sum[2]) / (3 * n);
  return d;
}

ImageBuffer quantize_8bit(const ImageBuffer& image, Encoding encoding) {
  ImageBuffer q = image;
  for (float& v : q.data) v = encode_8bit(v, encoding) / 255.0f;
  return q;
}

}  // namespace holoray
