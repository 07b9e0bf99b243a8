// Image output: the 8-bit rule, round trips, atomic writes and AOV names.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "image/image_io.hpp"
#include "test_util.hpp"

using namespace holoray;

TEST(Encode8Bit, LinearIsFloorOf255vPlusHalfClamped) {
  EXPECT_EQ(encode_8bit(0.0f, Encoding::linear), 0);
  EXPECT_EQ(encode_8bit(1.0f, Encoding::linear), 255);
  EXPECT_EQ(encode_8bit(0.5f, Encoding::linear), 128);         // 127.5 + 0.5
  EXPECT_EQ(encode_8bit(0.5f / 255, Encoding::linear), 1);     // exactly half a code rounds up
  EXPECT_EQ(encode_8bit(0.49f / 255, Encoding::linear), 0);
  EXPECT_EQ(encode_8bit(-3.0f, Encoding::linear), 0);
  EXPECT_EQ(encode_8bit(7.0f, Encoding::linear), 255);
  EXPECT_EQ(encode_8bit(NAN, Encoding::linear), 0);
}

TEST(Encode8Bit, SrgbUsesTheStandardTransferFunction) {
  EXPECT_EQ(encode_8bit(0.0f, Encoding::srgb), 0);
  EXPECT_EQ(encode_8bit(1.0f, Encoding::srgb), 255);
  EXPECT_EQ(encode_8bit(0.18f, Encoding::srgb), 118);  // 1.055 * 0.18^(1/2.4) - 0.055 = 0.4614
  EXPECT_EQ(encode_8bit(0.002f, Encoding::srgb), 7);   // linear segment: 12.92 * 0.002 * 255 = 6.59
}

TEST(ImageIo, PngRoundTripGivesTheCodesBack) {
  test::TempDir dir;
  ImageBuffer img(7, 5, 3);
  for (size_t k = 0; k < img.data.size(); ++k) img.data[k] = static_cast<float>(k % 256) / 255.0f;
  write_image(dir.file("a.png"), img);
  const ImageBuffer back = read_image(dir.file("a.png"));
  ASSERT_EQ(back.width, 7);
  ASSERT_EQ(back.height, 5);
  ASSERT_EQ(back.channels, 3);
  for (size_t k = 0; k < img.data.size(); ++k) EXPECT_FLOAT_EQ(back.data[k], img.data[k]);
}

TEST(ImageIo, ExrRoundTripIsExactFloat) {
  test::TempDir dir;
  ImageBuffer img(4, 3, 1);
  for (size_t k = 0; k < img.data.size(); ++k) img.data[k] = -1.5f + 0.123456789f * k;
  img.data[5] = NAN;
  write_image(dir.file("d.exr"), img);
  const ImageBuffer back = read_image(dir.file("d.exr"));
  for (size_t k = 0; k < img.data.size(); ++k) {
    if (k == 5) EXPECT_TRUE(std::isnan(back.data[k]));
    else EXPECT_EQ(back.data[k], img.data[k]);
  }
}

TEST(ImageIo, FailedWriteLeavesNothingBehind) {
  test::TempDir dir;
  const ImageBuffer img(2, 2, 3);
  EXPECT_THROW(write_image(dir.file("missing/a.png"), img), std::runtime_error);
  EXPECT_THROW(write_image(dir.file("a.jpg"), img), std::runtime_error);
  EXPECT_TRUE(std::filesystem::is_empty(dir.path));
}

TEST(ImageIo, OverwriteReplacesTheFileAndLeavesNoTemporary) {
  test::TempDir dir;
  write_image(dir.file("a.png"), ImageBuffer(2, 2, 3, 0.0f));
  write_image(dir.file("a.png"), ImageBuffer(3, 3, 3, 1.0f));
  EXPECT_EQ(read_image(dir.file("a.png")).width, 3);
  int files = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir.path)) ++files;
  EXPECT_EQ(files, 1);
}

TEST(ImageIo, AovPathSitsBesideTheImage) {
  EXPECT_EQ(aov_path("out/eia.png", "depth", "exr"), "out/eia.depth.exr");
  EXPECT_EQ(aov_path("eia.png", "albedo", "png"), "eia.albedo.png");
}

namespace holoray {
namespace {

// A giant EIA is written band by band as it arrives (mpirun render): the
// file is byte for byte the one written whole, PNG and EXR, and it appears
// only once every row is in.
TEST(ImageWriter, BandsGiveTheBytesOfTheWholeImageAndNoFileBeforeTheLastRow) {
  test::TempDir dir;
  ImageBuffer img(37, 29, 3);
  for (size_t k = 0; k < img.data.size(); ++k) img.data[k] = static_cast<float>((k * 7919) % 1000) / 999.0f;
  for (const std::string ext : {"png", "exr"}) {
    const std::string whole = dir.file("whole." + ext), banded = dir.file("banded." + ext);
    write_image(whole, img, Encoding::srgb);
    {
      ImageWriter w(banded, img.width, img.height, 3, Encoding::srgb);
      int y = 0;
      for (int rows : {5, 1, 13, 10}) {
        ImageBuffer band(img.width, rows, 3);
        std::copy_n(img.at(0, y), band.data.size(), band.data.begin());
        w.write_rows(band);
        y += rows;
        EXPECT_FALSE(std::filesystem::exists(banded)) << "appeared before the last row";
      }
      w.finish();
    }
    // EXR headers carry the time of writing; both were written within the second.
    EXPECT_EQ(test::read_bytes(banded).size(), test::read_bytes(whole).size()) << ext;
    if (ext == "png") EXPECT_EQ(test::read_bytes(banded), test::read_bytes(whole));
    const ImageBuffer back = read_image(banded);
    EXPECT_EQ(back.data, read_image(whole).data) << ext;
  }
  // Too many rows, or finishing early: refused; nothing left behind.
  {
    ImageWriter w(dir.file("short.png"), 4, 4, 3);
    EXPECT_THROW(w.write_rows(ImageBuffer(4, 5, 3)), std::logic_error);
    w.write_rows(ImageBuffer(4, 2, 3));
    EXPECT_THROW(w.finish(), std::logic_error);
  }
  for (const auto& e : std::filesystem::directory_iterator(dir.path))
    EXPECT_TRUE(e.path().filename().string().starts_with("whole.") || e.path().filename().string().starts_with("banded."))
        << "left behind: " << e.path();
}

}  // namespace
}  // namespace holoray
