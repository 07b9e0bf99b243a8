// Looking at outputs without a display (issue 14, item 4): what an eye sees
// through the lens sheet, and the sub-aperture views as a grid and a sweep.
#include <gtest/gtest.h>

#include "camera/subaperture.hpp"
#include "display/display_file.hpp"
#include "image/image_io.hpp"
#include "preview/simulate.hpp"
#include "preview/views.hpp"
#include "test_util.hpp"

namespace holoray {
namespace {

// 8x8 lenses of 7x7 pixels (0.1 mm), 2 mm gap; every pixel its own colour.
DisplayDesc square_display() {
  return parse_display("[panel]\nresolution = [56, 56]\npixel_pitch_mm = 0.1\nsubpixels = \"none\"\n"
                       "[lens]\ngrid = \"square\"\npitch_mm = 0.7\ngap_mm = 2\n",
                       "d.toml");
}
ImageBuffer coded_panel(int w, int h) {
  ImageBuffer img(w, h, 3);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      img.at(i, j)[0] = static_cast<float>(i) / w;
      img.at(i, j)[1] = static_cast<float>(j) / h;
      img.at(i, j)[2] = 0.5f;
    }
  return img;
}

// An eye on lens (3, 5)'s axis looks straight down it: at the lens centre it
// sees the pixel under the centre, the elemental image's centre pixel (3, 3).
TEST(Simulate, AnEyeOnALensAxisSeesThatLensCentrePixel) {
  const DisplayDesc d = square_display();
  const ImageBuffer panel = coded_panel(56, 56);
  SimulateOptions o;
  o.width = 8;   // one output pixel per lens, centred on it
  o.samples = 1;
  const double cx = -2.8 + 3.5 * 0.7, cy = 2.8 - 5.5 * 0.7;
  for (double distance : {150.0, 600.0}) {
    o.eye_mm = {cx, cy, distance};
    const ImageBuffer seen = simulate_view(panel, d, o);
    ASSERT_EQ(seen.width, 8);
    ASSERT_EQ(seen.height, 8);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(seen.at(3, 5)[c], panel.at(3 * 7 + 3, 5 * 7 + 3)[c]) << distance;
  }
}

// Parallax: moving the eye right, a lens shows pixels further left in its
// elemental image (p = c + g (q - eye) / distance); the shift is the gap over
// the distance times the eye's move.
TEST(Simulate, MovingTheEyeRightShowsPixelsFurtherLeftUnderEachLens) {
  const DisplayGeometry g{56, 56, 1, 0.1, Grid::square, 0.7, 0, 2.0, 0, INFINITY, RecordingMode::orthoscopic, Frame{}};
  const DisplayCamera cam(g);
  const Vec3 q{0.35 + 0.1, -0.2, 0};  // inside lens (4, 4)
  const Vec3 left = seen_panel_point(cam, {-30, 0, 300}, q), right = seen_panel_point(cam, {30, 0, 300}, q);
  EXPECT_NEAR(right.x - left.x, -60 * 2.0 / 300, 1e-12);
  EXPECT_NEAR(right.y - left.y, 0, 1e-12);
  EXPECT_EQ(left.z, -2.0);
  // Both land under the lens the eye looks through.
  EXPECT_EQ(cam.lens_at(left), cam.lens_at({q.x, q.y, -2}));
  EXPECT_EQ(cam.lens_at(right), cam.lens_at({q.x, q.y, -2}));
}

TEST(Simulate, RefusesAnEyeBehindTheSheetAndAPanelOfAnotherSize) {
  const DisplayDesc d = square_display();
  SimulateOptions o;
  o.eye_mm = {0, 0, -10};
  EXPECT_THROW(simulate_view(coded_panel(56, 56), d, o), std::invalid_argument);
  o.eye_mm = {0, 0, 300};
  EXPECT_THROW(simulate_view(coded_panel(50, 56), d, o), std::invalid_argument);
}

TEST(Views, GridTilesAreTheSubapertureViewsAndTheSweepRunsLeftToRightAndBack) {
  const ImageBuffer eia = coded_panel(24, 16);  // 6x4 lenses of 4 px
  const LensArray cam(eia_layout(24, 16, Grid::square, 4));
  const ImageBuffer grid = view_grid(eia, cam);
  ASSERT_EQ(grid.width, 24);
  ASSERT_EQ(grid.height, 16);
  for (int v = 0; v < 4; ++v)
    for (int u = 0; u < 4; ++u) {
      const ImageBuffer view = extract_subaperture(eia, cam, u, v);
      for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 6; ++x) ASSERT_EQ(grid.at(u * 6 + x, v * 4 + y)[0], view.at(x, y)[0]) << u << "," << v;
    }
  const std::vector<ImageBuffer> sweep = view_sweep(eia, cam);
  ASSERT_EQ(sweep.size(), 6u);  // u = 0 1 2 3 2 1
  const int order[] = {0, 1, 2, 3, 2, 1};
  for (size_t f = 0; f < sweep.size(); ++f) EXPECT_EQ(sweep[f].data, extract_subaperture(eia, cam, order[f], 2).data) << f;
  // Written as an animated GIF: six frames, read back.
  test::TempDir dir;
  write_animation(dir.file("s.gif"), sweep, 10);
  const auto info = test::run_shell("oiiotool --info -v " + dir.file("s.gif"));
  EXPECT_EQ(info.status, 0) << info.output;
  EXPECT_NE(info.output.find("6 subimages"), std::string::npos) << info.output;
  EXPECT_NE(info.output.find("gif:LoopCount: 0"), std::string::npos) << info.output;
  EXPECT_NE(info.output.find("FramesPerSecond: 100/10"), std::string::npos) << info.output;
}

}  // namespace
}  // namespace holoray
