// The public API's tools for finished images (holoray/image.hpp,
// preview.hpp, video.hpp, files.hpp), which the CLI and the Python module
// call instead of the core: each checked for a property of its own, not
// against the wrapper's internals.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

#include "holoray/holoray.hpp"
#include "test_util.hpp"

namespace api = holoray::api;
using holoray::test::TempDir;

namespace {

std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// A W x H x C image whose samples differ: v(k) = (k * 37 % 101) / 100.
api::Image ramp(int width, int height, int channels) {
  api::Image img(width, height, channels);
  for (size_t k = 0; k < img.size(); ++k) img.data()[k] = static_cast<float>(k * 37 % 101) / 100.0f;
  return img;
}

// Rows [y0, y1) of `img` as an image of their own.
api::Image rows_of(const api::Image& img, int y0, int y1) {
  api::Image band(img.width(), y1 - y0, img.channels());
  std::copy(img.at(0, y0), img.at(0, y0) + band.size(), band.data());
  return band;
}

size_t files_in(const std::filesystem::path& dir) {
  return static_cast<size_t>(std::distance(std::filesystem::directory_iterator(dir), {}));
}

}  // namespace

TEST(ImageWriter, BandByBandWritesTheBytesOfAWholeWrite) {
  TempDir dir;
  const api::Image img = ramp(37, 29, 3);
  for (const char* ext : {"png", "exr"}) {
    const std::string whole = dir.file(std::string("whole.") + ext), bands = dir.file(std::string("bands.") + ext);
    api::write_image(whole, img, api::Encoding::srgb);
    api::ImageWriter w(bands, img.width(), img.height(), img.channels(), api::Encoding::srgb);
    for (int y = 0; y < img.height(); y += 8) w.write_rows(rows_of(img, y, std::min(y + 8, img.height())));
    w.finish();
    EXPECT_EQ(file_bytes(whole), file_bytes(bands)) << ext;
  }
}

TEST(ImageWriter, LeavesNothingWhenNotFinished) {
  TempDir dir;
  {
    api::ImageWriter w(dir.file("cut.png"), 8, 8, 3);
    w.write_rows(ramp(8, 4, 3));
  }
  EXPECT_EQ(files_in(dir.path), 0u);
}

TEST(BackgroundWriter, WritesEveryImageGivenWithTheBytesOfWriteImage) {
  TempDir dir;
  api::BackgroundWriter writer(1);  // one waiting: the later submits block on the thread
  for (int k = 0; k < 6; ++k) {
    const api::Image img = ramp(31 + k, 17, 3);
    const std::string ext = k % 2 ? "exr" : "png";
    api::write_image(dir.file(fmt::format("direct{}.{}", k, ext)), img, api::Encoding::srgb);
    writer.submit(dir.file(fmt::format("queued{}.{}", k, ext)), img, api::Encoding::srgb);
  }
  writer.finish();
  for (int k = 0; k < 6; ++k) {
    const std::string ext = k % 2 ? "exr" : "png";
    EXPECT_EQ(file_bytes(dir.file(fmt::format("queued{}.{}", k, ext))), file_bytes(dir.file(fmt::format("direct{}.{}", k, ext))))
        << k;
  }
  EXPECT_EQ(files_in(dir.path), 12u);  // no temporaries left
  EXPECT_GT(writer.write_seconds(), 0.0);
}

TEST(BackgroundWriter, ImagesGivenBeforeTheWriterEndsAreWrittenWithoutFinish) {
  TempDir dir;
  {
    api::BackgroundWriter writer(3);
    for (int k = 0; k < 3; ++k) writer.submit(dir.file(fmt::format("f{}.png", k)), ramp(64, 64, 3));
  }
  EXPECT_EQ(files_in(dir.path), 3u);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(api::read_image(dir.file(fmt::format("f{}.png", k))).width(), 64);
}

TEST(BackgroundWriter, AFailedWriteIsThrownByTheNextCallAndNothingAfterItIsWritten) {
  TempDir dir;
  api::BackgroundWriter writer(4);
  const std::string missing = dir.file("no/such/folder/a.png");
  try {
    // The failure may come back from the second submit or from finish().
    writer.submit(missing, ramp(8, 8, 3));
    writer.submit(dir.file("after.png"), ramp(8, 8, 3));
    writer.finish();
    FAIL() << "neither submit() nor finish() threw";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(missing), std::string::npos) << e.what();
  }
  EXPECT_THROW(writer.submit(dir.file("later.png"), ramp(8, 8, 3)), std::runtime_error);
  EXPECT_FALSE(std::filesystem::exists(dir.file("after.png")));
  EXPECT_FALSE(std::filesystem::exists(dir.file("later.png")));
}

TEST(BackgroundWriter, RefusesADepthBelowOne) {
  try {
    api::BackgroundWriter writer(0);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "BackgroundWriter: depth must be at least 1, got 0");
  }
}

TEST(CompareImages, AnOffsetOfOneCodeIsAnMseOfOne) {
  api::Image a(4, 3, 3, 0.5f), b(4, 3, 3, 0.5f + 1.0f / 255.0f);
  const api::Difference d = api::compare_images(a, b);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(d.mse[static_cast<size_t>(c)], 1.0, 1e-6);
  EXPECT_NEAR(d.psnr(), 10 * std::log10(255.0 * 255.0), 1e-5);
  EXPECT_EQ(d.pixels, 12);
  EXPECT_TRUE(std::isinf(api::compare_images(a, a).psnr()));
}

TEST(SubapertureView, DefaultsToTheLensCentrePixelAndNamesTheLayoutInErrors) {
  // 3 x 2 lenses of 4 x 4 pixels; pixel (u, v) of lens (i, j) holds 100 j + 10 i + 4 v + u.
  api::Image eia(12, 8, 1);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 12; ++x) *eia.at(x, y) = static_cast<float>(100 * (y / 4) + 10 * (x / 4) + 4 * (y % 4) + x % 4);
  const api::Image centre = api::subaperture_view(eia, {api::Grid::square, 4});
  ASSERT_EQ(centre.width(), 3);
  ASSERT_EQ(centre.height(), 2);
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 3; ++i) EXPECT_EQ(*centre.at(i, j), 100 * j + 10 * i + 4 * 2 + 2);
  EXPECT_EQ(*api::subaperture_view(eia, {api::Grid::square, 4}, 1, 3).at(2, 1), 100 + 20 + 12 + 1);
  try {
    api::subaperture_view(eia, {api::Grid::square, 5});
    FAIL() << "an EIA of part lenses was taken";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "the EIA is 12 pixels wide, not a multiple of 5 pixels per lens");
  }
}

TEST(InterlaceQuilt, RefusesViewsOfPartPixelsAndAMissingCalibration) {
  const std::string cal = holoray::test::source_dir() + "/examples/displays/looking_glass_example_calibration.json";
  try {
    api::interlace_quilt(api::Image(10, 6, 3), 3, 2, cal);
    FAIL() << "a quilt of part pixels was taken";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "a 10x6 image is not 3x2 views of whole pixels");
  }
  TempDir dir;
  EXPECT_THROW(api::interlace_quilt(api::Image(9, 6, 3), 3, 2, dir.file("none.json")), std::system_error);
}

TEST(SimulateView, AMalformedDisplayFileIsASceneErrorNamingIt) {
  TempDir dir;
  const std::string path = dir.file("bad.toml");
  std::ofstream(path) << "[panel\n";
  try {
    api::simulate_view(api::Image(8, 8, 3), path);
    FAIL() << "a malformed display file was read";
  } catch (const api::SceneError& e) {
    EXPECT_EQ(e.file(), path);
  }
}

TEST(QuiltFileName, PutsTheLayoutBeforeTheExtension) {
  EXPECT_EQ(api::quilt_file_name("out/q.png", {8, 6, 420, 560, 40}), "out/q_qs8x6a0.75.png");
}

TEST(VideoWriter, RefusesAFrameOfAnotherSizeAndLeavesNoFile) {
  TempDir dir;
  {
    api::VideoWriter video(dir.file("v.mkv"), 16, 8, {});
    try {
      video.add_frame(api::Image(8, 8, 3));
      FAIL() << "a frame of another size was taken";
    } catch (const std::invalid_argument& e) {
      EXPECT_STREQ(e.what(), "video frame 0: expected 16x8 pixels of RGB, got 8x8 of 3 channels");
    }
  }
  EXPECT_EQ(files_in(dir.path), 0u);
}

TEST(WriteTextFile, WritesTheTextWholeAndNoTemporary) {
  TempDir dir;
  api::write_text_file(dir.file("r.md"), "# report\nline\n");
  EXPECT_EQ(file_bytes(dir.file("r.md")), "# report\nline\n");
  EXPECT_EQ(files_in(dir.path), 1u);
  EXPECT_THROW(api::write_text_file(dir.file("no/such/folder/r.md"), "x"), std::system_error);
}

TEST(BuiltWith, NamesTheLibrariesLinked) {
  const std::string s = api::built_with();
  for (const char* name : {"Embree ", "oneTBB ", "libpng ", "OpenEXR ", "assimp ", "fmt "})
    EXPECT_NE(s.find(name), std::string::npos) << name << " in " << s;
}
