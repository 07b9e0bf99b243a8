// The pinhole camera and its renderer (camera/pinhole.hpp,
// render/view_renderer.hpp; issue 13): the NFF view conventions
// (nff-notes §2), line() and project() as exact inverses, silhouettes
// against an analytic sphere, thread-count invariance, and agreement with
// POV-Ray, an independent renderer, on the same scene.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "camera/pinhole.hpp"
#include "image/image_io.hpp"
#include "image/metrics.hpp"
#include "render/view_renderer.hpp"
#include "scene/nff_reader.hpp"
#include "test_util.hpp"

namespace holoray {
namespace {
using test::source_dir;

PinholeDesc view(int w = 64, int h = 48) {
  // `up` not perpendicular to the view direction, as in most SPD scenes.
  return PinholeDesc{{1, -5, 2}, {0, 0, 0.5}, {0, 0.3, 1}, 40, w, h};
}

TEST(PinholeCamera, TheLookAtPointIsTheImageCentre) {
  const PinholeCamera cam(view(64, 48));
  PanelHit h;
  ASSERT_TRUE(cam.project({0, 0, 0.5}, h));
  // Even sizes: the centre is the corner shared by pixels (31, 23) and (32, 24).
  EXPECT_EQ(h.i, 32);
  EXPECT_EQ(h.j, 24);
  EXPECT_NEAR(h.u, 0, 1e-9);
  EXPECT_NEAR(h.v, 0, 1e-9);
  EXPECT_NEAR(h.t, length(Vec3{0, 0, 0.5} - Vec3{1, -5, 2}), 1e-12);
}

TEST(PinholeCamera, ProjectInvertsLineForEveryPixel) {
  const PinholeCamera cam(view(37, 23));
  for (int j = 0; j < cam.height(); ++j)
    for (int i = 0; i < cam.width(); ++i)
      for (const double t : {0.3, 4.0, 100.0}) {
        const PixelLine l = cam.line(i, j, 0.25, 0.75);
        PanelHit h;
        ASSERT_TRUE(cam.project(l.origin + l.dir * t, h)) << i << "," << j;
        EXPECT_EQ(h.i, i);
        EXPECT_EQ(h.j, j);
        EXPECT_NEAR(h.u, 0.25, 1e-7);
        EXPECT_NEAR(h.v, 0.75, 1e-7);
        EXPECT_NEAR(h.t, t, 1e-9 * t);
      }
}

// Right-handed: image right is d x up, image up is the side `up` points to;
// the field of view spans the full image height (nff-notes §2).
TEST(PinholeCamera, RightIsDirectionCrossUpAndTheAngleSpansTheImageHeight) {
  const PinholeDesc d = view(64, 64);
  const PinholeCamera cam(d);
  const Vec3 dir = normalize(d.at - d.from);
  const Vec3 right = normalize(cross(dir, d.up));
  const Vec3 up = cross(right, dir);
  PanelHit h;
  ASSERT_TRUE(cam.project(d.at + right * 0.1, h));
  EXPECT_GT(h.i, 32);
  ASSERT_TRUE(cam.project(d.at + up * 0.1, h));
  EXPECT_LT(h.j, 32);
  // A point just inside half the angle above the axis lands on the top row.
  const double half = d.fov_deg / 2 * std::numbers::pi / 180 - 1e-6;
  ASSERT_TRUE(cam.project(d.from + (dir * std::cos(half) + up * std::sin(half)) * 3, h));
  EXPECT_EQ(h.j, 0);
  EXPECT_LT(h.v, 1e-3);
  EXPECT_FALSE(cam.project(d.from - dir, h)) << "behind the eye";
  EXPECT_FALSE(cam.project(d.from + (dir * std::cos(half + 0.01) + up * std::sin(half + 0.01)) * 3, h)) << "above the image";
}

// What every camera offers (camera.hpp's PixelCamera), for the integral
// and the pinhole camera alike: every pixel's line, at any offset in the
// pixel, projects back onto that pixel and offset.
TEST(CameraInterface, EveryCameraProjectsItsPixelLinesBackToThem) {
  LensArrayDesc ld;
  ld.lenses_x = ld.lenses_y = 6;
  ld.pixels_per_lens = 5;
  std::vector<PanelHit> hits;
  auto check = [&](const PixelCamera auto& cam, const char* name) {
    for (int j = 0; j < cam.height(); ++j)
      for (int i = 0; i < cam.width(); ++i) {
        const PixelLine l = cam.line(i, j, 0.3, 0.6);
        cam.project(l.origin + l.dir * 2.5, hits);
        const bool found = std::any_of(hits.begin(), hits.end(), [&](const PanelHit& h) {
          return h.i == i && h.j == j && std::fabs(h.u - 0.3) < 1e-7 && std::fabs(h.v - 0.6) < 1e-7 &&
                 std::fabs(h.t - 2.5) < 1e-9;
        });
        EXPECT_TRUE(found) << name << " " << i << "," << j;
      }
  };
  check(LensArray(ld), "integral");
  check(PinholeCamera(view(30, 20)), "pinhole");
}

TEST(PinholeCamera, RefusesViewsThatCannotBeBuilt) {
  auto message = [](PinholeDesc d) {
    try {
      PinholeCamera cam(d);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  PinholeDesc d = view();
  d.at = d.from;
  EXPECT_EQ(message(d), "the pinhole camera looks nowhere: from and at are the same point (1, -5, 2)");
  d = view();
  d.up = d.at - d.from;
  EXPECT_EQ(message(d), "the up direction (-1, 5, -1.5) is parallel to the view direction");
  d = view();
  d.fov_deg = 180;
  EXPECT_EQ(message(d), "the field of view must be between 0 and 180 degrees, got 180");
  d = view();
  d.width = 0;
  EXPECT_EQ(message(d), "the image must be 1x1 to 2^30 pixels, got 0x48");
}

// Every pixel's id equals an analytic ray-sphere test of its centre ray
// (away from grazing rays), and depth is the distance from the eye.
TEST(PinholeView, SphereSilhouetteAndDepthMatchTheAnalyticSphere) {
  const SceneDesc desc = parse_nff("v\nfrom 0 -4 0\nat 0 0 0\nup 0 0 1\nangle 50\nhither 0\nresolution 64 64\n"
                                   "l 0 -5 5\nf 1 1 1 1 0 0 0 1\ns 0.3 0 0.2 1\n",
                                   "sphere.nff");
  const RenderScene scene(desc);
  const PinholeCamera cam(PinholeDesc{desc.viewpoint->from, desc.viewpoint->at, desc.viewpoint->up, 50, 64, 64});
  RenderOptions ro;
  ro.aovs.id = ro.aovs.depth = true;
  RenderStats stats;
  const FrameBuffers fb = render_view(scene, cam, ro, stats);
  const Vec3 c{0.3, 0, 0.2};
  int hits = 0, checked = 0;
  for (int j = 0; j < 64; ++j)
    for (int i = 0; i < 64; ++i) {
      const PixelLine l = cam.line(i, j);
      const Vec3 oc = l.origin - c;
      const double b = dot(oc, l.dir), disc = b * b - (dot(oc, oc) - 1);
      if (std::fabs(disc) < 1e-3) continue;  // grazing
      ++checked;
      const bool hit = disc > 0;
      hits += hit;
      EXPECT_EQ(*fb.id.at(i, j), hit ? 0.0f : -1.0f) << i << "," << j;
      if (hit) EXPECT_NEAR(*fb.depth.at(i, j), -b - std::sqrt(disc), 1e-5) << i << "," << j;
    }
  EXPECT_GT(checked, 4000);
  EXPECT_GT(hits, 500);
  EXPECT_EQ(stats.rays.eye, 64u * 64u);
}

TEST(PinholeView, SameImageForAnyThreadCountAndSampleCountAveragesJitter) {
  const SceneDesc desc = read_nff_file(source_dir() + "/tests/data/pinhole/spheres.nff");
  const RenderScene scene(desc);
  const Viewpoint& vp = *desc.viewpoint;
  const PinholeCamera cam(PinholeDesc{vp.from, vp.at, vp.up, vp.angle_deg, 96, 80});
  RenderOptions ro;
  RenderStats stats;
  ro.threads = 1;
  const FrameBuffers one = render_view(scene, cam, ro, stats);
  ro.threads = 3;
  const FrameBuffers three = render_view(scene, cam, ro, stats);
  EXPECT_EQ(one.colour.data, three.colour.data);
  ro.spp = 4;
  const FrameBuffers four = render_view(scene, cam, ro, stats);
  EXPECT_NE(four.colour.data, one.colour.data) << "jittered samples blur the silhouettes";
  EXPECT_GT(compare_images(one.colour, four.colour).psnr_all(), 30);
}

// POV-Ray, an independent ray tracer, renders the same scene (spheres.pov is
// bench/nff_to_pov.py's translation, see tests/data/pinhole/README.md): the
// views, silhouettes, shadows and Whitted shading agree. Measured 64.8 dB.
TEST(PinholeView, AgreesWithPovRay) {
  if (test::run_shell("command -v povray").status != 0) GTEST_SKIP() << "povray is not installed (scripts/setup.sh installs it)";
  test::TempDir dir;
  const std::string data = source_dir() + "/tests/data/pinhole/";
  const auto pov = test::run_shell("povray +I" + data + "spheres.pov +O" + dir.file("pov.png") +
                                   " +W256 +H256 -D -V +FN -A +WT1");
  ASSERT_EQ(pov.status, 0) << pov.output;
  const auto ours = test::run_cli("render " + data + "spheres.nff --camera pinhole --encoding srgb -o " +
                                  dir.file("holoray.png") + " -q");
  ASSERT_EQ(ours.status, 0) << ours.output;
  const ImageDifference d = compare_images(read_image(dir.file("holoray.png")), read_image(dir.file("pov.png")));
  EXPECT_GT(d.psnr_all(), 50);
}

// animate --camera pinhole renders each frame's viewpoint as render
// --camera pinhole does: a still shot's frames are that view, bit for bit.
TEST(PinholeView, AnimatePreviewFramesAreTheSceneView) {
  test::TempDir dir;
  const std::string scene = source_dir() + "/tests/data/pinhole/spheres.nff";
  test::write_text(dir.file("shot.toml"), "frames = 2\n[[object]]\nscene = \"" + scene + "\"\n");
  const auto anim = test::run_cli("animate " + dir.file("shot.toml") + " --camera pinhole --resolution 48x32 -o " +
                                  dir.file("frames") + " -q");
  ASSERT_EQ(anim.status, 0) << anim.output;
  const auto still = test::run_cli("render " + scene + " --camera pinhole --resolution 48x32 -o " +
                                   dir.file("still.png") + " -q");
  ASSERT_EQ(still.status, 0) << still.output;
  const ImageBuffer a = read_image(dir.file("frames/frame_0001.png")), b = read_image(dir.file("still.png"));
  EXPECT_EQ(a.width, 48);
  EXPECT_EQ(a.height, 32);
  EXPECT_EQ(a.data, b.data);
  const auto reuse = test::run_cli("animate " + dir.file("shot.toml") + " --camera pinhole --method reverse -o " +
                                   dir.file("r") + " -q");
  EXPECT_EQ(reuse.status, 1);
  EXPECT_NE(reuse.output.find("--camera pinhole: goes with --method full"), std::string::npos) << reuse.output;
}

}  // namespace
}  // namespace holoray
