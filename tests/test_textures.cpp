// Mesh textures (render/textures.hpp MipMap::sample_uv, scene/mesh_reader):
// the sampler's wrap modes and filters texel by texel, sRGB decoding, MIP
// levels, and textured glTF scenes against Blender's albedo (the Cycles
// DiffCol pass, tests/data/blender: the scenes, the script that rendered
// them and its EXRs).
#include <gtest/gtest.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include "camera/pinhole.hpp"
#include "image/image_io.hpp"
#include "image/metrics.hpp"
#include "render/render_scene.hpp"
#include "render/textures.hpp"
#include "render/view_renderer.hpp"
#include "scene/mesh_reader.hpp"
#include "test_util.hpp"

namespace holoray {
namespace {

// A quad over [-1, 1]^2 at z = 0 (positions), its texture coordinates (u
// right, v down as glTF has them) and two triangles, as one glTF buffer.
constexpr const char* kQuadBuffer = "AACAvwAAgL8AAAAAAACAPwAAgL8AAAAAAACAPwAAgD8AAAAAAACAvwAAgD8AAAAAAAAAAAAAgD8AAIA/AACAPwAAgD8AAAAAAAAAAAAAAAAAAAEAAgAAAAIAAwA=";

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
// pass (tests/data/blender/render_oracle.py): the texture's orientation,
// wrap modes (wrapped_box: u repeats, v mirrors), KHR_texture_transform
// (transform_box: offset, rotation, non-uniform scale), alphaMode MASK
// (masked_leaf: a disc cut from a quad by its RGBA image), sRGB decoding.
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

INSTANTIATE_TEST_SUITE_P(Fixtures, BlenderAlbedo, ::testing::Values("textured_box", "wrapped_box", "transform_box", "masked_leaf", "lit_spheres",
                                           "mapped_plane"));

// The same scene with its image beside the file, in a data URI and in a
// GLB's binary chunk (tests/data/blender/make_scenes.py): the same pixels.
TEST(MeshTextures, EmbeddedImagesRenderAsTheFileBesideTheScene) {
  const std::string data = std::string(HOLORAY_SOURCE_DIR) + "/tests/data/blender/";
  test::TempDir dir;
  std::vector<ImageBuffer> albedo;
  for (const char* file : {"textured_box.gltf", "textured_box_datauri.gltf", "textured_box.glb"}) {
    SCOPED_TRACE(file);
    const auto r = test::run_cli(fmt::format("render {}{} --camera pinhole --resolution 64x64 --aov albedo -o {}", data,
                                             file, dir.file("o.exr")));
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_EQ(r.output.find("warning"), std::string::npos) << r.output;
    albedo.push_back(read_image(dir.file("o.albedo.exr")));
  }
  EXPECT_EQ(albedo[0].data, albedo[1].data);
  EXPECT_EQ(albedo[0].data, albedo[2].data);
  // And the texture is there: the albedo is not one flat colour.
  EXPECT_NE(*std::min_element(albedo[0].data.begin(), albedo[0].data.end()),
            *std::max_element(albedo[0].data.begin(), albedo[0].data.end()));
}

TEST(MeshTextures, MaterialsSharingAnImageReadItOnceAndKeepTheirFactors) {
  test::TempDir dir;
  test::write_text(dir.file("m.mtl"), "newmtl plain\nmap_Kd t.ppm\nnewmtl tinted\nKd 0.5 0.25 1\nmap_Kd t.ppm\n");
  test::write_text(dir.file("t.ppm"), "P6\n1 1\n255\nabc");
  test::write_text(dir.file("m.obj"), "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n"
                                      "usemtl plain\nf 1/1 2/2 3/3\nusemtl tinted\nf 1/1 3/3 2/2\n");
  const SceneDesc d = read_mesh_file(dir.file("m.obj"));
  ASSERT_EQ(d.objects.size(), 2u);
  const Material& plain = d.materials.at(static_cast<size_t>(d.objects[0].material));
  const Material& tinted = d.materials.at(static_cast<size_t>(d.objects[1].material));
  // assimp's OBJ reader gives every material a Kd (0.6 when the file has
  // none), so only the written one can be checked here.
  EXPECT_EQ(tinted.colour.y, 0.25);
  EXPECT_GE(plain.texture, 0);
  EXPECT_GE(tinted.texture, 0);
  // One image read once for both materials.
  EXPECT_EQ(d.images.size(), 1u);
}

// A quad filling a pinhole view, textured with a one-texel black and white
// checker of 192x192: 64 pixels across, 3 texels each, every pixel centre on
// a texel centre. With no footprint each pixel reads its one texel (0 or 1);
// with a footprint of a pixel's angle, its MIP level (log2 3) averages them:
// the albedo is the checker's mean light, 0.5 (not the mean code's 0.21).
TEST(MeshTextures, ThePixelFootprintChoosesTheMipLevel) {
  SceneDesc d;
  d.source = "quad";
  ImageMap img;
  img.width = img.height = 192;
  img.srgb = true;
  for (int y = 0; y < 192; ++y)
    for (int x = 0; x < 192; ++x) {
      const unsigned char c = (x + y) % 2 ? 255 : 0;
      img.rgb.insert(img.rgb.end(), {c, c, c});
    }
  d.images.push_back(img);
  TextureDesc tex;
  tex.kind = TextureDesc::Kind::uv_image;
  tex.image = 0;
  d.textures.push_back(tex);
  Material m;
  m.colour = {1, 1, 1};
  m.texture = 0;
  d.materials.push_back(m);
  TriangleMeshDesc quad;
  quad.vertices = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  quad.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  quad.triangles = {{0, 1, 2}, {0, 2, 3}};
  ObjectDesc obj;
  obj.shape = quad;
  obj.material = 0;
  d.objects.push_back(obj);
  d.lights.push_back(Light{{0, 0, 5}});
  // 64 pixels over the quad's 2 units.
  const double distance = 5, fov = 2 * std::atan(1 / distance);
  PinholeDesc pd;
  pd.from = {0, 0, distance};
  pd.at = {0, 0, 0};
  pd.fov_deg = fov * 180 / 3.14159265358979;
  pd.width = pd.height = 64;
  const PinholeCamera cam(pd);
  RenderOptions opt;
  opt.aovs.albedo = true;
  auto spread_of_albedo = [&](double footprint_spread, double& mean) {
    RenderScene scene(d);
    RenderSettings settings = file_settings(scene);
    settings.footprint = {0, footprint_spread};
    RenderStats stats;
    const ImageBuffer a = render_view(RenderContext(scene, settings), cam, opt, stats).albedo;
    double sum = 0, sum2 = 0;
    int n = 0;
    for (int j = 8; j < 56; ++j)
      for (int i = 8; i < 56; ++i) {
        const double v = a.at(i, j)[0];
        sum += v, sum2 += v * v, ++n;
      }
    mean = sum / n;
    return std::sqrt(std::max(0.0, sum2 / n - mean * mean));
  };
  double sharp_mean, blurred_mean;
  const double sharp = spread_of_albedo(0, sharp_mean);
  const double blurred = spread_of_albedo(2 * std::tan(fov / 2) / 64, blurred_mean);
  EXPECT_GT(sharp, 0.3) << "the finest level: single texels, 0 or 1";
  EXPECT_LT(blurred, 0.05) << "levels 1 and 2: 2x2 and 4x4 texels averaged";
  EXPECT_NEAR(blurred_mean, 0.5, 0.03);
}

// A floor under a light, and between them (out of the view) an alpha-masked
// square: with alpha 0 it is cut away for eye and shadow rays alike, so the
// floor's pixels are those of the scene without it, bit for bit; with alpha
// 1 it shadows the floor.
TEST(MeshTextures, AlphaMaskCutsTheSurfaceForShadowRaysToo) {
  auto scene_with = [](std::optional<double> mask_alpha) {
    SceneDesc d;
    d.source = "mask";
    d.materials.push_back(Material{});
    TriangleMeshDesc floor;
    floor.vertices = {{-2, -2, 0}, {2, -2, 0}, {2, 2, 0}, {-2, 2, 0}};
    floor.triangles = {{0, 1, 2}, {0, 2, 3}};
    ObjectDesc f;
    f.shape = floor;
    f.material = 0;
    d.objects.push_back(f);
    if (mask_alpha) {
      Material m;
      m.alpha_mask = true;
      m.alpha = *mask_alpha;
      d.materials.push_back(m);
      TriangleMeshDesc leaf = floor;
      for (Vec3& v : leaf.vertices) v.z = 3;
      ObjectDesc o;
      o.shape = leaf;
      o.material = 1;
      d.objects.push_back(o);
    }
    d.lights.push_back(Light{{0, 0, 6}});
    return d;
  };
  PinholeDesc pd;
  pd.from = {0, -4, 0.6};
  pd.at = {0, 0, 0};
  pd.up = {0, 0, 1};
  pd.fov_deg = 30;
  pd.width = pd.height = 32;
  const PinholeCamera cam(pd);
  auto render = [&](const SceneDesc& d) {
    RenderScene scene(d);
    RenderStats stats;
    return render_view(scene, cam, RenderOptions{}, stats).colour;
  };
  const ImageBuffer bare = render(scene_with(std::nullopt));
  const ImageBuffer cut = render(scene_with(0.0));
  const ImageBuffer solid = render(scene_with(1.0));
  EXPECT_EQ(cut.data, bare.data);
  EXPECT_NE(solid.data, bare.data) << "the square, not cut, shadows the floor";
  double lit = 0, shadowed = 0;
  for (size_t k = 0; k < bare.data.size(); ++k) lit += bare.data[k], shadowed += solid.data[k];
  EXPECT_LT(shadowed, 0.75 * lit);  // ambient light stays: half or so
}

// MTL's map_d cuts the surface where the map is dark (a grey image: its
// first channel is the coverage): a grey quad whose map is white on the
// left and black on the right, before a red wall, shows grey on the left
// and the wall on the right.
TEST(MeshTextures, MtlMapDCutsTheSurfaceWhereTheMapIsDark) {
  test::TempDir dir;
  test::write_image_of(dir.file("mask.png"), 8, 8, [](int x, int, int) { return x < 4 ? 1.0f : 0.0f; });
  test::write_text(dir.file("m.mtl"), "newmtl leaf\nKd 0.8 0.8 0.8\nmap_d mask.png\nnewmtl wall\nKd 1 0 0\n");
  test::write_text(dir.file("m.obj"),
                   "mtllib m.mtl\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                   "usemtl leaf\nf 1/1 2/2 3/3 4/4\nv -3 -3 0\nv 3 -3 0\nv 3 3 0\nv -3 3 0\nusemtl wall\nf 5 6 7 8\n");
  const SceneDesc scene_desc = read_mesh_file(dir.file("m.obj"));
  PinholeDesc pd;
  pd.from = {0, 0, 6};
  pd.at = {0, 0, 0};
  pd.up = {0, 1, 0};
  pd.fov_deg = 30;
  pd.width = pd.height = 32;
  RenderScene scene(scene_desc);
  RenderStats stats;
  const ImageBuffer img = render_view(scene, PinholeCamera(pd), RenderOptions{}, stats).colour;
  const float* left = img.at(11, 16);   // on the quad's left half
  const float* right = img.at(20, 16);  // on its right half: cut, the wall behind
  EXPECT_GT(left[1], 0.1f) << "grey leaf";
  EXPECT_NEAR(left[0], left[1], 1e-6);
  EXPECT_GT(right[0], 0.1f) << "red wall";
  EXPECT_EQ(right[1], 0.0f);
}

// Every texture index of a file is rebased when several files make one
// scene: the mapped plane (its metallic-roughness and normal maps) after a
// textured box far away renders as it does alone.
TEST(MeshTextures, TheSecondFilesMapsAreItsOwn) {
  const std::string data = std::string(HOLORAY_SOURCE_DIR) + "/tests/data/blender/";
  SceneDesc box = read_mesh_file(data + "textured_box.gltf");
  for (ObjectDesc& o : box.objects)
    if (auto* m = std::get_if<TriangleMeshDesc>(&o.shape))
      for (Vec3& v : m->vertices) v.x += 100;
  const SceneDesc plane = read_mesh_file(data + "mapped_plane.gltf");
  ASSERT_TRUE(plane.viewpoint);
  const PinholeCamera cam(view_of(*plane.viewpoint, 64, 64));
  RenderStats stats;
  const RenderScene alone(plane);
  const RenderScene both(std::vector<ScenePart>{{&box, false}, {&plane, false}});
  const ImageBuffer a = render_view(alone, cam, RenderOptions{}, stats).colour;
  const ImageBuffer b = render_view(both, cam, RenderOptions{}, stats).colour;
  EXPECT_GE(compare_images(a, b).psnr_all(), 60);
}

// Emission is added to the shaded colour as it stands: a black, unlit
// quad (its light behind it) shows exactly its emissive factor, and with an
// emissive texture that times the decoded texel. (Debian's assimp 5.2 does
// not read KHR_materials_emissive_strength.)
TEST(MeshTextures, EmissionAddsTheFactorTimesTheTexture) {
  test::TempDir dir;
  // A quad facing +z, seen from +z; the light below it. 2x1 texture: left
  // texel sRGB 188 (0.5029 linear), right texel 255 (1).
  auto gltf = [&](bool textured) {
    return fmt::format(R"({{"asset": {{"version": "2.0"}}, "scene": 0, "scenes": [{{"nodes": [0, 1, 2]}}],
 "extensionsUsed": ["KHR_lights_punctual"],
 "extensions": {{"KHR_lights_punctual": {{"lights": [{{"type": "point", "intensity": 1}}]}}}},
 "nodes": [{{"mesh": 0}}, {{"camera": 0, "translation": [0, 0, 4]}}, {{"extensions": {{"KHR_lights_punctual": {{"light": 0}}}}, "translation": [0, 0, -3]}}],
 "cameras": [{{"type": "perspective", "perspective": {{"yfov": 0.3, "aspectRatio": 1.0, "znear": 0.1}}}}],
 "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0, "TEXCOORD_0": 1}}, "indices": 2, "material": 0}}]}}],
 "materials": [{{"name": "glow", "emissiveFactor": [1, 0.5, 0.25], {}
   "pbrMetallicRoughness": {{"baseColorFactor": [0, 0, 0, 1], "metallicFactor": 0}}}}],
 "textures": [{{"source": 0, "sampler": 0}}], "samplers": [{{"magFilter": 9728}}], "images": [{{"uri": "e.ppm"}}],
 "buffers": [{{"byteLength": 92, "uri": "data:application/octet-stream;base64,{}"}}],
 "bufferViews": [{{"buffer": 0, "byteLength": 48}}, {{"buffer": 0, "byteOffset": 48, "byteLength": 32}}, {{"buffer": 0, "byteOffset": 80, "byteLength": 12}}],
 "accessors": [{{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-1, -1, 0], "max": [1, 1, 0]}},
   {{"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2"}},
   {{"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}}]}})",
                       textured ? R"("emissiveTexture": {"index": 0},)" : "", kQuadBuffer);
  };
  test::write_text(dir.file("e.ppm"), std::string("P6\n2 1\n255\n") + "\xbc\xbc\xbc\xff\xff\xff");
  for (const bool textured : {false, true}) {
    SCOPED_TRACE(textured ? "textured" : "factor");
    test::write_text(dir.file("q.gltf"), gltf(textured));
    const auto r = test::run_cli(fmt::format("render {} --camera pinhole --resolution 16x16 -q -o {}", dir.file("q.gltf"),
                                             dir.file("o.exr")));
    ASSERT_EQ(r.status, 0) << r.output;
    const ImageBuffer img = read_image(dir.file("o.exr"));
    const float* left = img.at(4, 8);
    const float* right = img.at(11, 8);
    const double l = textured ? decode_table(true)[188] : 1.0;
    EXPECT_NEAR(left[0], 1 * l, 1e-5);
    EXPECT_NEAR(left[1], 0.5 * l, 1e-5);
    EXPECT_NEAR(left[2], 0.25 * l, 1e-5);
    EXPECT_NEAR(right[0], 1, 1e-5);
    EXPECT_NEAR(right[2], 0.25, 1e-5);
  }
}

// A shot's frames read mesh textures at the MIP levels a still does: the
// first frame of `animate` (EIA, and a pinhole preview) is `render` of the
// same camera, bit for bit (the repeated texture is minified, so the level
// matters: without a footprint the frame differs).
TEST(MeshTextures, AnimatedFramesReadTexturesAsRenderDoes) {
  const std::string scene = std::string(HOLORAY_SOURCE_DIR) + "/tests/data/blender/wrapped_box.gltf";
  test::TempDir dir;
  test::write_text(dir.file("shot.toml"),
                   "frames = 1\n[array]\nlenses = 32\npixels_per_lens = 8\n[[object]]\nscene = \"" + scene + "\"\n");
  struct Case {
    const char* animate;
    const char* render;
  };
  for (const Case c : {Case{"", "--lenses 32x32 --pixels-per-lens 8"},
                       Case{"--camera pinhole --resolution 64x64", "--camera pinhole --resolution 64x64"}}) {
    SCOPED_TRACE(c.render);
    const std::string frames = dir.file(c.animate[0] ? "views" : "eias");
    const auto anim = test::run_cli(fmt::format("animate {} {} --format exr -o {} -q", dir.file("shot.toml"), c.animate, frames));
    ASSERT_EQ(anim.status, 0) << anim.output;
    const auto still = test::run_cli(fmt::format("render {} {} -o {} -q", scene, c.render, dir.file("still.exr")));
    ASSERT_EQ(still.status, 0) << still.output;
    EXPECT_EQ(read_image(frames + "/frame_0000.exr").data, read_image(dir.file("still.exr")).data);
  }
}

}  // namespace
}  // namespace holoray
