// Image output: the 8-bit rule, round trips, atomic writes and AOV names.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <zlib.h>

#include <png.h>

#include "image/formats.hpp"
#include "image/image_io.hpp"
#include "image/srgb_code.hpp"
#include "test_util.hpp"

using namespace holoray;

// The fill is written on every core in 2 MiB pieces (image.cpp): every
// sample, the last partial piece included, must get it; sizes around the
// piece boundary and a 2048x2048 RGB frame (24 pieces).
TEST(ImageBufferFill, EverySampleGetsTheFillValueWhateverTheSize) {
  constexpr size_t kPiece = (size_t{2} << 20) / sizeof(float);
  const std::vector<std::array<int, 3>> sizes = {{1, 1, 1}, {3, 5, 3},           {int(kPiece) - 1, 1, 1},
                                                 {int(kPiece), 1, 1},            {int(kPiece) + 1, 1, 1},
                                                 {2048, 2048, 3}};
  for (const auto& [w, h, c] : sizes)
    for (float fill : {0.0f, -1.0f}) {
      const ImageBuffer img(w, h, c, fill);
      ASSERT_EQ(img.data.size(), size_t(w) * h * c);
      EXPECT_TRUE(std::all_of(img.data.begin(), img.data.end(), [&](float v) { return v == fill; }))
          << w << "x" << h << "x" << c << " fill " << fill;
    }
  const ImageBuffer depth(2048, 2048, 1, NAN);
  EXPECT_TRUE(std::all_of(depth.data.begin(), depth.data.end(), [](float v) { return std::isnan(v); }));
}

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

// The batch (four values per SSE2 pass, then a scalar tail) gives each
// value the single-value formula's code: every 997th float between -0.01 and
// 1.01 (every code step, both sides of each half), infinities, NaN and
// huge values, at odd counts so that the tail runs too.
TEST(Encode8Bit, LinearBatchEqualsTheFormulaValueByValue) {
  std::vector<float> values;
  for (float v = -0.01f; v < 1.01f;) {
    values.push_back(v);
    uint32_t bits;
    std::memcpy(&bits, &v, 4);
    bits = v < 0 ? bits - 997 : bits + 997;
    if (v < 0 && bits < 0x80000000u) bits = 0;
    std::memcpy(&v, &bits, 4);
  }
  for (const float k : {0.5f, 1.5f, 127.5f, 254.5f})
    for (const float d : {-1e-6f, 0.0f, 1e-6f}) values.push_back((k + d) / 255);
  for (const float v : {INFINITY, -INFINITY, NAN, -NAN, 1e30f, -1e30f, -0.0f}) values.push_back(v);
  ASSERT_GT(values.size(), size_t{1000000});
  for (const size_t n : {values.size(), values.size() - 1, size_t{3}}) {
    std::vector<uint8_t> codes(n);
    encode_8bit_here(values.data(), n, codes.data(), Encoding::linear);
    for (size_t k = 0; k < n; ++k)
      ASSERT_EQ(codes[k], encode_8bit(values[k], Encoding::linear)) << "value " << values[k] << " of " << n;
  }
}

TEST(Encode8Bit, SrgbUsesTheStandardTransferFunction) {
  EXPECT_EQ(encode_8bit(0.0f, Encoding::srgb), 0);
  EXPECT_EQ(encode_8bit(1.0f, Encoding::srgb), 255);
  EXPECT_EQ(encode_8bit(0.18f, Encoding::srgb), 118);  // 1.055 * 0.18^(1/2.4) - 0.055 = 0.4614
  EXPECT_EQ(encode_8bit(0.002f, Encoding::srgb), 7);   // linear segment: 12.92 * 0.002 * 255 = 6.59
}

// The table's codes are the formula's wherever the formula's code never
// decreases as v grows; only within a few ULPs of a step could a wiggle of
// pow() turn a code back, so every float within 4096 ULPs of each step is
// checked, and the steps are where the formula says.
TEST(SrgbCode, EqualsTheFormulaAtEveryFloatNearEveryStep) {
  for (int c = 1; c <= 255; ++c) {
    const float step = srgb_code_step(c);
    ASSERT_GE(srgb_code_by_formula(step), c);
    ASSERT_LT(srgb_code_by_formula(std::nextafter(step, -1.0f)), c);
    const uint32_t bits = std::bit_cast<uint32_t>(step);
    for (uint32_t b = bits - 4096; b <= bits + 4096; ++b) {
      const float v = std::bit_cast<float>(b);
      ASSERT_EQ(srgb_code(v), srgb_code_by_formula(v)) << "v = " << v << " near the step to " << c;
    }
  }
}

TEST(SrgbCode, EqualsTheFormulaOnSpecialAndRandomValues) {
  std::vector<float> v = {NAN, -NAN, INFINITY, -INFINITY, -0.0f, 0.0f, 1.0f, std::nextafter(1.0f, 0.0f), 2.0f,
                          -1e-30f, 1e-45f, 1e30f, 0.0031308f, std::nextafter(0.0031308f, 1.0f)};
  uint32_t state = 777;
  for (int k = 0; k < 1000000; ++k) {
    state = state * 1664525u + 1013904223u;
    v.push_back(static_cast<float>(state >> 8) / static_cast<float>(1 << 24) * 1.2f - 0.1f);
    v.push_back(std::bit_cast<float>(state & 0x3f7fffffu));  // any float in [0, 1), tiny ones included
  }
  for (float x : v) ASSERT_EQ(srgb_code(x), srgb_code_by_formula(x)) << x;
}

TEST(Encode8Bit, ManyAtOnceGiveTheCodesOfOneAtATime) {
  std::vector<float> v = {NAN, -NAN, INFINITY, -INFINITY, -0.0f, 0.0f, 1.0f, 2.0f, -1e-30f, 1e30f};
  for (int c = 0; c <= 256; ++c)  // around every half code, where the rounding turns
    for (int ulps = -3; ulps <= 3; ++ulps) {
      float x = (static_cast<float>(c) - 0.5f) / 255.0f;
      for (int u = 0; u < std::abs(ulps); ++u) x = std::nextafter(x, ulps < 0 ? -1.0f : 2.0f);
      v.push_back(x);
    }
  uint32_t state = 12345;
  for (int k = 0; k < 300000; ++k) {  // random values in and around 0..1, enough to run on several threads
    state = state * 1664525u + 1013904223u;
    v.push_back(static_cast<float>(state >> 8) / static_cast<float>(1 << 24) * 1.2f - 0.1f);
  }
  for (Encoding e : {Encoding::linear, Encoding::srgb}) {
    std::vector<uint8_t> codes(v.size());
    encode_8bit(v.data(), v.size(), codes.data(), e);
    for (size_t k = 0; k < v.size(); ++k) ASSERT_EQ(codes[k], encode_8bit(v[k], e)) << v[k];
    std::vector<uint8_t> here(v.size());
    encode_8bit_here(v.data(), v.size(), here.data(), e);
    EXPECT_EQ(here, codes);
  }
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

TEST(ImageIo, DefaultEncodingIsLinearForNffAndTachyonScenesAndSrgbForMeshes) {
  for (const char* scene : {"a.nff", "dir/b.NFF", "room.dat", "x.Dat"}) EXPECT_EQ(default_encoding(scene), Encoding::linear) << scene;
  for (const char* scene : {"truck.gltf", "m.glb", "m.OBJ", "m.ply", "noext"}) EXPECT_EQ(default_encoding(scene), Encoding::srgb) << scene;
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
    EXPECT_EQ(test::read_bytes(banded), test::read_bytes(whole)) << ext;
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

// ---- every format against an independent decoder (OpenImageIO's oiiotool) ----

namespace holoray {
namespace {

// oiiotool's decoding of `path`: every value of every pixel, rows from the
// top. Integer formats print their codes, float formats their values.
std::vector<double> oiio_values(const std::string& path) {
  const auto r = test::run_shell("oiiotool --iconfig oiio:UnassociatedAlpha 1 --dumpdata --info '" + path + "'");
  EXPECT_EQ(r.status, 0) << r.output;
  std::vector<double> values;
  std::istringstream lines(r.output);
  for (std::string line; std::getline(lines, line);) {
    const size_t at = line.find("): ");
    if (line.find("Pixel (") == std::string::npos || at == std::string::npos) continue;
    std::istringstream fields(line.substr(at + 3, line.find(" (", at + 3) - at - 3));
    for (std::string v; fields >> v;) values.push_back(v == "nan" ? NAN : std::stod(v));
  }
  return values;
}

ImageBuffer pattern(int w, int h, int c) {
  ImageBuffer img(w, h, c);
  for (size_t k = 0; k < img.data.size(); ++k) img.data[k] = static_cast<float>((k * 7919 + 13) % 1000) / 999.0f;
  return img;
}

TEST(ImageFormats, PngCodesAreTheEncodedValuesForAnIndependentDecoder) {
  test::TempDir dir;
  for (int channels : {1, 3, 4})
    for (Encoding e : {Encoding::linear, Encoding::srgb}) {
      const ImageBuffer img = pattern(9, 7, channels);
      const std::string file = dir.file("p" + std::to_string(channels) + ".png");
      write_image(file, img, e);
      const std::vector<double> codes = oiio_values(file);
      ASSERT_EQ(codes.size(), img.data.size()) << channels;
      for (size_t k = 0; k < codes.size(); ++k) ASSERT_EQ(codes[k], encode_8bit(img.data[k], e)) << channels << " " << k;
    }
}

// Deflated on several threads in segments of one 121-byte row each, from two
// bands of rows: still one image for another decoder, and the same codes as
// libpng's own compression gives.
TEST(ImageFormats, SegmentedPngIsTheSameImageForAnIndependentDecoder) {
  test::TempDir dir;
  const ImageBuffer img = pattern(40, 30, 3);
  auto write = [&](const std::string& file, formats::PngCompression c) {
    auto png = formats::open_png(file, 40, 30, 3, Encoding::srgb, c);
    png->write_rows(img.data.data(), 11);
    png->write_rows(img.data.data() + 11 * 40 * 3, 19);
    png->close();
  };
  write(dir.file("segmented.png"), {1, Z_DEFAULT_STRATEGY, PNG_FILTER_NONE, 200});
  write(dir.file("serial.png"), {1, Z_DEFAULT_STRATEGY, PNG_FILTER_NONE, 0});
  const std::vector<double> codes = oiio_values(dir.file("segmented.png"));
  ASSERT_EQ(codes.size(), img.data.size());
  for (size_t k = 0; k < codes.size(); ++k) ASSERT_EQ(codes[k], encode_8bit(img.data[k], Encoding::srgb)) << k;
  EXPECT_EQ(oiio_values(dir.file("serial.png")), codes);
  EXPECT_NE(test::run_shell("oiiotool --info -v '" + dir.file("segmented.png") + "'").output.find("sRGB"), std::string::npos);
}

TEST(ImageFormats, SegmentedPngNeedsRowsWithoutAFilter) {
  test::TempDir dir;
  try {
    formats::open_png(dir.file("x.png"), 4, 4, 3, Encoding::linear, {1, Z_DEFAULT_STRATEGY, PNG_FILTER_SUB, 200});
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "segmented PNG compression writes rows without a filter");
  }
}

TEST(ImageFormats, ExrFloatsAndChannelNamesAreTheSameForAnIndependentDecoder) {
  test::TempDir dir;
  for (int channels : {1, 3, 4}) {
    ImageBuffer img = pattern(9, 7, channels);
    img.data[3] = NAN;
    img.data[4] = -2.5e7f;
    const std::string file = dir.file("e" + std::to_string(channels) + ".exr");
    write_image(file, img);
    const std::vector<double> values = oiio_values(file);
    ASSERT_EQ(values.size(), img.data.size()) << channels;
    for (size_t k = 0; k < values.size(); ++k) {
      if (std::isnan(img.data[k])) EXPECT_TRUE(std::isnan(values[k]));
      else EXPECT_NEAR(values[k], img.data[k], 1e-6 * std::max(1.0, std::abs(double(img.data[k])))) << k;
    }
    const auto info = test::run_shell("oiiotool --info -v '" + file + "'");
    const char* names = channels == 1 ? "channel list: Y\n" : channels == 3 ? "channel list: R, G, B\n" : "channel list: R, G, B, A\n";
    EXPECT_NE(info.output.find(names), std::string::npos) << info.output;
    EXPECT_NE(info.output.find("compression: \"zip\""), std::string::npos) << info.output;
  }
}

// Every --exr-compression is lossless (NaN, negatives and huge values come
// back bit for bit) and names itself in the header an independent reader sees.
TEST(ImageFormats, EveryExrCompressionIsLosslessAndNamedInTheHeader) {
  test::TempDir dir;
  ImageBuffer img = pattern(37, 21, 4);
  img.data[3] = NAN;
  img.data[4] = -2.5e7f;
  for (const auto& [c, name] : {std::pair{ExrCompression::none, "none"}, {ExrCompression::rle, "rle"},
                                {ExrCompression::zips, "zips"}, {ExrCompression::zip, "zip"},
                                {ExrCompression::piz, "piz"}}) {
    const std::string file = dir.file(std::string(name) + ".exr");
    write_image(file, img, Encoding::linear, c);
    const ImageBuffer back = read_image(file);
    ASSERT_EQ(back.data.size(), img.data.size()) << name;
    EXPECT_EQ(std::memcmp(back.data.data(), img.data.data(), img.data.size() * sizeof(float)), 0) << name;
    const auto info = test::run_shell("oiiotool --info -v '" + file + "'");
    EXPECT_NE(info.output.find(std::string("compression: \"") + name + "\""), std::string::npos) << info.output;
  }
}

// Files written by OpenImageIO in each format holoray reads: read_image gives
// OpenImageIO's own decoding, codes over their maximum, rows from the top.
TEST(ImageFormats, EveryReadFormatGivesTheIndependentDecodersValues) {
  test::TempDir dir;
  write_image(dir.file("src.png"), pattern(11, 6, 3));
  write_image(dir.file("grey.png"), pattern(11, 6, 1));
  struct Case {
    const char* file;
    const char* oiio_args;
    const char* format;
    double max;
  } cases[] = {
      {"a.ppm", "src.png", "pnm", 255},          {"g.pgm", "grey.png", "pnm", 255},
      {"a.tga", "src.png", "targa", 255},        {"a.bmp", "src.png", "bmp", 255},
      {"a.jpg", "src.png", "jpeg", 255},         {"w.png", "src.png -d uint16", "png", 65535},
      {"h.exr", "src.png -d half", "openexr", 0}, {"rgba.png", "src.png --ch R,G,B,A=0.5", "png", 255},
  };
  for (const Case& c : cases) {
    const std::string file = dir.file(c.file);
    const auto made = test::run_shell("cd '" + dir.path.string() + "' && oiiotool " + c.oiio_args + " -o " + c.file);
    ASSERT_EQ(made.status, 0) << made.output;
    const ImageHeader h = read_image_header(file);
    EXPECT_EQ(h.format, c.format) << c.file;
    const ImageBuffer img = read_image(file);
    EXPECT_EQ(img.width, 11) << c.file;
    EXPECT_EQ(img.height, 6) << c.file;
    EXPECT_EQ(img.channels, h.channels) << c.file;
    const std::vector<double> want = oiio_values(file);
    ASSERT_EQ(want.size(), img.data.size()) << c.file;
    for (size_t k = 0; k < want.size(); ++k) {
      const double v = c.max > 0 ? want[k] / c.max : want[k];
      ASSERT_NEAR(img.data[k], v, 1e-6) << c.file << " value " << k;
    }
  }
}

// read_image_codes: an 8-bit PNG's or a JPEG's codes are read_image's
// values times 255, exactly; other images are left to read_image.
TEST(ImageFormats, CodesAreTheValuesTimes255ForEightBitPngAndJpeg) {
  test::TempDir dir;
  write_image(dir.file("src.png"), pattern(11, 6, 3));
  write_image(dir.file("grey.png"), pattern(11, 6, 1));
  for (const char* made : {"src.png -o a.jpg", "src.png --ch R,G,B,A=0.5 -o rgba.png", "src.png -d uint16 -o w.png",
                           "src.png -d half -o h.exr", "src.png -o a.ppm"}) {
    const auto r = test::run_shell("cd '" + dir.path.string() + "' && oiiotool " + made);
    ASSERT_EQ(r.status, 0) << r.output;
  }
  for (const char* f : {"src.png", "grey.png", "rgba.png", "a.jpg"}) {
    ImageHeader h;
    const auto codes = read_image_codes(dir.file(f), &h);
    ASSERT_TRUE(codes.has_value()) << f;
    const ImageBuffer img = read_image(dir.file(f));
    EXPECT_EQ(codes->width, img.width) << f;
    EXPECT_EQ(codes->height, img.height) << f;
    EXPECT_EQ(codes->channels, img.channels) << f;
    EXPECT_EQ(h.channels, img.channels) << f;
    ASSERT_EQ(codes->codes.size(), img.data.size()) << f;
    for (size_t k = 0; k < img.data.size(); ++k)
      ASSERT_EQ(static_cast<float>(codes->codes[k]) * (1.0f / 255.0f), img.data[k]) << f << " value " << k;
  }
  for (const char* f : {"w.png", "h.exr", "a.ppm"}) EXPECT_FALSE(read_image_codes(dir.file(f)).has_value()) << f;
}

// A PNG whose header claims 100000 x 100000 pixels: refused
// from the header, before 120 GB of pixels are allocated.
TEST(ImageFormats, AbsurdSizesAreRefusedFromTheHeader) {
  test::TempDir dir;
  std::string ihdr = std::string("IHDR") + std::string("\0\x01\x86\xa0\0\x01\x86\xa0\x08\x02\0\0\0", 13);
  const uLong crc = crc32(0, reinterpret_cast<const Bytef*>(ihdr.data()), static_cast<uInt>(ihdr.size()));
  std::string png = std::string("\x89PNG\r\n\x1a\n", 8) + std::string("\0\0\0\x0d", 4) + ihdr;
  for (int shift : {24, 16, 8, 0}) png += static_cast<char>((crc >> shift) & 0xff);
  png += std::string("\0\0\0\0IDAT\x35\xaf\x06\x1e", 12);  // an empty IDAT chunk: the pixels would follow
  std::ofstream(dir.file("huge.png"), std::ios::binary) << png;
  const ImageHeader h = read_image_header(dir.file("huge.png"));
  EXPECT_EQ(h.width, 100000);
  EXPECT_EQ(h.height, 100000);
  try {
    read_image(dir.file("huge.png"));
    ADD_FAILURE() << "read";
  } catch (const ImageReadError& e) {
    EXPECT_EQ(e.reason(), "100000x100000 pixels, 3 channels (at most 1073741824 pixels)");
  }
  try {
    read_image_codes(dir.file("huge.png"));
    ADD_FAILURE() << "read as codes";
  } catch (const ImageReadError& e) {
    EXPECT_EQ(e.reason(), "100000x100000 pixels, 3 channels (at most 1073741824 pixels)");
  }
}

TEST(ImageFormats, UnreadableFilesNameTheFileAndTheReason) {
  test::TempDir dir;
  std::ofstream(dir.file("text.png")) << "not an image\n";
  std::ofstream(dir.file("cut.png")) << "\x89PNG\r\n\x1a\n\0\0";
  for (const auto& [file, reason] : std::vector<std::pair<std::string, std::string>>{
           {"none.png", "no such file"},
           {"text.png", "not an image holoray reads"},
           {"cut.png", ""},
       }) {
    try {
      read_image(dir.file(file));
      ADD_FAILURE() << file << " was read";
    } catch (const ImageReadError& e) {
      EXPECT_TRUE(std::string(e.what()).starts_with("cannot read image '" + dir.file(file) + "': ")) << e.what();
      EXPECT_TRUE(e.reason().starts_with(reason)) << e.reason();
      EXPECT_FALSE(e.reason().empty());
    }
  }
}

}  // namespace
}  // namespace holoray
