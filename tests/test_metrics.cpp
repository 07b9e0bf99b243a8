// Image difference measures (paper Table 1): MSE on the 8-bit scale, PSNR,
// and NaN samples (the depth AOV's background).
#include <gtest/gtest.h>

#include <cmath>

#include "image/metrics.hpp"

namespace holoray {

TEST(Metrics, OneCodeStepEverywhereIsMseOne) {
  const ImageBuffer a(4, 3, 3, 0.5f);
  ImageBuffer b = a;
  for (float& v : b.data) v += 1.0f / 255.0f;
  const ImageDifference d = compare_images(a, b);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(d.mse[static_cast<size_t>(c)], 1.0, 1e-5);  // values are stored as float
  EXPECT_NEAR(d.psnr_all(), 10 * std::log10(255.0 * 255.0), 1e-5);
}

TEST(Metrics, NanAgainstNanIsEqualAndNanAgainstAValueIsCountedApart) {
  ImageBuffer a(2, 2, 1, 0.25f), b(2, 2, 1, 0.25f);
  *a.at(0, 0) = *b.at(0, 0) = NAN;  // background in both depth AOVs
  EXPECT_EQ(compare_images(a, b).mse_all, 0);
  EXPECT_TRUE(std::isinf(compare_images(a, b).psnr_all()));
  EXPECT_EQ(compare_images(a, b).nan_mismatches, 0);
  *b.at(1, 1) = NAN;  // a surface in one, background in the other
  *b.at(1, 0) = 0.25f + 2.0f / 255.0f;
  const ImageDifference d = compare_images(a, b);
  EXPECT_EQ(d.nan_mismatches, 3);  // a grey image counts as R = G = B
  // Of the 4 pixels, 3 compared per channel: one off by 2 codes.
  EXPECT_NEAR(d.mse_all, 4.0 / 3.0, 1e-5);
}

}  // namespace holoray
