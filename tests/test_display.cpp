// Display files and the display camera (issue 14): what a file becomes and
// what it refuses; a whole-pixel display is the integral camera's EIA bit for
// bit; the display camera's lines agree with the contract's camera where
// both apply; every subpixel's line crosses the axis of the lenticule above
// it; projection is the exact inverse of the lines; panels pack subpixels.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "camera/display_camera.hpp"
#include "camera/placement.hpp"
#include "camera/quilt_camera.hpp"
#include "display/display_file.hpp"
#include "display/display_placement.hpp"
#include "display/looking_glass.hpp"
#include "image/image_io.hpp"
#include "image/metrics.hpp"
#include "render/display_renderer.hpp"
#include "render/render_scene.hpp"
#include "render/view_renderer.hpp"
#include "scene/nff_reader.hpp"
#include "scene/parse_error.hpp"
#include "test_util.hpp"

namespace holoray {
namespace {

constexpr double kPi = 3.14159265358979323846;

std::string error_of(const std::string& text) {
  try {
    parse_display(text, "d.toml");
  } catch (const ParseError& e) {
    return e.headline();
  }
  return "no error";
}

const char* kLenticular =
    "name = \"test\"\n"
    "[panel]\nresolution = [40, 30]\npixel_pitch_mm = 0.1\nsubpixels = \"bgr\"\n"
    "[lens]\ngrid = \"lenticular\"\npitch_mm = 0.43\nslant_deg = 9.5\nfocal_length_mm = 0.6\noffset_mm = 0.05\n"
    "view_distance_mm = 400\n"
    "[scene]\nmode = \"pseudoscopic\"\nunits_per_mm = 0.5\ndepth = -1.5\n";

TEST(DisplayFile, ReadsEveryFieldWithItsUnit) {
  const DisplayDesc d = parse_display(kLenticular, "d.toml");
  EXPECT_EQ(d.width, 40);
  EXPECT_EQ(d.height, 30);
  EXPECT_EQ(d.pixel_pitch_mm, 0.1);
  EXPECT_EQ(d.subpixels, SubpixelOrder::bgr);
  EXPECT_EQ(d.samples_per_pixel(), 3);
  EXPECT_EQ(d.grid, Grid::lenticular);
  EXPECT_EQ(d.pitch_mm, 0.43);
  EXPECT_EQ(d.slant_deg, 9.5);
  EXPECT_EQ(d.gap_mm, 0.6);
  EXPECT_EQ(d.offset_mm, 0.05);
  EXPECT_EQ(d.view_distance_mm, 400);
  EXPECT_EQ(d.mode, RecordingMode::pseudoscopic);
  EXPECT_EQ(d.units_per_mm, 0.5);
  EXPECT_EQ(d.depth, -1.5);
  EXPECT_NEAR(d.pixels_per_lens(), 0.43 / std::cos(9.5 * kPi / 180) / 0.1, 1e-12);
  // Placed: millimetres times units_per_mm; the depth moves the lens plane.
  Viewpoint vp;
  vp.from = {0, 0, 10}, vp.at = {0, 0, 0}, vp.up = {0, 1, 0};
  const DisplayGeometry g = place_display(d, vp);
  EXPECT_DOUBLE_EQ(g.pixel_pitch, 0.05);
  EXPECT_DOUBLE_EQ(g.pitch, 0.215);
  EXPECT_DOUBLE_EQ(g.gap, 0.3);
  EXPECT_DOUBLE_EQ(g.offset, 0.025);
  EXPECT_DOUBLE_EQ(g.view_distance, 200);
  // Pseudoscopic: at `from`, z = normalize(at - from) = -z_world; depth -1.5 along it.
  EXPECT_NEAR(g.frame.origin.z, 10 + 1.5, 1e-12);
}

TEST(DisplayFile, ImpossibleValuesAreRefusedWithTheValueAndItsUnit) {
  const std::string panel = "[panel]\nresolution = [40, 30]\npixel_pitch_mm = 0.1\n";
  EXPECT_EQ(error_of(panel + "[lens]\npitch_mm = -1\ngap_mm = 1\n"),
            "d.toml:5:12: error: expected a positive 'pitch_mm' (the lens pitch), found -1 mm");
  EXPECT_EQ(error_of(panel + "[lens]\npitch_mm = 0.5\nslant_deg = 60\ngap_mm = 1\n"),
            "d.toml:6:13: error: expected 'slant_deg' from -45 to 45 degrees, found 60 degrees");
  EXPECT_EQ(error_of(panel + "[lens]\npitch_mm = 0.05\ngap_mm = 1\n"),
            "d.toml:5:12: error: a lens of 0.05 mm is narrower than a pixel (0.1 mm); expected 'pitch_mm' >= "
            "'pixel_pitch_mm'");
  EXPECT_EQ(error_of(panel + "[lens]\ngrid = \"square\"\npitch_mm = 0.5\nslant_deg = 5\ngap_mm = 1\n"),
            "d.toml:7:13: error: a slant goes with grid = \"lenticular\", not \"square\"");
  EXPECT_EQ(error_of("[panel]\nresolution = [0, 30]\npixel_pitch_mm = 0.1\n[lens]\npitch_mm = 1\ngap_mm = 1\n"),
            "d.toml:2:15: error: expected a panel width from 1 to 1048576 pixels, found 0 pixels");
  EXPECT_EQ(error_of("[panel]\nresolution = [40, 30]\npixel_pitch_mm = 0\n[lens]\npitch_mm = 1\ngap_mm = 1\n"),
            "d.toml:3:18: error: expected a positive 'pixel_pitch_mm' (the pixel pitch), found 0 mm");
  EXPECT_EQ(error_of(panel + "[lens]\npitch_mm = 0.5\n"),
            "d.toml:4:1: error: expected 'gap_mm' (lens plane to panel, mm) or 'focal_length_mm', found neither");
  EXPECT_EQ(error_of(panel + "[lens]\npitch_mm = 0.5\ngap_mm = 1\nslant = 3\n"),
            "d.toml:7:1: error: unknown key 'slant' in [lens] (expected one of: grid, pitch_mm, slant_deg, gap_mm, "
            "focal_length_mm, offset_mm, view_distance_mm)");
  EXPECT_EQ(error_of(panel + "[lens]\npitch_mm = 0.5\ngap_mm = 1\n[scene]\nunits_per_mm = -2\n"),
            "d.toml:8:16: error: expected a positive 'units_per_mm' (scene units per mm), found -2");
}

// A scene with a viewpoint, for placement and rendering.
SceneDesc small_scene() {
  return parse_nff(test::kSmallViewpointScene, "s.nff");
}

// The contract's camera for a whole-pixel display: the integral camera's
// settings, as `render --grid G --lenses N --pixels-per-lens P --gap` gives.
TEST(DisplayPlacement, AWholePixelDisplayIsTheIntegralCamerasEia) {
  const SceneDesc scene = small_scene();
  for (const char* grid : {"square", "lenticular"}) {
    SCOPED_TRACE(grid);
    const DisplayDesc d = parse_display(
        fmt::format("[panel]\nresolution = [96, 64]\npixel_pitch_mm = 0.125\nsubpixels = \"none\"\n"
                    "[lens]\ngrid = \"{}\"\npitch_mm = 1.0\ngap_mm = 2.5\n",
                    grid),
        "d.toml");
    const auto eia = as_lens_array(d, scene.viewpoint);
    ASSERT_TRUE(eia);
    ArraySettings s;
    s.grid = std::string(grid) == "square" ? Grid::square : Grid::lenticular;
    s.lenses_x = 12, s.lenses_y = s.grid == Grid::square ? 8 : 1, s.pixels_per_lens = 8;
    s.rows = s.grid == Grid::lenticular ? 64 : 0;
    // The scale at which the panel's 12 mm span the viewpoint's field.
    const double k = place_by_viewpoint(RecordingMode::orthoscopic, *scene.viewpoint).width / 12.0;
    s.gap = 2.5 * k;
    EXPECT_EQ(*eia, place_array(s, scene.viewpoint));
    // And through the command line, bit for bit.
    test::TempDir dir;
    test::write_text(dir.file("d.toml"), fmt::format("[panel]\nresolution = [96, 64]\npixel_pitch_mm = 0.125\n"
                                                     "subpixels = \"none\"\n[lens]\ngrid = \"{}\"\npitch_mm = 1.0\n"
                                                     "gap_mm = 2.5\n",
                                                     grid));
    test::write_text(dir.file("s.nff"), "v\nfrom 0 -8 3\nat 0 0 0\nup 0 0 1\nangle 40\nhither 1\nresolution 64 64\n"
                                        "l 4 -5 8\nf 0.9 0.3 0.2 1 0 0 0 0\ns 0 0 0 1\n");
    const auto a = test::run_cli("render " + dir.file("s.nff") + " --display " + dir.file("d.toml") + " -o " +
                                 dir.file("a.exr") + " -q");
    ASSERT_EQ(a.status, 0) << a.output;
    const auto b = test::run_cli(fmt::format("render {} --grid {} --lenses 12x8 --pixels-per-lens 8 {} --gap {:.17g} -o {} -q",
                                             dir.file("s.nff"), grid, s.grid == Grid::lenticular ? "--rows 64" : "", 2.5 * k,
                                             dir.file("b.exr")));
    ASSERT_EQ(b.status, 0) << b.output;
    EXPECT_EQ(read_image(dir.file("a.exr")).data, read_image(dir.file("b.exr")).data);
  }
  // Fractional pitch, a slant, an offset or subpixels: not an ordinary EIA.
  const DisplayDesc frac = parse_display(
      "[panel]\nresolution = [96, 64]\npixel_pitch_mm = 0.125\nsubpixels = \"none\"\n[lens]\npitch_mm = 1.1\ngap_mm = 2\n",
      "d.toml");
  EXPECT_FALSE(as_lens_array(frac, scene.viewpoint));
}

// The display camera's own formulas against the integral camera's where both
// apply (whole pixels per lens, no slant, no offset): the same lines.
TEST(DisplayCamera, WholePixelLinesAreTheContractsLines) {
  for (Grid grid : {Grid::square, Grid::lenticular}) {
    for (double V : {double(INFINITY), 40.0}) {
      if (grid == Grid::square && std::isfinite(V)) continue;
      SCOPED_TRACE(fmt::format("{} V={}", to_string(grid), V));
      DisplayGeometry g;
      g.width = 48, g.height = 40, g.pixel_pitch = 0.25, g.grid = grid, g.pitch = 2.0, g.gap = 3.0;
      g.view_distance = V;
      const DisplayCamera cam(g);
      LensArrayDesc a;
      a.grid = grid, a.lenses_x = 6, a.lenses_y = 5, a.pixels_per_lens = 8, a.pitch = 2.0, a.gap = 3.0;
      a.rows = grid == Grid::lenticular ? 40 : 0;
      a.view_distance = V;
      const LensArray eia(a);
      ASSERT_EQ(cam.width(), eia.width());
      ASSERT_EQ(cam.height(), eia.height());
      for (int j = 0; j < cam.height(); ++j)
        for (int i = 0; i < cam.width(); ++i) {
          const PixelLine x = cam.line_local(i, j, 0.3, 0.7), y = eia.line_local(i, j, 0.3, 0.7);
          ASSERT_LT(length(x.origin - y.origin), 1e-12) << i << "," << j;
          ASSERT_LT(length(x.dir - y.dir), 1e-12) << i << "," << j;
        }
    }
  }
}

// van Berkel's slanted sheet, checked from the horizontal side: lenticule n's
// axis crosses the middle row at x_n = left + (n + 1/2) p / cos(slant) and
// runs along (sin, cos); the lenticule above a point is the axis within half
// a pitch of it. Every subpixel of a small panel with a fractional pitch
// (4.37 px along a row) and an offset: its line crosses the lens plane on
// that axis, and leaves the panel point toward it (across the axis).
TEST(DisplayCamera, EverySubpixelLineCrossesTheAxisOfTheLenticuleAboveIt) {
  DisplayGeometry g;
  g.width = 40, g.height = 30, g.samples_per_pixel = 3, g.pixel_pitch = 0.1, g.grid = Grid::lenticular;
  const double slant = 9.4623 * kPi / 180, ph = 0.437;  // horizontal pitch
  g.pitch = ph * std::cos(slant), g.slant_rad = slant, g.gap = 0.5, g.offset = 0.03;
  const DisplayCamera cam(g);
  ASSERT_EQ(cam.width(), 120);
  const double left = -g.width * g.pixel_pitch / 2 + g.offset, s_sub = g.pixel_pitch / 3;
  const double ex = std::sin(slant), ey = std::cos(slant);  // axis direction
  int lenticules_seen = 0, last = -1000;
  for (int j = 0; j < g.height; ++j)
    for (int c = 0; c < cam.width(); ++c) {
      const double px = -g.width * g.pixel_pitch / 2 + (c + 0.5) * s_sub, py = g.height * g.pixel_pitch / 2 - (j + 0.5) * g.pixel_pitch;
      // The axis nearest the point, by perpendicular distance.
      int n_best = 0;
      double d_best = INFINITY;
      for (int n = -5; n < 20; ++n) {
        const double xn = left + (n + 0.5) * ph;
        const double d = std::fabs((px - xn) * ey - py * ex);  // |cross(p - (xn, 0), e)|
        if (d < d_best) d_best = d, n_best = n;
      }
      ASSERT_LE(d_best, g.pitch / 2 + 1e-12);
      const PixelLine line = cam.line_local(c, j);
      ASSERT_EQ(line.origin.z, 0);
      const double xn = left + (n_best + 0.5) * ph;
      EXPECT_LT(std::fabs((line.origin.x - xn) * ey - line.origin.y * ex), 1e-12) << c << "," << j;
      if (j == 0 && n_best != last) ++lenticules_seen, last = n_best;
    }
  EXPECT_GE(lenticules_seen, 9);  // the 4 mm row crosses nine or ten lenticules
}

// Contract property 2 for the display camera: every sample project() returns
// has a line through the point, and a point on a sample's line projects back
// to that sample (square and hex with fractional pitch; the slanted sheet
// with a finite view distance).
TEST(DisplayCamera, ProjectionIsTheExactInverseOfTheLines) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> uni(0, 1);
  for (Grid grid : {Grid::square, Grid::hex, Grid::lenticular}) {
    SCOPED_TRACE(to_string(grid));
    DisplayGeometry g;
    g.width = 30, g.height = 24, g.samples_per_pixel = 3, g.pixel_pitch = 0.1, g.grid = grid;
    g.pitch = 0.537, g.gap = 0.8, g.offset = -0.02;
    if (grid == Grid::lenticular) g.slant_rad = -0.16, g.view_distance = 30;
    g.frame = Frame::from_normal_up({0.5, -1, 2}, {0.2, -1, 0.3}, {0, 0, 1});
    const DisplayCamera cam(g);
    std::vector<PanelHit> hits;
    int found = 0;
    for (int k = 0; k < 200; ++k) {
      const int c = static_cast<int>(uni(rng) * cam.width()), j = static_cast<int>(uni(rng) * cam.height());
      const double u = 0.05 + 0.9 * uni(rng), v = 0.05 + 0.9 * uni(rng), t = (uni(rng) - 0.5) * 6;
      if (std::fabs(t) < 0.05) continue;
      const PixelLine line = cam.line(c, j, u, v);
      const Vec3 X = line.origin + line.dir * t;
      cam.project(X, hits);
      bool back = false;
      for (const PanelHit& h : hits) {
        const PixelLine l = cam.line(h.i, h.j, h.u, h.v);
        ASSERT_LT(length(l.origin + l.dir * h.t - X), 1e-9);
        back = back || (h.i == c && h.j == j && std::fabs(h.u - u) < 1e-6 && std::fabs(h.v - v) < 1e-6);
      }
      EXPECT_TRUE(back) << "sample " << c << "," << j << " at t " << t;
      found += static_cast<int>(hits.size());
    }
    EXPECT_GT(found, 200);  // points off the lens plane are seen by several lenses
  }
}

TEST(DisplayRender, SubpixelsTakeTheirChannelFromTheirOwnSample) {
  ImageBuffer samples(6, 1, 3);
  for (int c = 0; c < 6; ++c)
    for (int ch = 0; ch < 3; ++ch) samples.at(c, 0)[ch] = static_cast<float>(10 * c + ch);
  const ImageBuffer rgb = pack_subpixels(samples, true), bgr = pack_subpixels(samples, false);
  ASSERT_EQ(rgb.width, 2);
  // RGB: R from the left sample, G the middle, B the right.
  EXPECT_EQ(std::vector<float>(rgb.data.begin(), rgb.data.end()), (std::vector<float>{0, 11, 22, 30, 41, 52}));
  // BGR: B from the left sample, R from the right.
  EXPECT_EQ(std::vector<float>(bgr.data.begin(), bgr.data.end()), (std::vector<float>{20, 11, 2, 50, 41, 32}));
}

// A panel image does not depend on the thread count, and each channel is the
// colour traced one ray at a time along its own subpixel's line (BGR: R from
// the right-hand sample, B from the left), to the float rounding of the
// packets' direct light (light_batch.hpp), far below the subpixels'
// differences.
TEST(DisplayRender, EachChannelIsItsOwnSubpixelsSingleRayColour) {
  const SceneDesc desc = small_scene();
  const RenderScene scene(desc);
  DisplayDesc d = parse_display(kLenticular, "d.toml");
  d.mode = RecordingMode::orthoscopic, d.depth = 0, d.units_per_mm.reset();
  const DisplayCamera cam(place_display(d, desc.viewpoint));
  RenderOptions one, two;
  one.threads = 1, two.threads = 2;
  RenderStats stats;
  const FrameBuffers a = render_display(scene, cam, false, one, stats);
  const FrameBuffers b = render_display(scene, cam, false, two, stats);
  ASSERT_EQ(a.colour.width, 40);
  ASSERT_EQ(a.colour.height, 30);
  EXPECT_EQ(a.colour.data, b.colour.data);
  int differing = 0;
  for (int j = 0; j < 30; j += 3)
    for (int i = 0; i < 40; ++i) {
      float c[3];
      for (int ch = 0; ch < 3; ++ch) {
        const int sample = 3 * i + (2 - ch);  // BGR
        Vec3 colour = scene.background();
        RayCounts counts;
        if (const auto pr = primary_ray_along(cam.line(sample, j), scene.bounds(), scene.epsilon(), RecordingMode::orthoscopic)) {
          Hit hit;
          if (scene.accel().intersect(pr->ray, hit, RayCoherence::coherent))
            colour = shade(scene, pr->ray, scene.surface(pr->ray, hit, {}), 1, counts);
        }
        c[ch] = static_cast<float>(ch == 0 ? colour.x : ch == 1 ? colour.y : colour.z);
        ASSERT_NEAR(a.colour.at(i, j)[ch], c[ch], 1e-5f) << i << "," << j << " channel " << ch;
      }
      differing += c[0] != c[1] || c[1] != c[2];
    }
  EXPECT_GT(differing, 100);  // a grey would not show the channels apart
}


// A Looking Glass quilt, checked against the documented frustum written out
// here: view k looks from from + r D tan(phi_k) along d, its window shifted
// by -tan(phi_k), and sits in tile (k mod C, R - 1 - k div C) counted from
// the top left (view 0 bottom left, the last view top right).
TEST(Quilt, TileKIsThePinholeViewOfItsShearedFrustum) {
  const SceneDesc desc = small_scene();
  const RenderScene scene(desc);
  QuiltDesc q;
  q.columns = 3, q.rows = 2, q.view_width = 24, q.view_height = 18, q.view_cone_deg = 30;
  const PinholeDesc centre = view_of(*desc.viewpoint, 24, 18);
  const QuiltCamera cam(q, centre);
  RenderOptions ro;
  RenderStats stats;
  const FrameBuffers quilt = render_quilt(scene, cam, ro, stats);
  ASSERT_EQ(quilt.colour.width, 72);
  ASSERT_EQ(quilt.colour.height, 36);
  const Vec3 d = normalize(centre.at - centre.from), r = normalize(cross(d, centre.up));
  const double D = length(centre.at - centre.from);
  for (int k = 0; k < 6; ++k) {
    SCOPED_TRACE(k);
    const double phi = (-15.0 + 30.0 * k / 5) * kPi / 180;
    PinholeDesc v = centre;
    v.from = centre.from + r * (D * std::tan(phi));
    v.at = centre.at + r * (D * std::tan(phi));
    v.shift_x = -std::tan(phi);
    const FrameBuffers one = render_view(scene, PinholeCamera(v), ro, stats);
    const int x0 = (k % 3) * 24, y0 = (1 - k / 3) * 18;
    for (int j = 0; j < 18; ++j)
      for (int i = 0; i < 24; ++i)
        for (int c = 0; c < 3; ++c) ASSERT_EQ(quilt.colour.at(x0 + i, y0 + j)[c], one.colour.at(i, j)[c]) << i << "," << j;
  }
}

// The views share the focal plane through `at`: a point on it sits at the
// same pixel in every view, a point nearer the eye moves left as the views
// move right, a point beyond moves right.
TEST(Quilt, ViewsShareTheFocalPlaneAndShowParallaxAroundIt) {
  const SceneDesc desc = small_scene();
  QuiltDesc q;
  q.columns = 4, q.rows = 2, q.view_width = 40, q.view_height = 30, q.view_cone_deg = 35;
  const PinholeDesc centre = view_of(*desc.viewpoint, 40, 30);
  const QuiltCamera cam(q, centre);
  const Vec3 d = normalize(centre.at - centre.from);
  const Vec3 on_plane = centre.at + normalize(cross(d, centre.up)) * 0.7, near = on_plane - d * 3, far = on_plane + d * 4;
  double last_near = INFINITY, last_far = -INFINITY;
  std::vector<PanelHit> hits;
  for (int k = 0; k < 8; ++k) {
    PanelHit a, n, f;
    ASSERT_TRUE(cam.view(k).project(on_plane, a));
    ASSERT_TRUE(cam.view(k).project(near, n));
    ASSERT_TRUE(cam.view(k).project(far, f));
    PanelHit a0;
    ASSERT_TRUE(cam.view(0).project(on_plane, a0));
    EXPECT_NEAR(a.i + a.u, a0.i + a0.u, 1e-9);
    EXPECT_NEAR(a.j + a.v, a0.j + a0.v, 1e-9);
    EXPECT_LT(n.i + n.u, last_near);
    EXPECT_GT(f.i + f.u, last_far);
    last_near = n.i + n.u, last_far = f.i + f.u;
  }
  // The quilt's projection: one hit per view, each the inverse of its line.
  cam.project(near, hits);
  ASSERT_EQ(hits.size(), 8u);
  for (const PanelHit& h : hits) {
    const PixelLine l = cam.line(h.i, h.j, h.u, h.v);
    EXPECT_LT(length(l.origin + l.dir * h.t - near), 1e-9);
  }
}

// Every view sees a point on the same row: the views differ by a move
// along the image's right vector. A shared quilt gives each task one row of
// all the views on the strength of it (render/view_sharing.hpp). Points
// before, on and beyond the focal plane, on a mirrored screen too.
TEST(Quilt, EveryViewSeesAPointOnTheSameRow) {
  const SceneDesc desc = small_scene();
  QuiltDesc q;
  q.columns = 4, q.rows = 3, q.view_width = 40, q.view_height = 30, q.view_cone_deg = 40;
  int checked = 0;
  for (const bool mirrored : {false, true}) {
    PinholeDesc centre = view_of(*desc.viewpoint, 40, 30);
    centre.mirrored = mirrored;
    const QuiltCamera cam(q, centre);
    const Vec3 d = normalize(centre.at - centre.from), r = normalize(cross(d, centre.up)), u = cross(r, d);
    const double D = length(centre.at - centre.from);
    for (double a = -0.3; a <= 0.3; a += 0.1)
      for (double b = -0.25; b <= 0.25; b += 0.05)
        for (const double depth : {0.5, 1.0, 2.5}) {
          const Vec3 p = centre.from + (d + r * a + u * b) * (D * depth);
          PanelHit h0;
          if (!cam.view(0).project(p, h0)) continue;
          for (int k = 1; k < 12; ++k) {
            PanelHit h;
            if (!cam.view(k).project(p, h)) continue;
            EXPECT_NEAR(h.j + h.v, h0.j + h0.v, 1e-9) << "view " << k << ", mirrored " << mirrored;
            ++checked;
          }
        }
  }
  EXPECT_GT(checked, 500);
}

TEST(Quilt, FilesAreNamedAsLookingGlassToolsReadThem) {
  QuiltDesc q;  // 8x6 of 420x560: Looking Glass Portrait
  EXPECT_EQ(quilt_file_name("out.png", q), "out_qs8x6a0.75.png");
  q.columns = 5, q.rows = 9, q.view_width = 819, q.view_height = 455;
  EXPECT_EQ(quilt_file_name("renders/scene.exr", q), "renders/scene_qs5x9a1.8.exr");
  EXPECT_EQ(quilt_file_name("mine_qs5x9a1.8.png", q), "mine_qs5x9a1.8.png");
  test::TempDir dir;
  test::write_text(dir.file("s.nff"), "v\nfrom 0 -8 3\nat 0 0 0\nup 0 0 1\nangle 40\nhither 1\nresolution 64 64\n"
                                      "l 4 -5 8\nf 0.9 0.3 0.2 1 0 0 0 0\ns 0 0 0 1\n");
  const auto r = test::run_cli("render " + dir.file("s.nff") + " --quilt 3x2 --resolution 16x12 -o " + dir.file("q.png") + " -q");
  ASSERT_EQ(r.status, 0) << r.output;
  const ImageBuffer img = read_image(dir.file("q_qs3x2a1.333.png"));
  EXPECT_EQ(img.width, 48);
  EXPECT_EQ(img.height, 24);
}

// animate --display: each frame is `render --display` of the frame's
// viewpoint (here the scene's own, the shot placing nothing), bit for bit.
TEST(DisplayRender, AnimatedPanelFramesAreRenderDisplayOfTheirViewpoint) {
  test::TempDir dir;
  test::write_text(dir.file("s.nff"), "v\nfrom 0 -8 3\nat 0 0 0\nup 0 0 1\nangle 40\nhither 1\nresolution 64 64\n"
                                      "l 4 -5 8\nf 0.9 0.3 0.2 1 0 0 0 0\ns 0 0 0 1\nf 0.2 0.8 0.3 1 0 0 0 0\ns 1.5 1 0.5 0.6\n");
  test::write_text(dir.file("d.toml"), "[panel]\nresolution = [40, 30]\npixel_pitch_mm = 0.1\n"
                                       "[lens]\npitch_mm = 0.43\nslant_deg = 9.5\nfocal_length_mm = 0.6\n");
  test::write_text(dir.file("shot.toml"), "frames = 2\n[[object]]\nscene = \"s.nff\"\n");
  const auto still = test::run_cli("render " + dir.file("s.nff") + " --display " + dir.file("d.toml") + " -o " +
                                   dir.file("still.png") + " -q");
  ASSERT_EQ(still.status, 0) << still.output;
  const auto anim = test::run_cli("animate " + dir.file("shot.toml") + " --display " + dir.file("d.toml") + " -o " +
                                  dir.file("frames") + " -q");
  ASSERT_EQ(anim.status, 0) << anim.output;
  for (const char* f : {"frame_0000.png", "frame_0001.png"})
    EXPECT_EQ(test::read_bytes(dir.file(std::string("frames/") + f)), test::read_bytes(dir.file("still.png"))) << f;
  const auto reuse = test::run_cli("animate " + dir.file("shot.toml") + " --display " + dir.file("d.toml") +
                                   " --method reverse -o " + dir.file("x") + " -q");
  EXPECT_EQ(reuse.status, 1);
  EXPECT_NE(reuse.output.find("--display: goes with --method full"), std::string::npos) << reuse.output;
}

}  // namespace
}  // namespace holoray
