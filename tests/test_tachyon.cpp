// Tachyon's scene language (scene/tachyon_reader.hpp) and Tachyon shading:
// what each construct becomes, exact refusals, the left-handed screen, and
// agreement with tachyon-nox itself on a scene using every construct read.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "camera/pinhole.hpp"
#include "image/image_io.hpp"
#include "image/metrics.hpp"
#include "render/render_scene.hpp"
#include "render/textures.hpp"
#include "render/view_renderer.hpp"
#include "scene/parse_error.hpp"
#include "scene/tachyon_reader.hpp"
#include "test_util.hpp"

namespace holoray {
namespace {

const char* kHeader =
    "begin_scene resolution 64 48\n"
    "camera zoom 2.0 aspectratio 1.0 antialiasing 0 raydepth 7\n"
    "  center 0 0 -5 viewdir 0 0 2 updir 0 1 0 end_camera\n";

std::string scene_text(const std::string& body) { return std::string(kHeader) + body + "end_scene\n"; }

// PSNR of holoray's pinhole view of tests/data/tachyon/`scene` (with
// `options`) against tachyon-nox's picture of it (-aasamples 0), both run
// from that folder. Fails the test when either program fails.
double psnr_against_tachyon(const std::string& scene, const std::string& options) {
  test::TempDir dir;
  const std::string data = test::source_dir() + "/tests/data/tachyon/";
  const auto ref = test::run_shell("cd " + data + " && tachyon-nox " + scene + " -aasamples 0 -format PNG -o " +
                                   dir.file("tachyon.png"));
  EXPECT_EQ(ref.status, 0) << ref.output;
  const auto ours = test::run_cli("render " + data + scene + " --camera pinhole " + options + " -o " +
                                  dir.file("holoray.png") + " -q");
  EXPECT_EQ(ours.status, 0) << ours.output;
  if (ref.status != 0 || ours.status != 0) return 0;
  return compare_images(read_image(dir.file("holoray.png")), read_image(dir.file("tachyon.png"))).psnr_all();
}

std::string error_of(const std::string& text) {
  try {
    parse_tachyon(text, "t.dat");
  } catch (const ParseError& e) {
    return e.headline();
  }
  return "no error";
}

TEST(TachyonReader, CameraBecomesAMirroredViewpointWithTachyonsFieldOfView) {
  const SceneDesc d = parse_tachyon(scene_text("sphere center 0 0 3 rad 1 texture ambient 0.1 diffuse 0.9 "
                                               "specular 0 opacity 1 color 1 1 1 texfunc 0\n"),
                                    "t.dat");
  ASSERT_TRUE(d.viewpoint);
  // Image plane 1/zoom tall at distance 1: full angle 2 atan(0.5 / zoom).
  EXPECT_NEAR(d.viewpoint->angle_deg, 2 * std::atan(0.25) * 180 / std::numbers::pi, 1e-12);
  EXPECT_TRUE(d.viewpoint->mirrored);
  EXPECT_EQ(d.viewpoint->xres, 64);
  EXPECT_EQ(d.viewpoint->yres, 48);
  EXPECT_EQ(d.max_depth, 7);
  // The look-at point sits at the depth of the objects' centre, along the unit view.
  EXPECT_NEAR(d.viewpoint->at.z, 3, 1e-12);
  EXPECT_EQ(d.shading, ShadingModel::tachyon);
}

TEST(TachyonReader, KeywordsAreCaseInsensitiveTextureNamesAreNot) {
  const SceneDesc d = parse_tachyon(scene_text("TexDef Shiny AMBIENT 0.2 Diffuse 0.5 specular 0.3 OPACITY 0.75\n"
                                               "  Phong Metal 0.4 phong_size 20 COLOR 1 0.5 0.25 TexFunc 0\n"
                                               "TEXALIAS other Shiny\n"
                                               "SPHERE CENTER 0 0 3 RAD 1 other\n"
                                               "sphere center 1 0 3 rad 1 shiny\n"),
                                    "t.dat");
  ASSERT_EQ(d.objects.size(), 2u);
  const Material& m = d.materials[static_cast<size_t>(d.objects[0].material)];
  EXPECT_EQ(m.model, ShadingModel::tachyon);
  EXPECT_DOUBLE_EQ(m.ambient, 0.2);
  EXPECT_DOUBLE_EQ(m.kd, 0.5);
  EXPECT_DOUBLE_EQ(m.ks, 0.3);
  EXPECT_DOUBLE_EQ(m.transmittance, 0.25);
  EXPECT_DOUBLE_EQ(m.phong, 0.4);
  EXPECT_DOUBLE_EQ(m.shine, 20);
  EXPECT_TRUE(m.phong_metal);
  EXPECT_EQ(m.colour, (Vec3{1, 0.5, 0.25}));
  // 'shiny' is not 'Shiny': Tachyon's default texture, with a warning.
  const Material& fallback = d.materials[static_cast<size_t>(d.objects[1].material)];
  EXPECT_DOUBLE_EQ(fallback.kd, 0.9);
  ASSERT_EQ(d.warnings.size(), 1u);
  EXPECT_EQ(d.warnings[0], "t.dat:8:27: warning: undefined texture 'shiny': Tachyon's default (white, ambient 0.1, "
                           "diffuse 0.9) used");
}

// Tachyon's texture hash keeps a name's first entry; VMD-style exports that
// reuse names rely on it (lattice.dat: 17.8 dB before, 43.8 after).
TEST(TachyonReader, ATextureNameDefinedAgainKeepsItsFirstDefinition) {
  const SceneDesc d = parse_tachyon(scene_text("texdef m ambient 0.1 diffuse 0.9 specular 0 opacity 1 color 1 0 0 texfunc 0\n"
                                               "texdef m ambient 0.1 diffuse 0.9 specular 0 opacity 1 color 0 0 1 texfunc 0\n"
                                               "sphere center 0 0 3 rad 1 m\n"),
                                    "t.dat");
  ASSERT_EQ(d.objects.size(), 1u);
  EXPECT_EQ(d.materials[static_cast<size_t>(d.objects[0].material)].colour, (Vec3{1, 0, 0}));
  ASSERT_EQ(d.warnings.size(), 1u);
  EXPECT_EQ(d.warnings[0], "t.dat:5:8: warning: texture 'm' defined again: Tachyon keeps the first definition");
}

TEST(TachyonReader, CompositeObjectsBecomeTheirPrimitives) {
  const std::string tex = " texture ambient 0.1 diffuse 0.9 specular 0 opacity 1 color 1 1 1 texfunc 0\n";
  const SceneDesc d = parse_tachyon(
      scene_text("box min 0 0 0 max 1 2 3" + tex + "ring center 0 0 0 normal 0 1 0 inner 0.5 outer 1" + tex +
                 "ring center 0 0 0 normal 0 1 0 inner 0 outer 1" + tex +
                 "polycylinder points 3 0 0 0 0 1 0 1 1 0 rad 0.1" + tex + "plane center 0 -1 0 normal 0 2 0" + tex),
      "t.dat");
  ASSERT_EQ(d.objects.size(), 3u + 5u + 1u);
  const auto& box = std::get<TriangleMeshDesc>(d.objects[0].shape);
  EXPECT_EQ(box.triangles.size(), 12u);
  // Every box triangle faces out: its normal points away from the box centre.
  for (const auto& t : box.triangles) {
    const Vec3 n = cross(box.vertices[t[1]] - box.vertices[t[0]], box.vertices[t[2]] - box.vertices[t[0]]);
    EXPECT_GT(dot(n, box.vertices[t[0]] - Vec3{0.5, 1, 1.5}), 0);
  }
  const auto& annulus = std::get<TriangleMeshDesc>(d.objects[1].shape);
  const auto& disc = std::get<TriangleMeshDesc>(d.objects[2].shape);
  EXPECT_EQ(annulus.triangles.size(), 2 * disc.triangles.size());
  // Ring triangles face along the ring's normal, vertices at the two radii.
  for (const auto& t : annulus.triangles)
    EXPECT_GT(cross(annulus.vertices[t[1]] - annulus.vertices[t[0]], annulus.vertices[t[2]] - annulus.vertices[t[0]]).y,
              0);
  for (const Vec3& v : annulus.vertices) {
    const double r = length(v);
    EXPECT_TRUE(std::fabs(r - 0.5) < 1e-12 || std::fabs(r - 1) < 1e-12) << r;
  }
  // Polycylinder: a sphere per point, an open cylinder back to the previous one.
  EXPECT_TRUE(std::holds_alternative<SphereDesc>(d.objects[3].shape));
  EXPECT_TRUE(std::holds_alternative<SphereDesc>(d.objects[4].shape));
  EXPECT_EQ(std::get<ConeDesc>(d.objects[5].shape).apex, (Vec3{0, 1, 0}));
  EXPECT_TRUE(std::holds_alternative<SphereDesc>(d.objects[6].shape));
  EXPECT_EQ(std::get<ConeDesc>(d.objects[7].shape).base, (Vec3{0, 1, 0}));
  EXPECT_EQ(std::get<PlaneDesc>(d.objects[8].shape).normal, (Vec3{0, 1, 0}));
}

TEST(TachyonReader, UnsupportedConstructsAreRefusedWhereTheyAre) {
  EXPECT_EQ(error_of(scene_text("scalarvol min 0 0 0 max 1 1 1 dim 2 2 2 file v.dat\n")),
            "t.dat:4:1: error: 'scalarvol' (scalar volumes) is not supported yet (docs/tachyon-notes.md §6)");
  EXPECT_EQ(error_of(scene_text("texdef m ambient 0 diffuse 1 specular 0 opacity 1 color 1 1 1 texfunc 3\n")),
            "t.dat:4:71: error: texfunc 3 (marble) is not supported yet (0, 1, 4 and 6 to 10 are)");
  EXPECT_EQ(error_of("begin_scene resolution 8 8 camera projection fisheye zoom 1 aspectratio 1 antialiasing 0 "
                     "raydepth 3 center 0 0 0 viewdir 0 0 1 updir 0 1 0 end_camera end_scene"),
            "t.dat:1:46: error: the 'fisheye' projection is not supported yet (perspective only)");
  EXPECT_EQ(error_of(std::string(kHeader) + "sphere center 0 0 0 rad 1\n"),
            "t.dat:4:26: error: expected a texture name or 'TEXTURE', found end of file");
  EXPECT_EQ(error_of(scene_text("cone\n")),
            "t.dat:4:1: error: expected a Tachyon object or declaration (camera, light, texdef, sphere, tri, plane, "
            "...), found 'cone'");
  EXPECT_EQ(error_of(scene_text("texdef m ambient 0 diffuse 1 specular 0 opacity 1 color 1 1 1 texfunc 9 "
                                "no_such_image.ppm center 0 0 0 rotate 0 0 0 scale 1 1 1 uaxis 1 0 0 vaxis 0 1 0\n"))
                .substr(0, 79),
            "t.dat:4:73: error: cannot read the image map 'no_such_image.ppm': no such file");
  EXPECT_EQ(error_of("resolution 8 8"), "t.dat:1:1: error: expected 'BEGIN_SCENE', found 'resolution'");
}

// IMAGEDEF (tachyon-notes §3): texels x fastest, then y, then z; a 3-digit
// texel has one digit per channel (f = 255), a 6-digit one two. A volume map
// (texfunc 10) reads its w axis; a "::" name nobody defined takes Tachyon's
// stand-in with a warning, a file that cannot be read stays an error (above).
TEST(TachyonReader, InlineImagesDecodeTheirTexelsInOrder) {
  const SceneDesc d = parse_tachyon(
      scene_text("imagedef ::v format rgb24 resolution 2 1 2 encoding hex 0f8 102030 fff 000\n"
                 "texdef m ambient 0 diffuse 1 specular 0 opacity 1 color 1 1 1 texfunc 10 ::v center 1 2 3 "
                 "rotate 0 0 0 scale 1 1 1 uaxis 1 0 0 vaxis 0 1 0 waxis 0 0 2\n"
                 "texdef g ambient 0 diffuse 1 specular 0 opacity 1 color 1 1 1 texfunc 9 ::gone center 0 0 0 "
                 "rotate 0 0 0 scale 1 1 1 uaxis 1 0 0 vaxis 0 1 0\n"
                 "sphere center 0 0 3 rad 1 m\nsphere center 0 0 6 rad 1 g\n"),
      "t.dat");
  ASSERT_EQ(d.images.size(), 2u);
  const ImageMap& v = d.images[0];
  EXPECT_EQ(v.path, "::v");
  EXPECT_EQ(v.width, 2);
  EXPECT_EQ(v.height, 1);
  EXPECT_EQ(v.depth, 2);
  EXPECT_EQ(v.rgb, (std::vector<unsigned char>{0x00, 0xff, 0x88, 0x10, 0x20, 0x30, 0xff, 0xff, 0xff, 0, 0, 0}));
  ASSERT_EQ(d.textures.size(), 2u);
  EXPECT_EQ(d.textures[0].kind, TextureDesc::Kind::volume_image);
  EXPECT_EQ(d.textures[0].waxis, (Vec3{0, 0, 2}));
  EXPECT_EQ(d.textures[0].image, 0);
  const ImageMap& stand_in = d.images[1];
  EXPECT_EQ(stand_in.width, 4);
  EXPECT_EQ(stand_in.height, 4);
  EXPECT_EQ(stand_in.rgb, std::vector<unsigned char>(4 * 4 * 3, 255));
  ASSERT_EQ(d.warnings.size(), 1u);
  EXPECT_EQ(d.warnings[0],
            "t.dat:6:73: warning: no inline image '::gone' (IMAGEDEF) was defined: Tachyon's stand-in (4x4 white) used");
}

TEST(TachyonReader, MalformedInlineImagesAreRefusedWhereTheyAre) {
  EXPECT_EQ(error_of(scene_text("imagedef ::p format rgb24 resolution 2 1 1 encoding hex fff 0g0\n")),
            "t.dat:4:61: error: expected texel 2 of 2 of image '::p': 3 or 6 hex digits, found '0g0'");
  EXPECT_EQ(error_of(scene_text("imagedef ::p format rgb24 resolution 2 1 1 encoding hex ffff 000\n")),
            "t.dat:4:57: error: expected texel 1 of 2 of image '::p': 3 or 6 hex digits, found 'ffff'");
  EXPECT_EQ(error_of(scene_text("imagedef ::p format rgb48 resolution 1 1 1 encoding hex fff\n")),
            "t.dat:4:21: error: expected 'RGB24' (the only inline image format), found 'rgb48'");
  EXPECT_EQ(error_of(scene_text("imagedef ::p format rgb24 resolution 100000 100000 100000 encoding hex\n")),
            "t.dat:4:38: error: expected an image of at most 268435456 texels, found 100000x100000x100000");
  EXPECT_EQ(error_of(scene_text("imagedef ::p format rgb24 resolution 2 0 1 encoding hex\n")),
            "t.dat:4:38: error: expected an image resolution of 1 to 268435456 texels per axis, found 0");
}

// Tachyon's VolMIPMap on a volume: one level (no decimation across slices),
// the texels themselves at the lattice points and the mean of two slices
// halfway between; a flat image is its own slice 0 whatever w is.
TEST(TachyonTextures, VolumeImagesInterpolateTrilinearlyBetweenSlices) {
  ImageMap v;
  v.width = 2, v.height = 2, v.depth = 3;
  for (int i = 0; i < 12; ++i) v.rgb.insert(v.rgb.end(), {static_cast<unsigned char>(20 * i), 0, 255});
  const MipMap vol(v);
  EXPECT_EQ(vol.levels(), 1);
  auto texel = [&](int x, int y, int z) { return v.rgb[size_t(((z * 2 + y) * 2 + x) * 3)] / 255.0; };
  for (int z = 0; z < 3; ++z)
    for (int y = 0; y < 2; ++y)
      for (int x = 0; x < 2; ++x) EXPECT_DOUBLE_EQ(vol.sample_volume(x, y, z / 2.0, 0.7).x, texel(x, y, z));
  EXPECT_NEAR(vol.sample_volume(1, 0, 0.25, 0).x, (texel(1, 0, 0) + texel(1, 0, 1)) / 2, 1e-12);
  EXPECT_NEAR(vol.sample_volume(0.5, 0.5, 0.75, 0).x,
              (texel(0, 0, 1) + texel(1, 0, 1) + texel(0, 1, 1) + texel(1, 1, 1) + texel(0, 0, 2) + texel(1, 0, 2) +
               texel(0, 1, 2) + texel(1, 1, 2)) / 8,
              1e-12);
  EXPECT_EQ(vol.sample_volume(0.5, 0.5, 1.5, 0), (Vec3{}));  // outside [0,1]^3: black, as Tachyon
  ImageMap flat;
  flat.width = 4, flat.height = 4;
  for (int i = 0; i < 16; ++i) flat.rgb.insert(flat.rgb.end(), {static_cast<unsigned char>(15 * i), 7, 9});
  const MipMap f(flat);
  EXPECT_EQ(f.levels(), 3);
  for (double d : {0.0, 0.3, 0.9}) EXPECT_EQ(f.sample_volume(0.3, 0.6, 0.8, d), f.sample(0.3, 0.6, d));
}

TEST(TachyonReader, IncludeReadsBesideTheIncludingFileAndStopsRecursion) {
  test::TempDir dir;
  test::write_text(dir.file("lights.inc"), "light center 0 5 0 rad 0.1 color 1 1 1\n");
  test::write_text(dir.file("self.inc"), "include self.inc\n");
  const SceneDesc d = parse_tachyon(scene_text("include lights.inc\n"), dir.file("main.dat"));
  ASSERT_EQ(d.lights.size(), 1u);
  EXPECT_EQ(d.lights[0].position, (Vec3{0, 5, 0}));
  try {
    parse_tachyon(scene_text("include self.inc\n"), dir.file("main.dat"));
    FAIL() << "a file including itself was accepted";
  } catch (const ParseError& e) {
    EXPECT_NE(e.message().find("nested at most 16 deep"), std::string::npos) << e.what();
  }
}

TEST(TachyonReader, PolygonFilesAreScaledRotatedMovedAndRewound) {
  test::TempDir dir;
  test::write_text(dir.file("one.tpoly"), "3\n1 0 0\n0 2 0\n0 0 3\n3\n0 0 0 1 0 0 0 1 0\n4\n");
  const std::string tex = " texture ambient 0.1 diffuse 0.9 specular 0 opacity 1 color 1 1 1 texfunc 0\n";
  const SceneDesc d = parse_tachyon(
      scene_text("tpolyfile scale 2 2 2 rot 0 0 90 center 10 0 0 file one.tpoly" + tex), dir.file("main.dat"));
  // Two triangles: the record of 4 vertices ends the file, as in Tachyon.
  ASSERT_EQ(d.objects.size(), 2u);
  const auto& p = std::get<PolygonDesc>(d.objects[0].shape).vertices;
  // Scaled by 2, turned 90 degrees about z (x -> y, y -> -x), moved by
  // (10, 0, 0), and written v1 v0 v2.
  EXPECT_NEAR(p[0].x, 10 - 4, 1e-6);
  EXPECT_NEAR(p[0].y, 0, 1e-6);
  EXPECT_NEAR(p[1].x, 10, 1e-6);
  EXPECT_NEAR(p[1].y, 2, 1e-6);
  EXPECT_NEAR(p[2].z, 6, 1e-6);
}

TEST(TachyonReader, VertexArraysBecomeOneMeshPerStripOrTriangleList) {
  const SceneDesc d = parse_tachyon(
      scene_text("vertexarray numverts 4 coords 0 0 3 1 0 3 0 1 3 1 1 3 normals 0 0 -1 0 0 -1 0 0 -1 0 0 -1\n"
                 "colors 1 0 0 0 1 0 0 0 1 1 1 1\n"
                 "tristrip 4 0 1 2 3\n"
                 "texture ambient 0.2 diffuse 0.8 specular 0 opacity 1 color 1 1 1 texfunc 0\n"
                 "trimesh 1 3 2 1\n"
                 "end_vertexarray\n"),
      "t.dat");
  ASSERT_EQ(d.objects.size(), 2u);
  const auto& strip = std::get<TriangleMeshDesc>(d.objects[0].shape);
  // Every other triangle of a strip turns round, so all face the same way.
  ASSERT_EQ(strip.triangles.size(), 2u);
  EXPECT_EQ(strip.triangles[0], (std::array<uint32_t, 3>{0, 1, 2}));
  EXPECT_EQ(strip.triangles[1], (std::array<uint32_t, 3>{2, 1, 3}));
  EXPECT_EQ(strip.colours.size(), 4u);
  // Before any TEXTURE, Tachyon's default texture; after it, that texture.
  EXPECT_DOUBLE_EQ(d.materials[static_cast<size_t>(d.objects[0].material)].kd, 0.9);
  EXPECT_DOUBLE_EQ(d.materials[static_cast<size_t>(d.objects[1].material)].kd, 0.8);
  EXPECT_EQ(error_of(scene_text("vertexarray numverts 1 coords 0 0 0 normals 0 0 1 trimesh 1 0 0 1 end_vertexarray\n")),
            "t.dat:4:65: error: expected a vertex index below 1, found 1");
}

TEST(TachyonReader, FogIsReadAndOffClearsIt) {
  const SceneDesc on = parse_tachyon(scene_text("fog exp2 start 1 end 9 density 0.5 color 1 0.5 0.25\n"), "t.dat");
  ASSERT_TRUE(on.fog);
  EXPECT_EQ(on.fog->mode, FogDesc::Mode::exp2);
  EXPECT_DOUBLE_EQ(on.fog->density, 0.5);
  EXPECT_EQ(on.fog->colour, (Vec3{1, 0.5, 0.25}));
  const SceneDesc off = parse_tachyon(
      scene_text("fog linear start 1 end 9 density 1 color 1 1 1\nfog off start 0 end 0 density 0 color 0 0 0\n"),
      "t.dat");
  EXPECT_FALSE(off.fog);
  EXPECT_EQ(error_of(scene_text("fog linear start 5 end 2 density 1 color 1 1 1\n")),
            "t.dat:4:24: error: expected a fog end past its start (5), found 2");
}

// Tachyon's screen is left-handed (right = up x view): looking down +z with
// y up, +x is on the right of the picture, where NFF's would put it on the left.
TEST(TachyonShading, ScreenIsLeftHandedAndAmbientIsTextureTimesAmbient) {
  const SceneDesc d = parse_tachyon(scene_text("sphere center 0.4 0 3 rad 0.3 texture ambient 0.5 diffuse 0 "
                                               "specular 0 opacity 1 color 0.8 0.4 0.2 texfunc 0\n"),
                                    "t.dat");
  RenderScene scene(d);
  const Viewpoint& vp = *d.viewpoint;
  const PinholeCamera cam(PinholeDesc{vp.from, vp.at, vp.up, vp.angle_deg, 64, 48, vp.mirrored});
  RenderOptions opt;
  opt.threads = 1;
  RenderStats stats;
  const FrameBuffers f = render_view(scene, cam, opt, stats);
  int right = 0, left = 0;
  for (int j = 0; j < 48; ++j)
    for (int i = 0; i < 64; ++i) {
      const float* p = &f.colour.data[(size_t(j) * 64 + i) * 3];
      if (p[0] == 0 && p[1] == 0 && p[2] == 0) continue;
      (i >= 32 ? right : left) += 1;
      // No light: colour = ambient * texture colour, exactly.
      EXPECT_FLOAT_EQ(p[0], 0.4f);
      EXPECT_FLOAT_EQ(p[1], 0.2f);
      EXPECT_FLOAT_EQ(p[2], 0.1f);
    }
  EXPECT_GT(right, 20);
  EXPECT_EQ(left, 0);
}

// Tachyon lanes of a packet trace their shadow rays as packets; single-ray
// styles trace them one by one: the same image, bit for bit (the scene has
// no ray exactly on a shared triangle edge).
TEST(TachyonShading, PacketAndSingleRayStylesGiveTheSameEia) {
  const std::string data = test::source_dir() + "/tests/data/tachyon/shapes.dat";
  test::TempDir dir;
  for (const char* style : {"packet", "horizontal"}) {
    const auto r = test::run_cli(fmt::format("render {} --lenses 24x24 --style {} -o {} -q", data, style,
                                             dir.file(std::string(style) + ".exr")));
    ASSERT_EQ(r.status, 0) << r.output;
  }
  const ImageBuffer a = read_image(dir.file("packet.exr")), b = read_image(dir.file("horizontal.exr"));
  EXPECT_EQ(a.data, b.data);
}

// The independent check: tachyon-nox renders tests/data/tachyon/shapes.dat
// (every construct holoray reads: attenuated, spot and directional lights,
// a light's visible sphere, image map, checker, plastic and metal
// highlights, mirror, a transparent sphere and its filtered shadow, box,
// ring, plane, fcylinder, polycylinder, tri, stri) and holoray's pinhole
// view, sampled where Tachyon samples, agrees. Measured 36.8 dB; the rest is the
// MIP level of reflected texels (holoray measures the optic distance from
// the last bounce) and float-rounded checker edges.
TEST(TachyonShading, AgreesWithTachyon) {
  if (test::run_shell("command -v tachyon-nox").status != 0)
    GTEST_SKIP() << "tachyon-nox is not installed (scripts/setup.sh installs it)";
  const double at_tachyons_samples = psnr_against_tachyon("shapes.dat", "--sample-at tachyon");
  EXPECT_GT(at_tachyons_samples, 35);
  // Sampling at pixel centres shifts the picture by half a pixel: measurably worse.
  EXPECT_LT(psnr_against_tachyon("shapes.dat", "--sample-at centre"), at_tachyons_samples - 3);
}

// The rest of what holoray reads (fog, a polygon file, a coloured vertex
// array and a vertex-coloured triangle, the cylindrical checker,
// cylindrical and spherical image maps) against tachyon-nox: measured 48.1 dB.
TEST(TachyonShading, FogPolygonFilesAndCurvedImageMapsAgreeWithTachyon) {
  if (test::run_shell("command -v tachyon-nox").status != 0)
    GTEST_SKIP() << "tachyon-nox is not installed (scripts/setup.sh installs it)";
  EXPECT_GT(psnr_against_tachyon("extras.dat", "--sample-at tachyon"), 42);
}

// Inline images (tests/data/tachyon/inline_images.dat: a flat one on a planar
// map, a volume whose w axis crosses its slices, 3- and 6-digit texels, an
// undefined name's stand-in) against tachyon-nox: measured 51.0 dB (25.0 at
// pixel centres).
TEST(TachyonShading, InlineAndVolumeImagesAgreeWithTachyon) {
  if (test::run_shell("command -v tachyon-nox").status != 0)
    GTEST_SKIP() << "tachyon-nox is not installed (scripts/setup.sh installs it)";
  EXPECT_GT(psnr_against_tachyon("inline_images.dat", "--sample-at tachyon"), 48);
}

}  // namespace
}  // namespace holoray
