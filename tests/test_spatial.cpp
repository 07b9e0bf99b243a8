// Spatial reuse (issue 4): a still frame built from every k-th lens. With
// geometry reuse, every pixel that reused the surface full ray tracing sees
// is bit-identical to full ray tracing, nearly all reused pixels do, and
// every pixel is either reused or traced.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include "camera/placement.hpp"
#include "render/renderer.hpp"
#include "scene/nff_reader.hpp"
#include "temporal/spatial.hpp"
#include "test_util.hpp"

namespace holoray {
namespace {

LensArrayDesc array_for(const SceneDesc& desc, Grid grid) {
  ArraySettings s;
  s.grid = grid;
  s.lenses_x = s.lenses_y = 32;
  s.pixels_per_lens = 8;
  return place_array(s, *desc.viewpoint);
}

}  // namespace

class SpatialReuse : public ::testing::TestWithParam<std::tuple<Grid, int>> {};

TEST_P(SpatialReuse, ReusedSurfacesShadeExactlyAsFullRayTracing) {
  const auto [grid, stride] = GetParam();
  // Mirrors, a glass sphere, cones and polygons (examples/primitives.nff).
  const SceneDesc desc = read_nff_file(test::source_dir() + "/examples/primitives.nff");
  const RenderScene scene(desc);
  const LensArray cam(array_for(desc, grid));
  RenderOptions ro;
  ro.aovs.id = true;
  RenderStats stats;
  const FrameBuffers full = render_frame(scene, cam, ro, stats);

  SpatialOptions so;
  so.stride = stride;
  const SpatialFrame sf = render_spatial(scene, cam, so);
  const ReprojectedFrame& rf = sf.frame;
  size_t reused = 0, same_surface = 0, untraced_hits = 0;
  for (int j = 0; j < cam.height(); ++j)
    for (int i = 0; i < cam.width(); ++i) {
      const size_t p = static_cast<size_t>(j) * cam.width() + i;
      const int truth = static_cast<int>(*full.id.at(i, j));
      const bool traced = traced_at_stride(cam, stride, i, j);
      untraced_hits += truth >= 0 && !traced;
      // The traced lenses are full ray tracing, kept as they are.
      if (traced) {
        ASSERT_EQ(rf.status[p], PixelStatus::traced);
        for (int c = 0; c < 3; ++c) ASSERT_EQ(rf.colour.at(i, j)[c], full.colour.at(i, j)[c]);
      }
      if (rf.status[p] != PixelStatus::reprojected) continue;
      ++reused;
      if (rf.object[p] != truth) continue;
      ++same_surface;
      for (int c = 0; c < 3; ++c)
        ASSERT_EQ(rf.colour.at(i, j)[c], full.colour.at(i, j)[c]) << "pixel " << i << "," << j << " object " << truth;
    }
  // Most of the lenses left out must come from reuse, or the test proves
  // nothing; and a reused pixel showing another surface than full tracing
  // is rare.
  EXPECT_GT(reused, untraced_hits / 2);
  EXPECT_GE(same_surface, reused * 99 / 100) << reused - same_surface << " pixels reused the wrong surface";
  // Pixels neither reused nor traced do not exist: fill_missed left none.
  for (PixelStatus s : rf.status) ASSERT_TRUE(s == PixelStatus::reprojected || s == PixelStatus::traced);
}

INSTANTIATE_TEST_SUITE_P(GridsAndStrides, SpatialReuse,
                         ::testing::Combine(::testing::Values(Grid::square, Grid::hex, Grid::lenticular),
                                            ::testing::Values(2, 3)),
                         [](const auto& info) {
                           return fmt::format("{}_every_{}", to_string(std::get<0>(info.param)), std::get<1>(info.param));
                         });

TEST(SpatialReuseOptions, StrideBelowTwoIsRefused) {
  const SceneDesc desc = read_nff_file(test::source_dir() + "/examples/primitives.nff");
  const RenderScene scene(desc);
  SpatialOptions so;
  so.stride = 1;
  EXPECT_THROW(render_spatial(scene, LensArray(array_for(desc, Grid::square)), so), std::invalid_argument);
}

}  // namespace holoray
