// NFF reader: every entity, the format's quirks (nff-notes §1-§9), and the
// exact message for each class of malformed input.
#include <gtest/gtest.h>

#include <system_error>

#include "scene/nff_reader.hpp"
#include "scene/parse_error.hpp"
#include "test_util.hpp"

using namespace holoray;

namespace {

const char* kView =
    "v\nfrom 0 0 10\nat 0 0 0\nup 0 1 0\nangle 30\nhither 1\nresolution 512 256\n";

std::string error_of(const std::string& text) {
  try {
    parse_nff(text, "t.nff");
  } catch (const ParseError& e) {
    return e.headline();
  }
  return "no error";
}

}  // namespace

TEST(NffReader, ReadsViewpointWithOptionalFields) {
  const SceneDesc s = parse_nff(kView, "t.nff");
  ASSERT_TRUE(s.viewpoint);
  EXPECT_EQ(s.viewpoint->from, (Vec3{0, 0, 10}));
  EXPECT_EQ(s.viewpoint->at, (Vec3{0, 0, 0}));
  EXPECT_EQ(s.viewpoint->up, (Vec3{0, 1, 0}));
  EXPECT_DOUBLE_EQ(s.viewpoint->angle_deg, 30);
  EXPECT_DOUBLE_EQ(s.viewpoint->hither, 1);
  EXPECT_EQ(s.viewpoint->xres, 512);
  EXPECT_EQ(s.viewpoint->yres, 256);
  const SceneDesc bare = parse_nff("v from 1 2 3 at 0 0 0 up 0 0 1 angle 45", "t.nff");
  EXPECT_EQ(bare.viewpoint->xres, 0);
}

TEST(NffReader, ConeOnOneLineOrThreeReadsTheSame) {
  const SceneDesc one = parse_nff("c 0 0 0 1 0 0 2 0.5\n", "t.nff");
  const SceneDesc three = parse_nff("c\n0 0 0 1\n0 0 2 0.5\n", "t.nff");
  ASSERT_EQ(one.objects.size(), 1u);
  ASSERT_EQ(three.objects.size(), 1u);
  const auto& a = std::get<ConeDesc>(one.objects[0].shape);
  const auto& b = std::get<ConeDesc>(three.objects[0].shape);
  EXPECT_EQ(a.base, b.base);
  EXPECT_EQ(a.apex, (Vec3{0, 0, 2}));
  EXPECT_DOUBLE_EQ(a.base_radius, 1);
  EXPECT_DOUBLE_EQ(b.apex_radius, 0.5);
}

TEST(NffReader, EveryEntityIsRead) {
  const std::string text = std::string("b 0.1 0.2 0.3\n") + kView +
                           "l 1 2 3\n"
                           "l 4 5 6 0.5 0.25 1\n"
                           "f 1 0 0 0.8 0.2 10 0.5 1.5\n"
                           "s 1 1 1 0.5\n"
                           "p 3\n0 0 0\n1 0 0\n0 1 0\n"
                           "pp 3\n0 0 1 0 0 1\n1 0 1 0 0 1\n0 1 1 0 0 -1\n";
  const SceneDesc s = parse_nff(text, "t.nff");
  EXPECT_EQ(s.background, (Vec3{0.1, 0.2, 0.3}));
  ASSERT_EQ(s.lights.size(), 2u);
  EXPECT_EQ(s.lights[0].colour, (Vec3{1, 1, 1}));  // default when no RGB follows
  EXPECT_EQ(s.lights[1].colour, (Vec3{0.5, 0.25, 1}));
  ASSERT_EQ(s.materials.size(), 1u);
  const Material& m = s.materials[0];
  EXPECT_EQ(m.colour, (Vec3{1, 0, 0}));
  EXPECT_DOUBLE_EQ(m.kd, 0.8);
  EXPECT_DOUBLE_EQ(m.ks, 0.2);
  EXPECT_DOUBLE_EQ(m.shine, 10);
  EXPECT_DOUBLE_EQ(m.transmittance, 0.5);
  EXPECT_DOUBLE_EQ(m.ior, 1.5);
  ASSERT_EQ(s.objects.size(), 3u);
  EXPECT_EQ(std::get<SphereDesc>(s.objects[0].shape).centre, (Vec3{1, 1, 1}));
  EXPECT_EQ(std::get<PolygonDesc>(s.objects[1].shape).vertices.size(), 3u);
  EXPECT_TRUE(std::get<PolygonDesc>(s.objects[1].shape).normals.empty());
  const auto& patch = std::get<PolygonDesc>(s.objects[2].shape);
  ASSERT_EQ(patch.normals.size(), 3u);
  EXPECT_EQ(patch.normals[2], (Vec3{0, 0, -1}));  // kept as written; flipped when built
  for (const auto& o : s.objects) EXPECT_EQ(o.material, 0);
  EXPECT_EQ(s.objects[0].loc.line, 12);
  EXPECT_EQ(s.objects[0].loc.col, 1);
}

TEST(NffReader, CommentsRunToEndOfLineAnywhere) {
  const SceneDesc s = parse_nff("# a scene\ns 0 0 0 1 # unit sphere\n#s 9 9 9 9\n", "t.nff");
  ASSERT_EQ(s.objects.size(), 1u);
}

TEST(NffReader, ObjectsBeforeAnyFillGetTheDefaultMaterial) {
  const SceneDesc s = parse_nff("s 0 0 0 1\nf 1 1 1 1 0 0 0 0\ns 0 0 0 2\n", "t.nff");
  EXPECT_EQ(s.objects[0].material, -1);
  EXPECT_EQ(s.objects[1].material, 0);
}

TEST(NffReader, OpaqueMaterialIgnoresZeroIor) {
  const SceneDesc s = parse_nff("f 1 1 1 1 0 0 0 0\n", "t.nff");
  EXPECT_DOUBLE_EQ(s.materials[0].ior, 1);
}

TEST(NffReader, NumbersInEveryCFormat) {
  const SceneDesc s = parse_nff("s -0 1.11022e-16 +2 1E1\n", "t.nff");
  const auto& sp = std::get<SphereDesc>(s.objects[0].shape);
  EXPECT_DOUBLE_EQ(sp.centre.y, 1.11022e-16);
  EXPECT_DOUBLE_EQ(sp.centre.z, 2);
  EXPECT_DOUBLE_EQ(sp.radius, 10);
}

// Each class of malformed input, with its exact message.
TEST(NffReaderErrors, UnknownKeyword) {
  EXPECT_EQ(error_of("s 0 0 0 1\nsphere 1 2 3\n"),
            "t.nff:2:1: error: expected an NFF entity (v, b, l, f, c, s, p, pp), found 'sphere'");
}
TEST(NffReaderErrors, NonNumericField) {
  EXPECT_EQ(error_of("s 0 0 abc 1\n"), "t.nff:1:7: error: expected a sphere centre coordinate, found 'abc'");
}
TEST(NffReaderErrors, TruncatedFile) {
  EXPECT_EQ(error_of("p 3\n0 0 0\n1 0 0\n0 1"), "t.nff:4:4: error: expected a vertex coordinate, found end of file");
}
TEST(NffReaderErrors, NanAndInfinity) {
  EXPECT_EQ(error_of("s 0 0 0 nan\n"), "t.nff:1:9: error: expected a finite number for the sphere radius, found 'nan'");
  EXPECT_EQ(error_of("b inf 0 0\n"), "t.nff:1:3: error: expected a finite number for background colour, found 'inf'");
}
TEST(NffReaderErrors, VertexCountTooSmallOrHuge) {
  EXPECT_EQ(error_of("p 2\n0 0 0\n1 0 0\n"), "t.nff:1:3: error: expected a vertex count of at least 3, found 2");
  EXPECT_EQ(error_of("p 99999999999\n"), "t.nff:1:3: error: expected a vertex count of at most 1000000, found 99999999999");
  EXPECT_EQ(error_of("pp -3\n"), "t.nff:1:4: error: expected a patch vertex count, found '-3'");
}
TEST(NffReaderErrors, ZeroSphereRadius) {
  EXPECT_EQ(error_of("s 1 2 3 0\n"), "t.nff:1:9: error: expected a non-zero sphere radius, found 0");
}
TEST(NffReaderErrors, CoincidentConeEnds) {
  EXPECT_EQ(error_of("\n  c 1 1 1 1 1 1 1 0.5\n"), "t.nff:2:3: error: expected distinct cone base and apex, found the same point");
}
TEST(NffReaderErrors, MixedSignConeRadii) {
  EXPECT_EQ(error_of("c 0 0 0 -1 0 0 1 1\n"),
            "t.nff:1:18: error: expected cone radii of the same sign (both negative: inside only), found -1 and 1");
}
TEST(NffReaderErrors, SecondViewpoint) {
  const std::string v = "v from 0 0 1 at 0 0 0 up 0 1 0 angle 40\n";
  EXPECT_EQ(error_of(v + v), "t.nff:2:1: error: expected one viewpoint, found a second 'v' (the first is on line 1)");
}
TEST(NffReaderErrors, ViewpointKeywordsInOrder) {
  EXPECT_EQ(error_of("v from 0 0 1 up 0 1 0 at 0 0 0 angle 40\n"), "t.nff:1:14: error: expected 'at', found 'up'");
  EXPECT_EQ(error_of("v from 0 0 1 at 0 0 0 up 0 0 1 angle 40\n"),
            "t.nff:1:23: error: expected an 'up' direction not parallel to the view direction, found a parallel or zero one");
  EXPECT_EQ(error_of("v from 0 0 1 at 0 0 0 up 0 1 0 angle 180\n"),
            "t.nff:1:38: error: expected a view angle between 0 and 180 degrees, found 180");
}
TEST(NffReaderErrors, BinaryGarbage) {
  EXPECT_EQ(error_of(std::string("s 0 0 0 1\n\x01\x02\xff", 13)),
            "t.nff:2:1: error: expected an NFF entity (v, b, l, f, c, s, p, pp), found '?\?\?'");
}
TEST(NffReaderErrors, ReportShowsTheLineAndACaret) {
  try {
    parse_nff("s 0 0 0 1\ns 1 2 x 4\n", "t.nff");
    FAIL() << "no error";
  } catch (const ParseError& e) {
    EXPECT_STREQ(e.what(), "t.nff:2:7: error: expected a sphere centre coordinate, found 'x'\n  s 1 2 x 4\n        ^");
  }
}
TEST(NffReaderErrors, MissingFile) {
  try {
    read_nff_file("/nonexistent/scene.nff");
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "cannot read '/nonexistent/scene.nff': No such file or directory");
  }
}

TEST(NffReaderErrors, FolderInsteadOfFile) {
  test::TempDir dir;
  try {
    read_nff_file(dir.path.string());
    FAIL() << "no error";
  } catch (const std::system_error& e) {
    EXPECT_EQ(e.code(), std::errc::is_a_directory);
    EXPECT_EQ(std::string(e.what()), "cannot read '" + dir.path.string() + "': " + e.code().message());
  }
}

TEST(NffReader, ReadsEveryShippedScene) {
  if (!test::have_shared_scenes()) GTEST_SKIP() << "no ../shared/scenes";
  for (const auto& entry : std::filesystem::directory_iterator(test::shared_dir() + "/scenes/nff")) {
    const SceneDesc s = read_nff_file(entry.path().string());
    EXPECT_TRUE(s.viewpoint) << entry.path();
    EXPECT_FALSE(s.objects.empty()) << entry.path();
  }
}
