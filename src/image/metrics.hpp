// holoray/image: image difference measures on the 8-bit scale, as the paper
// reports them (Table 1): MSE per channel and overall, RMSE, and
// PSNR = 10*log10(255^2 / MSE) in dB (infinite for identical images).
#pragma once

#include <array>
#include <cstdint>

#include "image/image.hpp"
#include "image/image_io.hpp"

namespace holoray {

struct ImageDifference {
  std::array<double, 3> mse{};  ///< per channel (R, G, B), on 0..255
  double mse_all = 0;           ///< over all three channels
  int64_t pixels = 0;
  /// Channel samples that are NaN in one image only, left out of the MSE
  /// (NaN against NaN counts as equal: the depth AOV's background).
  int64_t nan_mismatches = 0;

  double rmse(int channel) const;
  double rmse_all() const;
  double psnr(int channel) const;
  double psnr_all() const;
};

/// PSNR in dB of an MSE on the 8-bit scale; +infinity for 0.
double psnr_from_mse(double mse);

/// Compares two images of values in 0..1 nominal (scaled by 255; a grey
/// image counts as R=G=B, an alpha channel is ignored). NaN samples: see
/// ImageDifference::nan_mismatches. Throws std::invalid_argument when the
/// sizes differ.
ImageDifference compare_images(const ImageBuffer& a, const ImageBuffer& b);

/// The values a PNG write would store, as k/255, so that in-memory
/// comparisons match comparisons of the written files.
ImageBuffer quantize_8bit(const ImageBuffer& image, Encoding encoding);

}  // namespace holoray
