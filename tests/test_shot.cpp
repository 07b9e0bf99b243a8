// Shot files (TOML), Tachyon camera paths, keyframe tracks and the animate /
// compare commands.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>
#include <filesystem>

#include "math/transform.hpp"
#include "scene/parse_error.hpp"
#include "shot/camera_path.hpp"
#include "shot/shot_frames.hpp"
#include "shot/shot_reader.hpp"
#include "image/image_io.hpp"
#include "temporal/sequence.hpp"
#include "test_util.hpp"

namespace holoray {
namespace {
using namespace test;

TEST(Transform, InverseUndoesTheKeyAndNormalsStayPerpendicular) {
  TransformKey k;
  k.translate = {1, -2, 3};
  k.rotate_deg = {30, -45, 60};
  k.scale = {2, 0.5, 3};
  const Affine a = k.matrix();
  const Vec3 p{0.3, -0.7, 1.1};
  const Vec3 back = a.inverse().point(a.point(p));
  EXPECT_NEAR(length(back - p), 0, 1e-12);
  // A tangent maps with the matrix, the normal with the inverse transpose.
  const Vec3 tangent{1, 1, 0}, normal{1, -1, 0.5};
  EXPECT_NEAR(dot(a.dir(tangent), a.normal(normal)), 0, 1e-12);
}

TEST(Transform, TracksHoldTheirEndsAndInterpolateBetween) {
  TransformTrack track;
  TransformKey a, b;
  a.frame = 10;
  b.frame = 20;
  b.translate = {10, 0, 0};
  track.keys = {a, b};
  EXPECT_EQ(track.at(0).translate.x, 0);
  EXPECT_EQ(track.at(25).translate.x, 10);
  EXPECT_DOUBLE_EQ(track.at(12.5).translate.x, 2.5);
  track.interpolation = Interpolation::smooth;
  EXPECT_DOUBLE_EQ(track.at(15).translate.x, 5);       // symmetric ease
  EXPECT_LT(track.at(11).translate.x, 1.0);            // slow start
  EXPECT_FALSE(track.is_static());
}

TEST(CameraPath, ReadsTheTachyonFilesAndReportsBadLines) {
  if (!have_shared_scenes()) GTEST_SKIP() << "../shared not present";
  const auto path = read_camera_path(shared_dir() + "/scenes/tachyon/teapot.cam");
  EXPECT_EQ(path.size(), 654u);
  EXPECT_NEAR(path[0].view.y, -0.925, 1e-12);
  EXPECT_NEAR(path[0].centre.y, 9.456, 1e-12);
  EXPECT_NE(error_of([] { parse_camera_path("0 0 1 0 1 0 0 0 0\n0 0 1 0 1 0 0 0\n", "p.cam"); })
                .find("p.cam:2:"), std::string::npos);
  EXPECT_NE(error_of([] { parse_camera_path("0 0 1 0 0 1 0 0 0\n", "p.cam"); }).find("parallel"), std::string::npos);
  EXPECT_NE(error_of([] { parse_camera_path("", "p.cam"); }).find("at least one frame"), std::string::npos);
}

TEST(ShotReader, ReadsEveryFieldAndResolvesPathsAgainstTheShot) {
  const Shot shot = parse_shot(R"(
frames = 12
fps = 30
[array]
grid = "hex"
mode = "pseudoscopic"
lenses = [20, 10]
pixels_per_lens = 6
fov_lens = 15
[camera]
interpolation = "smooth"
[[camera.key]]
frame = 0
from = [0, -10, 0]
at = [0, 0, 0]
up = [0, 0, 1]
[[camera.key]]
frame = 11
from = [2, -10, 0]
at = [2, 0, 0]
up = [0, 0, 1]
angle = 30
[[object]]
scene = "scenes/a.nff"
[[object.key]]
frame = 0
rotate = [0, 0, 90]
scale = 2
)", "/shots/x.toml");
  EXPECT_EQ(shot.frames, 12);
  EXPECT_EQ(shot.fps, 30);
  EXPECT_EQ(shot.array.grid, Grid::hex);
  EXPECT_EQ(shot.array.mode, RecordingMode::pseudoscopic);
  EXPECT_EQ(shot.array.lenses_x, 20);
  EXPECT_EQ(shot.array.lenses_y, 10);
  EXPECT_EQ(*shot.array.fov_lens_deg, 15);
  ASSERT_EQ(shot.camera.keys.size(), 2u);
  EXPECT_EQ(*shot.camera.keys[1].angle_deg, 30);
  EXPECT_EQ(shot.camera.interpolation, Interpolation::smooth);
  ASSERT_EQ(shot.objects.size(), 1u);
  EXPECT_EQ(shot.objects[0].scene, "/shots/scenes/a.nff");
  EXPECT_EQ(shot.objects[0].motion.keys[0].scale, (Vec3{2, 2, 2}));
}

TEST(ShotReader, ErrorsNameTheFileLineAndWhatWasExpected) {
  auto err = [](const std::string& text) { return error_of([&] { parse_shot(text, "s.toml"); }); };
  EXPECT_NE(err("frames = 3\n[[object]]\nscene = 'a.nff'\ncolour = 1\n").find("s.toml:4:1: error: unknown key 'colour'"),
            std::string::npos);
  EXPECT_NE(err("frames = 0\n").find("s.toml:1:"), std::string::npos);
  EXPECT_NE(err("frames = 0\n").find("from 1 to"), std::string::npos);
  EXPECT_NE(err("frames = 3\n").find("[[object]]"), std::string::npos);
  EXPECT_NE(err("frames = 3\n[array]\ngrid = 'round'\n[[object]]\nscene='a'\n").find("square, hex, lenticular"),
            std::string::npos);
  EXPECT_NE(err("frames = [\n").find("s.toml:"), std::string::npos);  // TOML syntax
  EXPECT_NE(err("frames = 3\n[[object]]\nscene='a'\n[[object.key]]\nframe=5\n[[object.key]]\nframe=2\n")
                .find("increasing frame order"),
            std::string::npos);
}

TEST(ShotReader, CameraNameAndTexturePathsAreReadAndResolvedAgainstTheShot) {
  const Shot one = parse_shot("frames = 2\ncamera_name = 'Cam'\ntexture_path = 'tex'\n[[object]]\nscene = 'a.dae'\n",
                              "/shots/s.toml");
  EXPECT_EQ(one.read.camera_name, "Cam");
  EXPECT_EQ(one.read.texture_paths, (std::vector<std::string>{"/shots/tex"}));
  const Shot two = parse_shot("frames = 2\ntexture_path = ['t1', '/abs/t2']\n[[object]]\nscene = 'a.dae'\n", "/shots/s.toml");
  EXPECT_EQ(two.read.texture_paths, (std::vector<std::string>{"/shots/t1", "/abs/t2"}));
  EXPECT_NE(error_of([] { parse_shot("frames = 2\ntexture_path = 3\n[[object]]\nscene = 'a'\n", "s.toml"); })
                .find("s.toml:2:16: error: texture_path: expected a folder or an array of folders (strings)"),
            std::string::npos);
}

TEST(ShotFrames, TachyonPathPlacesTheArrayOnTheViewDirection) {
  if (!have_shared_scenes()) GTEST_SKIP() << "../shared not present";
  TempDir dir;
  write_text(dir.file("s.toml"), fmt::format(R"(
frames = 5
[array]
lenses = 16
[camera]
path = "{0}/scenes/tachyon/teapot.cam"
distance = 4
[[object]]
scene = "{0}/scenes/nff/teapot_s1.nff"
)", shared_dir()));
  ShotFrames shot(read_shot_file(dir.file("s.toml")));
  const auto& f = shot.shot().camera.path[3];
  const LensArrayDesc cam = shot.camera(3);
  // Orthoscopic: the array sits `distance` along the view and faces back at the camera.
  EXPECT_NEAR(length(cam.frame.origin - (f.centre + normalize(f.view) * 4)), 0, 1e-12);
  EXPECT_NEAR(dot(cam.frame.z, normalize(f.view)), -1, 1e-12);
}

// A scene file placed by several shot objects is read once per object, but
// its warnings are the file's: printed once.
TEST(AnimateCli, SceneWarningsArePrintedOncePerFile) {
  TempDir dir;
  write_text(dir.file("scene.nff"), "v\nfrom 0 -10 2\nat 0 0 0\nup 0 0 1\nangle 40\nhither 1\nresolution 64 64\n"
                                    "l 5 -6 10\nf 0.9 0.3 0.2 1 0 0 0 0\ns 0 0 0 1\np 3\n0 0 0\n1 1 1\n2 2 2\n");
  write_text(dir.file("shot.toml"), "frames = 1\n[array]\nlenses = 8\npixels_per_lens = 4\n"
                                    "[[object]]\nscene = \"scene.nff\"\n[[object]]\nscene = \"scene.nff\"\n");
  const auto r = run_cli("animate " + dir.file("shot.toml") + " -o " + dir.file("out"));
  ASSERT_EQ(r.status, 0) << r.output;
  const std::string warning = "warning: polygon with no area";
  const size_t first = r.output.find(warning);
  ASSERT_NE(first, std::string::npos) << r.output;
  EXPECT_EQ(r.output.find(warning, first + 1), std::string::npos) << r.output;
}

TEST(AnimateCli, ResumedRunEqualsUninterruptedRunAndCompareSeesNoDifference) {
  TempDir dir;
  write_text(dir.file("scene.nff"), "v\nfrom 0 -10 2\nat 0 0 0\nup 0 0 1\nangle 40\nhither 1\nresolution 64 64\n"
                                    "l 5 -6 10\nf 0.9 0.3 0.2 1 0 0 0 0\ns 0 0 0 1\n");
  write_text(dir.file("shot.toml"), R"(
frames = 7
[array]
lenses = 12
pixels_per_lens = 6
[camera]
[[camera.key]]
frame = 0
from = [0, -10, 2]
at = [0, 0, 0]
up = [0, 0, 1]
[[camera.key]]
frame = 6
from = [0.5, -10, 2]
at = [0.5, 0, 0]
up = [0, 0, 1]
[[object]]
scene = "scene.nff"
[[object.key]]
frame = 0
[[object.key]]
frame = 6
translate = [0, 0, 0.3]
)");
  const std::string shot = dir.file("shot.toml");
  const auto whole = run_cli("animate " + shot + " -o " + dir.file("a") + " --keyframe-interval 3 --report " + dir.file("a/r.md"));
  ASSERT_EQ(whole.status, 0) << whole.output;
  EXPECT_NE(whole.output.find("frame     3  traced"), std::string::npos) << whole.output;
  EXPECT_TRUE(std::filesystem::exists(dir.file("a/r.md")));
  // An interrupted run: frames 0-3 done; the rerun must make the rest identical.
  ASSERT_EQ(run_cli("animate " + shot + " -o " + dir.file("b") + " --keyframe-interval 3").status, 0);
  for (int f : {4, 5, 6}) std::filesystem::remove(dir.file(fmt::format("b/frame_{:04}.png", f)));
  const auto resumed = run_cli("animate " + shot + " -o " + dir.file("b") + " --keyframe-interval 3 --resume");
  ASSERT_EQ(resumed.status, 0) << resumed.output;
  EXPECT_EQ(resumed.output.find("frame     1 "), std::string::npos) << "finished frames are skipped";
  for (int f = 0; f < 7; ++f) {
    const auto cmp = run_cli(fmt::format("compare {} {}", dir.file(fmt::format("a/frame_{:04}.png", f)),
                                         dir.file(fmt::format("b/frame_{:04}.png", f))));
    ASSERT_EQ(cmp.status, 0) << cmp.output;
    EXPECT_NE(cmp.output.find("all         0.0000     0.0000       inf"), std::string::npos) << cmp.output;
  }
  // An unknown method is refused with the choices.
  const auto bad = run_cli("animate " + shot + " -o " + dir.file("c") + " --method fast");
  EXPECT_EQ(bad.status, 2) << "a usage error";
  EXPECT_NE(bad.output.find("holoray: error: --method: expected reverse, reproject or full, got 'fast'"), std::string::npos) << bad.output;
}

TEST(CompareCli, PsnrFollowsThePapersDefinition) {
  TempDir dir;
  ImageBuffer a(4, 4, 3, 0.0f), b(4, 4, 3, 0.0f);
  b.at(0, 0)[0] = 10 / 255.0f;  // one channel of one pixel off by 10 levels
  write_image(dir.file("a.png"), a);
  write_image(dir.file("b.png"), b);
  const auto r = run_cli("compare " + dir.file("a.png") + " " + dir.file("b.png"));
  ASSERT_EQ(r.status, 0) << r.output;
  // MSE over 48 values = 100/48; PSNR = 10 log10(255^2 / MSE).
  EXPECT_NE(r.output.find(fmt::format("{:.3f}", 10 * std::log10(255.0 * 255.0 / (100.0 / 48)))), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find(fmt::format("{:.4f}", 100.0 / 16)), std::string::npos) << r.output;  // MSE of R
  EXPECT_EQ(run_cli("compare " + dir.file("a.png") + " " + dir.file("missing.png")).status, 1);
}

TEST(Sequence, KeyframesAreEveryKthFrameAndTheLast) {
  EXPECT_EQ(keyframes(10, 4), (std::vector<int>{0, 4, 8, 9}));
  EXPECT_EQ(keyframes(9, 4), (std::vector<int>{0, 4, 8}));
  EXPECT_EQ(keyframes(1, 4), (std::vector<int>{0}));
}

}  // namespace
}  // namespace holoray
