// The integral camera against shared/docs/camera-model.md: its three
// properties, the grids' geometry, placement and validation.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "camera/lens_array.hpp"
#include "camera/placement.hpp"
#include "test_util.hpp"

using namespace holoray;

namespace {

LensArrayDesc make_desc(Grid grid, RecordingMode mode = RecordingMode::orthoscopic) {
  LensArrayDesc d;
  d.grid = grid;
  d.mode = mode;
  d.lenses_x = 12;
  d.lenses_y = 10;
  d.pixels_per_lens = 6;
  d.pitch = 0.5;
  d.gap = 1.2;
  // A tilted placement, so world/local mistakes show.
  d.frame = Frame::from_normal_up({1, -2, 0.5}, {0.3, 0.2, 1}, {0, 1, 0.1});
  return d;
}

double dist_to_line(const PixelLine& l, double t, const Vec3& x) { return length(l.origin + l.dir * t - x); }

}  // namespace

// Property 1 (square): pixel (u, v) of every elemental image has the same direction.
TEST(LensArrayContract, SubApertureRaysAreParallelOnSquareGrid) {
  const LensArray cam(make_desc(Grid::square));
  const int P = cam.desc().pixels_per_lens;
  for (int v = 0; v < P; ++v)
    for (int u = 0; u < P; ++u) {
      const Vec3 d0 = cam.line(u, v).dir;
      for (int ly = 0; ly < cam.lens_count_y(); ++ly)
        for (int lx = 0; lx < cam.lens_count_x(); ++lx)
          EXPECT_LT(length(cam.line(lx * P + u, ly * P + v).dir - d0), 1e-12);
    }
}

// Property 1 (lenticular, infinite V): column u of every lens, any row, has the same direction.
TEST(LensArrayContract, SubApertureRaysAreParallelOnLenticularSheet) {
  const LensArray cam(make_desc(Grid::lenticular));
  const int P = cam.desc().pixels_per_lens;
  for (int u = 0; u < P; ++u) {
    const Vec3 d0 = cam.line(u, 0).dir;
    for (int lx = 0; lx < cam.lens_count_x(); ++lx)
      for (int j = 0; j < cam.height(); j += 7) EXPECT_LT(length(cam.line(lx * P + u, j).dir - d0), 1e-12);
  }
}

// Hex rows are pitch*sqrt(3)/2 apart, not a whole number of pixels, so the
// property holds to within the angle of one pixel (noted in the README).
TEST(LensArrayContract, SubApertureRaysAreParallelWithinAPixelOnHexGrid) {
  const LensArray cam(make_desc(Grid::hex));
  const double pixel_angle = cam.pixel_pitch() / cam.desc().gap;
  for (int ly = 0; ly < cam.lens_count_y(); ++ly)
    for (int lx = 0; lx < cam.lens_count_x(); ++lx) {
      const Vec3 c = cam.lens_centre_local({lx, ly});
      // The pixel nearest the lens centre: it looks nearly straight along the normal.
      const int i = static_cast<int>(std::floor(c.x / cam.pixel_pitch() + cam.width() / 2.0));
      const int j = static_cast<int>(std::floor(cam.height() / 2.0 - c.y / cam.pixel_pitch()));
      ASSERT_EQ(cam.lens_of_pixel(i, j), (LensIndex{lx, ly}));
      EXPECT_LT(length(cam.line_local(i, j).dir - Vec3{0, 0, 1}), pixel_angle);
    }
}

// Property 2: forward projection and ray generation are exact inverses, both ways.
class ProjectionRoundTrip : public ::testing::TestWithParam<std::tuple<Grid, RecordingMode>> {};

TEST_P(ProjectionRoundTrip, ProjectedPixelsTraceBackThroughThePoint) {
  const auto [grid, mode] = GetParam();
  const LensArray cam(make_desc(grid, mode));
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> xy(-3, 3), z(-6, 6);
  std::vector<PanelHit> hits;
  int total = 0;
  for (int n = 0; n < 400; ++n) {
    const Vec3 x_local{xy(rng), xy(rng), z(rng)};
    const Vec3 x = cam.desc().frame.to_world_point(x_local);
    cam.project(x, hits);
    total += static_cast<int>(hits.size());
    for (const PanelHit& h : hits) {
      EXPECT_LT(dist_to_line(cam.line(h.i, h.j, h.u, h.v), h.t, x), 1e-9);
      if (mode == RecordingMode::pseudoscopic) EXPECT_GT(h.t, 0);
    }
  }
  EXPECT_GT(total, 400);  // most points are seen by several lenses
}

TEST_P(ProjectionRoundTrip, PointsOnAPixelLineProjectBackToThatPixel) {
  const auto [grid, mode] = GetParam();
  const LensArray cam(make_desc(grid, mode));
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> pi(0, cam.width() - 1), pj(0, cam.height() - 1);
  std::uniform_real_distribution<double> off(0.01, 0.99), tt(0.2, 8);
  std::vector<PanelHit> hits;
  for (int n = 0; n < 2000; ++n) {
    const int i = pi(rng), j = pj(rng);
    const double u = off(rng), v = off(rng);
    const double t = (mode == RecordingMode::orthoscopic && n % 2) ? -tt(rng) : tt(rng);
    const PixelLine l = cam.line(i, j, u, v);
    cam.project(l.origin + l.dir * t, hits);
    bool found = false;
    for (const PanelHit& h : hits)
      if (h.i == i && h.j == j) {
        found = true;
        EXPECT_NEAR(h.u, u, 1e-9);
        EXPECT_NEAR(h.v, v, 1e-9);
        EXPECT_NEAR(h.t, t, 1e-9 * std::fabs(t) + 1e-12);
      }
    EXPECT_TRUE(found) << "pixel " << i << "," << j << " t " << t;
  }
}

// The reprojections' lookup: a point seen along a pixel's own line direction
// is recorded by that pixel, at the line's parameter (through the lens the
// line crosses, found without a search over lenses).
TEST_P(ProjectionRoundTrip, PointsSeenAlongAPixelLineProjectAlongItToThatPixel) {
  const auto [grid, mode] = GetParam();
  const LensArray cam(make_desc(grid, mode));
  std::mt19937 rng(13);
  std::uniform_int_distribution<int> pi(0, cam.width() - 1), pj(0, cam.height() - 1);
  std::uniform_real_distribution<double> off(0.01, 0.99), tt(0.2, 8);
  for (int n = 0; n < 2000; ++n) {
    const int i = pi(rng), j = pj(rng);
    const double u = off(rng), v = off(rng);
    const double t = (mode == RecordingMode::orthoscopic && n % 2) ? -tt(rng) : tt(rng);
    const PixelLine l = cam.line_local(i, j, u, v);
    PanelHit h;
    LensIndex lens;
    ASSERT_TRUE(cam.project_along(l.origin + l.dir * t, l.dir * 3.0, h, &lens)) << "pixel " << i << "," << j;
    EXPECT_EQ(h.i, i);
    EXPECT_EQ(h.j, j);
    EXPECT_EQ(lens, cam.lens_of_pixel(i, j));
    EXPECT_NEAR(h.u, u, 1e-9);
    EXPECT_NEAR(h.v, v, 1e-9);
    EXPECT_NEAR(h.t, t, 1e-9 * std::fabs(t) + 1e-12);
  }
  PanelHit h;
  EXPECT_FALSE(cam.project_along({0.1, 0.2, 1}, {1, 0, 0}, h));  // parallel to the array: crosses it nowhere
}

INSTANTIATE_TEST_SUITE_P(AllGridsAndModes, ProjectionRoundTrip,
                         ::testing::Combine(::testing::Values(Grid::square, Grid::hex, Grid::lenticular),
                                            ::testing::Values(RecordingMode::orthoscopic, RecordingMode::pseudoscopic)),
                         test::grid_mode_name);

// Property 2, the "every lens" half: an independent brute force over all lenses
// of the square grid, straight from the contract's formulas.
TEST(LensArrayContract, ProjectionFindsEveryLensThatSeesThePoint) {
  const LensArray cam(make_desc(Grid::square));
  const auto& d = cam.desc();
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> xy(-3, 3), z(-6, 6);
  std::vector<PanelHit> hits;
  for (int n = 0; n < 300; ++n) {
    const Vec3 x{xy(rng), xy(rng), z(rng)};
    int expected = 0;
    for (int ly = 0; ly < d.lenses_y; ++ly)
      for (int lx = 0; lx < d.lenses_x; ++lx) {
        const Vec3 c{(lx + 0.5) * d.pitch - d.lenses_x * d.pitch / 2, d.lenses_y * d.pitch / 2 - (ly + 0.5) * d.pitch, 0};
        const double k = -d.gap / x.z;  // p = c + k * (x - c) on z = -g
        const double px = c.x + k * (x.x - c.x), py = c.y + k * (x.y - c.y);
        // Inside this lens's elemental image.
        expected += std::fabs(px - c.x) < d.pitch / 2 && std::fabs(py - c.y) < d.pitch / 2;
      }
    cam.project(d.frame.to_world_point(x), hits);
    EXPECT_EQ(static_cast<int>(hits.size()), expected);
  }
}

// The packet path generates a lens's lines together (issue 4), two lanes
// per SSE2 instruction (issue 43); it must give line()'s bits exactly, on
// every grid, for runs of pixels that stay in one lens and runs that cross
// lenses (rows of a hex block), jittered or not, and on an odd run, whose
// last lane takes the scalar path.
TEST(LensArrayContract, BatchedLinesEqualLineBitForBit) {
  for (const Grid grid : {Grid::square, Grid::hex, Grid::lenticular}) {
    const LensArray cam(make_desc(grid));
    constexpr int kRun = PixelLineLanes::kLaneCount, kOdd = 7;
    int is[kRun], js[kRun];
    double us[kRun], vs[kRun];
    for (int start_j = 0; start_j + 4 <= cam.height(); start_j += 3)
      for (int start_i = 0; start_i + 4 <= cam.width(); start_i += 5) {
        for (int k = 0; k < kRun; ++k) {  // a 4x4 micro-tile
          is[k] = start_i + k % 4;
          js[k] = start_j + k / 4;
          us[k] = (k * 37 % 16) / 16.0;
          vs[k] = (k * 11 % 16) / 16.0;
        }
        PixelLineLanes full, odd;
        cam.lines(is, js, us, vs, kRun, full);
        cam.lines(is, js, us, vs, kOdd, odd);
        for (int k = 0; k < kRun; ++k) {
          const PixelLine one = cam.line(is[k], js[k], us[k], vs[k]);
          for (const PixelLineLanes* l : {&full, &odd}) {
            if (l == &odd && k >= kOdd) continue;
            const Vec3 o{l->ox[k], l->oy[k], l->oz[k]}, d{l->dx[k], l->dy[k], l->dz[k]};
            for (int a = 0; a < 3; ++a) {
              ASSERT_EQ(o[a], one.origin[a]) << to_string(grid) << " lane " << k << " pixel " << is[k] << "," << js[k];
              ASSERT_EQ(d[a], one.dir[a]) << to_string(grid) << " lane " << k << " pixel " << is[k] << "," << js[k];
            }
          }
        }
      }
  }
}

TEST(LensArrayGeometry, SquareGridMatchesTheContractFormulas) {
  const LensArray cam(make_desc(Grid::square));
  const auto& d = cam.desc();
  EXPECT_EQ(cam.width(), 72);
  EXPECT_EQ(cam.height(), 60);
  const PixelLine l = cam.line_local(13, 7);
  const double s = d.pitch / d.pixels_per_lens;
  const Vec3 p{13.5 * s - 72 * s / 2, 60 * s / 2 - 7.5 * s, -d.gap};
  const Vec3 c{2.5 * d.pitch - 12 * d.pitch / 2, 10 * d.pitch / 2 - 1.5 * d.pitch, 0};
  EXPECT_LT(length(l.origin - c), 1e-15);
  EXPECT_LT(length(l.dir - normalize(c - p)), 1e-15);
  EXPECT_NEAR(cam.lens_fov_deg(), 2 * std::atan(0.5 / 2.4) * 180 / M_PI, 1e-12);
}

TEST(LensArrayGeometry, HexPixelsBelongToTheNearestCentre) {
  const LensArray cam(make_desc(Grid::hex));
  EXPECT_EQ(cam.height(), static_cast<int>(std::lround(10 * 6 * std::sqrt(3.0) / 2)));
  for (int j = 0; j < cam.height(); ++j)
    for (int i = 0; i < cam.width(); ++i) {
      const Vec3 p = cam.panel_point_local(i, j);
      const LensIndex got = cam.lens_of_pixel(i, j);
      const Vec3 cg = cam.lens_centre_local(got);
      const double dg = std::hypot(p.x - cg.x, p.y - cg.y);
      for (int ly = 0; ly < 10; ++ly)
        for (int lx = 0; lx < 12; ++lx) {
          const Vec3 c = cam.lens_centre_local({lx, ly});
          ASSERT_GE(std::hypot(p.x - c.x, p.y - c.y), dg - 1e-12) << i << "," << j;
        }
    }
  // Odd rows are shifted right by half a pitch.
  EXPECT_NEAR(cam.lens_centre_local({0, 1}).x - cam.lens_centre_local({0, 0}).x, 0.25, 1e-15);
}

TEST(LensArrayGeometry, LenticularVerticalPerspectiveFromViewDistance) {
  LensArrayDesc d = make_desc(Grid::lenticular);
  d.view_distance = 50;
  d.frame = Frame{};
  const LensArray cam(d);
  EXPECT_EQ(cam.height(), cam.width());
  const PixelLine l = cam.line_local(3, 0);  // top row: y_p > 0, ray tilts down toward the viewer's eye line
  const Vec3 p = cam.panel_point_local(3, 0);
  EXPECT_DOUBLE_EQ(l.origin.y, p.y);
  EXPECT_NEAR(l.dir.y / l.dir.z, -p.y / 50, 1e-15);
}

TEST(Placement, OrthoscopicSitsAtTheLookAtPointFacingTheEye) {
  Viewpoint vp{{0, 0, 10}, {0, 0, 0}, {0, 1, 1}, 40, 0, 0, 0, {}};
  ArraySettings s;
  s.lenses_x = 50;
  const LensArrayDesc d = place_array(s, vp);
  EXPECT_EQ(d.frame.origin, (Vec3{0, 0, 0}));
  EXPECT_LT(length(d.frame.z - Vec3{0, 0, 1}), 1e-15);
  EXPECT_LT(length(d.frame.y - Vec3{0, 1, 0}), 1e-15);  // up orthogonalised
  EXPECT_LT(length(d.frame.x - Vec3{1, 0, 0}), 1e-15);
  EXPECT_NEAR(d.pitch * 50, 2 * 10 * std::tan(20 * M_PI / 180), 1e-12);
  EXPECT_NEAR(d.gap, d.pitch / (2 * std::tan(10 * M_PI / 180)), 1e-12);
}

TEST(Placement, PseudoscopicSitsAtTheEyeFacingTheScene) {
  Viewpoint vp{{0, 0, 10}, {0, 0, 0}, {0, 1, 0}, 40, 0, 0, 0, {}};
  ArraySettings s;
  s.mode = RecordingMode::pseudoscopic;
  s.gap = 0.3;
  const LensArrayDesc d = place_array(s, vp);
  EXPECT_EQ(d.frame.origin, (Vec3{0, 0, 10}));
  EXPECT_LT(length(d.frame.z - Vec3{0, 0, -1}), 1e-15);
  EXPECT_DOUBLE_EQ(d.gap, 0.3);
}

TEST(Placement, RefusesNonsense) {
  Viewpoint vp{{0, 0, 10}, {0, 0, 0}, {0, 1, 0}, 40, 0, 0, 0, {}};
  auto message = [&](ArraySettings s, std::optional<Viewpoint> v) {
    try {
      LensArray cam(place_array(s, v));
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  ArraySettings s;
  s.fov_lens_deg = 180;
  EXPECT_EQ(message(s, vp), "lens field of view must be between 0 and 180 degrees, got 180");
  s = {};
  s.gap = -1;
  EXPECT_EQ(message(s, vp), "gap must be positive and finite, got -1");
  s = {};
  s.pitch = 0;
  EXPECT_EQ(message(s, vp), "lens pitch must be positive and finite, got 0");
  s = {};
  s.lenses_x = 0;
  EXPECT_EQ(message(s, vp), "lens counts must be at least 1, got 0x64");
  s = {};
  EXPECT_EQ(message(s, std::nullopt), "the scene has no viewpoint ('v'); place the array with `origin`, `normal`, `up` and `pitch`");
  s.origin = Vec3{0, 0, 0};
  s.normal = Vec3{0, 0, 1};
  s.up = Vec3{0, 0, 2};
  s.pitch = 0.1;
  EXPECT_EQ(message(s, std::nullopt), "'up' is zero or parallel to the array normal");
  s = {};
  s.gap = 1;
  s.fov_lens_deg = 10;
  EXPECT_EQ(message(s, vp), "give either `gap` or `fov_lens_deg`, not both");
  s = {};
  s.lenses_x = 1 << 20;
  s.lenses_y = 1;
  s.pixels_per_lens = 4096;
  EXPECT_EQ(message(s, vp), "image of 4294967296x4096 pixels: each side must be between 1 and 1073741824");
}
