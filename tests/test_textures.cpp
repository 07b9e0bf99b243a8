// Mesh textures (render/textures.hpp MipMap::sample_uv, scene/mesh_reader):
// the sampler's wrap modes and filters texel by texel, sRGB decoding, MIP
// levels, and textured glTF scenes against Blender's albedo (the Cycles
// DiffCol pass, tests/data/blender: the scenes, the script that rendered
// them and its EXRs).
#include <gtest/gtest.h>
#include <fmt/format.h>

#include <cmath>

#include "image/image_io.hpp"
#include "image/metrics.hpp"
#include "render/textures.hpp"
#include "test_util.hpp"

namespace holoray {
namespace {

// A width x 1 image whose texel x has red code codes[x] (green, blue 0).
MipMap red_row(std::initializer_list<unsigned char> codes) {
  ImageMap img;
  img.width = static_cast<int>(codes.size());
  img.height = 1;
  for (unsigned char c : codes) img.rgb.insert(img.rgb.end(), {c, 0, 0});
  return MipMap(img);
}

const float* linear_codes() { return decode_table(false); }

double red_at(const MipMap& m, double u, TextureWrap wrap, bool nearest, double level = 0) {
  return m.sample_uv(u, 0.5, level, wrap, TextureWrap::clamp, nearest, linear_codes()).x * 255;
}

TEST(MeshTextures, WrapModesPickTheTexelsOfGltfsSampler) {
  const MipMap m = red_row({10, 20, 30, 40});
  // u = 1.1 is texel 4.4: repeat -> texel 0, clamp -> 3, mirror -> 3 (the last read backwards).
  EXPECT_NEAR(red_at(m, 1.1, TextureWrap::repeat, true), 10, 1e-3);
  EXPECT_NEAR(red_at(m, 1.1, TextureWrap::clamp, true), 40, 1e-3);
  EXPECT_NEAR(red_at(m, 1.1, TextureWrap::mirror, true), 40, 1e-3);
  // u = 1.3 is texel 5.2: repeat -> 1, clamp -> 3, mirror -> 2.
  EXPECT_NEAR(red_at(m, 1.3, TextureWrap::repeat, true), 20, 1e-3);
  EXPECT_NEAR(red_at(m, 1.3, TextureWrap::clamp, true), 40, 1e-3);
  EXPECT_NEAR(red_at(m, 1.3, TextureWrap::mirror, true), 30, 1e-3);
  // Negative u: -0.1 is texel -0.4: repeat -> 3, mirror -> 0.
  EXPECT_NEAR(red_at(m, -0.1, TextureWrap::repeat, true), 40, 1e-3);
  EXPECT_NEAR(red_at(m, -0.1, TextureWrap::mirror, true), 10, 1e-3);
}

TEST(MeshTextures, LinearFilterBlendsTexelCentresAndWrapsAcrossTheSeam) {
  const MipMap m = red_row({10, 20, 30, 40});
  EXPECT_NEAR(red_at(m, 0.125, TextureWrap::repeat, false), 10, 1e-4);  // texel 0's centre
  EXPECT_NEAR(red_at(m, 0.25, TextureWrap::repeat, false), 15, 1e-4);   // between 0 and 1
  // Past the last centre: repeat blends toward texel 0, clamp holds texel 3.
  EXPECT_NEAR(red_at(m, 1.0, TextureWrap::repeat, false), 25, 1e-4);
  EXPECT_NEAR(red_at(m, 1.0, TextureWrap::clamp, false), 40, 1e-4);
}

TEST(MeshTextures, SrgbCodesAreDecodedBeforeFiltering) {
  const float* srgb = decode_table(true);
  EXPECT_EQ(srgb[0], 0.0f);
  EXPECT_EQ(srgb[255], 1.0f);
  EXPECT_NEAR(srgb[188], 0.5029, 1e-4);  // IEC 61966-2-1
  EXPECT_NEAR(srgb[10], 10 / 255.0 / 12.92, 1e-7);
  // Half way between black and white is the mean of the decoded values (0.5), not decode(127.5).
  const MipMap m = red_row({0, 255});
  EXPECT_NEAR(m.sample_uv(0.5, 0.5, 0, TextureWrap::clamp, TextureWrap::clamp, false, srgb).x, 0.5, 1e-6);
}

TEST(MeshTextures, CoarseLevelsAverageTheImage) {
  const MipMap m = red_row({0, 200, 0, 200});
  ASSERT_EQ(m.levels(), 3);
  EXPECT_NEAR(red_at(m, 0.4, TextureWrap::repeat, false, 2), 100, 1);  // one texel: the mean
  // Between levels: linear in the level.
  const double l0 = red_at(m, 0.375, TextureWrap::repeat, false, 0), l1 = red_at(m, 0.375, TextureWrap::repeat, false, 1);
  EXPECT_NEAR(red_at(m, 0.375, TextureWrap::repeat, false, 0.25), 0.75 * l0 + 0.25 * l1, 1e-4);
  // Levels past the last are the last.
  EXPECT_NEAR(red_at(m, 0.4, TextureWrap::repeat, false, 9), 100, 1);
}

// holoray's pinhole albedo AOV of each glTF scene against Blender's DiffCol
// pass (tests/data/blender/render_albedo.py): the texture's orientation,
// wrap modes (wrapped_box: u repeats, v mirrors), sRGB decoding and factor.
class BlenderAlbedo : public ::testing::TestWithParam<const char*> {};

TEST_P(BlenderAlbedo, PinholeAlbedoAovMatchesBlendersDiffuseColourPass) {
  const std::string data = std::string(HOLORAY_SOURCE_DIR) + "/tests/data/blender/";
  test::TempDir dir;
  const std::string out = dir.file("o.exr");
  const auto r = test::run_cli(fmt::format("render {}{}.gltf --camera pinhole --resolution 128x128 --aov albedo -q -o {}",
                                           data, GetParam(), out));
  ASSERT_EQ(r.status, 0) << r.output;
  const ImageBuffer ours = as_rgb(read_image(dir.file("o.albedo.exr")));
  const ImageBuffer blender = as_rgb(read_image(data + GetParam() + ".albedo.exr"));
  const double psnr = compare_images(ours, blender).psnr_all();
  RecordProperty("psnr_db", fmt::format("{:.2f}", psnr));
  EXPECT_GE(psnr, 30) << GetParam();
}

INSTANTIATE_TEST_SUITE_P(Fixtures, BlenderAlbedo, ::testing::Values("textured_box", "wrapped_box"));

}  // namespace
}  // namespace holoray
