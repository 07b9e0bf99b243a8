// The renderer against analytic scenes and the camera contract's property 3,
// plus determinism across thread counts.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <thread>

#include <fmt/format.h>

#include "camera/lens_array.hpp"
#include "image/metrics.hpp"
#include "render/renderer.hpp"
#include "scene/mesh_reader.hpp"
#include "scene/scene_desc.hpp"
#include "test_util.hpp"

using namespace holoray;

namespace {

// An array at the world origin facing +z (array frame = world frame).
LensArrayDesc flat_array(Grid grid, RecordingMode mode) {
  LensArrayDesc d;
  d.grid = grid;
  d.mode = mode;
  d.lenses_x = 24;
  d.lenses_y = 20;
  d.pixels_per_lens = 8;
  d.pitch = 0.25;
  d.gap = 0.7;
  return d;
}

SceneDesc one_object(ObjectDesc obj) {
  SceneDesc s;
  s.background = {0.1, 0.2, 0.3};
  Material m;
  m.colour = {0.9, 0.5, 0.1};
  s.materials.push_back(m);
  obj.material = 0;
  s.objects.push_back(obj);
  return s;
}

SceneDesc square_plane(double z0, double half) {
  PolygonDesc p;
  p.vertices = {{-half, -half, z0}, {half, -half, z0}, {half, half, z0}, {-half, half, z0}};
  return one_object(ObjectDesc{p, 0, {}});
}

FrameBuffers render(const SceneDesc& desc, const LensArrayDesc& cam_desc, int threads = 0,
                    TileOrder order = TileOrder::row_major) {
  const RenderScene scene(desc);
  const LensArray cam(cam_desc);
  RenderOptions opt;
  opt.aovs = {true, true, true, true};
  opt.threads = threads;
  opt.tile_order = order;
  RenderStats stats;
  return render_frame(scene, cam, opt, stats);
}

}  // namespace

// The pixels a sphere covers are exactly those whose line meets it, computed
// here independently in double; pseudoscopic needs the far root t > 0 too.
class SphereCoverage : public ::testing::TestWithParam<std::tuple<Grid, RecordingMode>> {};

TEST_P(SphereCoverage, MatchesTheAnalyticPrediction) {
  const auto [grid, mode] = GetParam();
  const Vec3 centre{0.4, -0.3, 0.5};  // straddles the array plane
  const double r = 0.9;
  const FrameBuffers fb = render(one_object(ObjectDesc{SphereDesc{centre, r}, 0, {}}), flat_array(grid, mode));
  const LensArray cam(flat_array(grid, mode));
  int covered = 0, ambiguous = 0;
  for (int j = 0; j < cam.height(); ++j)
    for (int i = 0; i < cam.width(); ++i) {
      const PixelLine l = cam.line(i, j);
      const Vec3 oc = l.origin - centre;
      const double b = dot(oc, l.dir), c = dot(oc, oc) - r * r, disc = b * b - c;
      const double t_far = -b + std::sqrt(std::fmax(disc, 0)), t_near = -b - std::sqrt(std::fmax(disc, 0));
      const bool hit = disc > 0 && (mode == RecordingMode::orthoscopic || t_far > 0);
      // Lines grazing within float rounding of the silhouette could go either way.
      if (std::fabs(disc) < 1e-6 * r * r || std::fabs(t_far) < 1e-6) {
        ++ambiguous;
        continue;
      }
      const float id = *fb.id.at(i, j);
      ASSERT_EQ(id == 0.0f, hit) << "pixel " << i << "," << j;
      if (!hit) continue;
      ++covered;
      const double expected_t = mode == RecordingMode::orthoscopic ? t_far : (t_near > 0 ? t_near : t_far);
      EXPECT_NEAR(*fb.depth.at(i, j), expected_t, 1e-5 * std::fabs(expected_t) + 1e-7);
    }
  EXPECT_GT(covered, 1000);
  EXPECT_LT(ambiguous, 20);
}

INSTANTIATE_TEST_SUITE_P(AllGridsAndModes, SphereCoverage,
                         ::testing::Combine(::testing::Values(Grid::square, Grid::hex, Grid::lenticular),
                                            ::testing::Values(RecordingMode::orthoscopic, RecordingMode::pseudoscopic)),
                         test::grid_mode_name);

// A plane at known depth: the depth AOV is the contract's t = z0 / d_z, to 1e-5 relative.
TEST(RenderAnalytic, PlaneDepthMatchesWithinRelative1em5) {
  for (double z0 : {0.8, -1.7}) {
    const auto d = flat_array(Grid::square, RecordingMode::orthoscopic);
    const FrameBuffers fb = render(square_plane(z0, 50), d);
    const LensArray cam(d);
    for (int j = 0; j < cam.height(); ++j)
      for (int i = 0; i < cam.width(); ++i) {
        const double t = z0 / cam.line(i, j).dir.z;
        ASSERT_LE(std::fabs(*fb.depth.at(i, j) - t), 1e-5 * std::fabs(t)) << i << "," << j << " z0 " << z0;
      }
  }
}

// Property 3: a plane in front of the array (z0 > 0) records the same in both
// modes; behind it (z0 < 0) only the orthoscopic image shows it.
TEST(RenderContract, PlaneInFrontSameInBothModesBehindOnlyOrthoscopic) {
  for (Grid grid : {Grid::square, Grid::hex, Grid::lenticular}) {
    // No lights: ambient shading does not depend on which side of the plane is seen.
    const FrameBuffers ortho_front = render(square_plane(1.5, 50), flat_array(grid, RecordingMode::orthoscopic));
    const FrameBuffers pseudo_front = render(square_plane(1.5, 50), flat_array(grid, RecordingMode::pseudoscopic));
    EXPECT_EQ(ortho_front.colour.data, pseudo_front.colour.data);
    EXPECT_EQ(ortho_front.id.data, pseudo_front.id.data);
    for (float id : ortho_front.id.data) ASSERT_EQ(id, 0.0f);

    const FrameBuffers ortho_back = render(square_plane(-1.5, 50), flat_array(grid, RecordingMode::orthoscopic));
    const FrameBuffers pseudo_back = render(square_plane(-1.5, 50), flat_array(grid, RecordingMode::pseudoscopic));
    for (float id : ortho_back.id.data) ASSERT_EQ(id, 0.0f);
    for (float id : pseudo_back.id.data) ASSERT_EQ(id, -1.0f);
    for (size_t k = 0; k < pseudo_back.colour.data.size(); k += 3) {
      ASSERT_FLOAT_EQ(pseudo_back.colour.data[k], 0.1f);
      ASSERT_FLOAT_EQ(pseudo_back.colour.data[k + 2], 0.3f);
    }
  }
}

// Orthoscopic records the largest t: with two planes in front, the nearer to the viewer wins.
TEST(RenderContract, OrthoscopicSeesTheSurfaceNearestTheViewer) {
  SceneDesc s = square_plane(-1.0, 50);
  s.objects.push_back(square_plane(2.0, 50).objects[0]);  // object 1, further along +z
  const FrameBuffers ortho = render(s, flat_array(Grid::square, RecordingMode::orthoscopic));
  const FrameBuffers pseudo = render(s, flat_array(Grid::square, RecordingMode::pseudoscopic));
  for (float id : ortho.id.data) ASSERT_EQ(id, 1.0f);
  for (float id : pseudo.id.data) ASSERT_EQ(id, 1.0f);  // the only one at t > 0
}

TEST(RenderAov, AlbedoIsTheFlatColourAndNormalFacesTheViewer) {
  const FrameBuffers fb = render(square_plane(1.0, 50), flat_array(Grid::square, RecordingMode::pseudoscopic));
  const float* a = fb.albedo.at(10, 10);
  EXPECT_FLOAT_EQ(a[0], 0.9f);
  EXPECT_FLOAT_EQ(a[1], 0.5f);
  EXPECT_FLOAT_EQ(a[2], 0.1f);
  const float* n = fb.normal.at(10, 10);  // the pseudoscopic viewer is on the -z side of this plane
  EXPECT_FLOAT_EQ(n[2], -1.0f);
}

TEST(RenderDeterminism, IdenticalForAnyThreadCount) {
  SceneDesc s;
  s.lights.push_back({{3, 4, 5}, {1, 1, 1}, {}});
  s.materials.push_back(Material{{0.8, 0.3, 0.3}, 0.7, 0.3, 20, 0, 1, {}});
  s.materials.push_back(Material{{1, 1, 1}, 0.1, 0.1, 50, 0.8, 1.5, {}});
  s.objects.push_back({SphereDesc{{0, 0, 0.5}, 0.8}, 0, {}});
  s.objects.push_back({SphereDesc{{0.6, 0.4, 1.6}, 0.4}, 1, {}});
  s.objects.push_back({ConeDesc{{-1, -1, -1}, {-1, 1, 0}, 0.3, 0.1}, 0, {}});
  s.objects.push_back(square_plane(-1.2, 4).objects[0]);
  const auto d = flat_array(Grid::hex, RecordingMode::orthoscopic);
  const FrameBuffers one = render(s, d, 1), two = render(s, d, 2), many = render(s, d, 7);
  EXPECT_EQ(one.colour.data, two.colour.data);
  EXPECT_EQ(one.colour.data, many.colour.data);
  EXPECT_EQ(one.depth.data.size(), many.depth.data.size());
  EXPECT_EQ(0, std::memcmp(one.depth.data.data(), many.depth.data.data(), one.depth.data.size() * sizeof(float)));
}

TEST(RenderDeterminism, IdenticalForAnyTileOrder) {
  SceneDesc s = square_plane(-1.2, 4);
  s.lights.push_back({{3, 4, 5}, {1, 1, 1}, {}});
  s.materials.push_back(Material{{1, 1, 1}, 0.1, 0.1, 50, 0.8, 1.5, {}});
  s.objects.push_back({SphereDesc{{0.2, -0.3, 0.6}, 0.7}, static_cast<int>(s.materials.size()) - 1, {}});
  for (const Grid grid : {Grid::square, Grid::hex, Grid::lenticular}) {
    SCOPED_TRACE(to_string(grid));
    const auto d = flat_array(grid, RecordingMode::pseudoscopic);
    const FrameBuffers ref = render(s, d, 1, TileOrder::row_major);
    for (const TileOrder order : {TileOrder::reversed, TileOrder::strided})
      for (const int threads : {1, 3}) {
        const FrameBuffers other = render(s, d, threads, order);
        EXPECT_EQ(ref.colour.data, other.colour.data);
        EXPECT_EQ(ref.id.data, other.id.data);
        EXPECT_EQ(0, std::memcmp(ref.normal.data.data(), other.normal.data.data(), ref.normal.data.size() * sizeof(float)));
      }
  }
}

TEST(RenderLimits, RefusesBuffersOverTheMemoryLimitBeforeAllocating) {
  const RenderScene scene(square_plane(1, 1));
  LensArrayDesc d = flat_array(Grid::square, RecordingMode::orthoscopic);
  d.lenses_x = d.lenses_y = 100000;  // 800000^2 px * 12 B = 7324218.75 MiB of colour
  const LensArray cam(d);
  RenderStats stats;
  try {
    render_frame(scene, cam, RenderOptions{}, stats, uint64_t{1} << 30);
    FAIL() << "no error";
  } catch (const std::length_error& e) {
    EXPECT_STREQ(e.what(), "a 800000x800000 image needs 7324218.8 MiB of buffers, over the limit of 1024.0 MiB");
  }
}

// Paper §6 / issue 4: the pixel-tracing style changes the order rays are
// traced in and whether they go as packets, never what a pixel sees. Every
// grid and mode, 1 and 2 samples per pixel (the second sample is jittered),
// with mirrors, glass, a cone, a plane and two lights: every AOV, the
// primary hits and the eye, mirror and refraction ray counts agree bit for
// bit, and the two single-ray styles give the same colours bit for bit. The
// packet styles shade NFF's direct light in float batches (light_batch.hpp)
// where the single rays shade in double: their colours keep the image
// budget (issue 43: at least 60 dB), and a light's shadow ray is cast by
// both paths but where N.L is within float rounding of 0 (a few in a
// thousand here at most). P = 6 leaves partial packets at every lens edge.
// The floor is an irregular quad: a pixel line exactly on the shared edge of
// two triangles may be given either one by Embree's packet and single-ray
// kernels (an exact tie), and a centred square's diagonal would meet the
// symmetric pixel lines exactly.
TEST(RenderStyles, EveryStyleSeesTheSameSurfacesAndShadesWithinTheImageBudget) {
  PolygonDesc floor;
  floor.vertices = {{-4.1, -3.7, -1.2}, {3.9, -4.2, -1.2}, {4.3, 3.8, -1.2}, {-3.6, 4.1, -1.2}};
  SceneDesc s = one_object(ObjectDesc{floor, 0, {}});
  s.lights.push_back({{3, 4, 5}, {1, 1, 1}, {}});
  s.lights.push_back({{-2, 1, 4}, {0.5, 0.7, 1}, {}});
  s.materials.push_back(Material{{0.8, 0.3, 0.3}, 0.7, 0.3, 20, 0, 1, {}});
  s.materials.push_back(Material{{1, 1, 1}, 0.1, 0.1, 50, 0.8, 1.5, {}});
  s.objects.push_back({SphereDesc{{0, 0, 0.5}, 0.8}, 1, {}});
  s.objects.push_back({SphereDesc{{0.6, 0.4, 1.6}, 0.4}, 2, {}});
  s.objects.push_back({ConeDesc{{-1, -1, -1}, {-1, 1, 0}, 0.3, 0.1}, 1, {}});
  const RenderScene scene(s);
  for (const Grid grid : {Grid::square, Grid::hex, Grid::lenticular})
    for (const RecordingMode mode : {RecordingMode::orthoscopic, RecordingMode::pseudoscopic})
      for (const int spp : {1, 2}) {
        SCOPED_TRACE(fmt::format("{} {} spp {}", to_string(grid), to_string(mode), spp));
        LensArrayDesc d = flat_array(grid, mode);
        d.pixels_per_lens = 6;
        const LensArray cam(d);
        RenderOptions opt;
        opt.spp = spp;
        opt.aovs = {true, true, true, true};
        opt.primary_hits = true;
        opt.style = TraceStyle::horizontal;
        RenderStats ref_stats;
        const FrameBuffers ref = render_frame(scene, cam, opt, ref_stats);
        for (const TraceStyle style : {TraceStyle::vertical, TraceStyle::packet, TraceStyle::subaperture}) {
          SCOPED_TRACE(to_string(style));
          opt.style = style;
          RenderStats stats;
          const FrameBuffers other = render_frame(scene, cam, opt, stats);
          if (style == TraceStyle::vertical) EXPECT_EQ(ref.colour.data, other.colour.data);
          else EXPECT_GE(compare_images(ref.colour, other.colour).psnr_all(), 60.0);
          EXPECT_EQ(ref.albedo.data, other.albedo.data);
          EXPECT_EQ(ref.id.data, other.id.data);
          EXPECT_EQ(0, std::memcmp(ref.depth.data.data(), other.depth.data.data(), ref.depth.data.size() * sizeof(float)));
          EXPECT_EQ(0, std::memcmp(ref.normal.data.data(), other.normal.data.data(), ref.normal.data.size() * sizeof(float)));
          EXPECT_EQ(0, std::memcmp(ref.primary.data(), other.primary.data(), ref.primary.size() * sizeof(PrimaryHit)));
          EXPECT_EQ(ref_stats.rays.eye, stats.rays.eye);
          EXPECT_NEAR(static_cast<double>(stats.rays.shadow), static_cast<double>(ref_stats.rays.shadow),
                      ref_stats.rays.shadow * 0.003);
          EXPECT_EQ(ref_stats.rays.reflected, stats.rays.reflected);
          EXPECT_EQ(ref_stats.rays.refracted, stats.rays.refracted);
        }
      }
}

// Issue 43's image budget on the scenes users render: each SPD scene, the
// NFF examples and Tachyon's Room, as a 48x48-lens EIA of 8 px through the
// scene's own viewpoint, traced in packets
// (float direct light) against single rays (double) keep at least 60 dB.
TEST(RenderStyles, PacketsKeepTheImageBudgetOnTheSpdTachyonAndGltfScenes) {
  if (!test::have_shared_scenes()) GTEST_SKIP() << "no ../shared/scenes";
  std::vector<std::string> files;
  for (const char* name : {"balls_s2", "gears_s2", "mount_s2", "rings_s2", "teapot_s2", "tetra_s3", "tree_s2"})
    files.push_back(test::shared_dir() + "/scenes/nff/" + name + ".nff");
  for (const char* name : {"primitives.nff", "room.nff"}) files.push_back(test::source_dir() + "/examples/" + name);
  files.push_back(test::shared_dir() + "/scenes/tachyon/room.dat");
  // glTF's float batch: point, spot and directional lights, metals, textures, alpha.
  for (const char* name : {"lit_spheres.gltf", "mapped_plane.gltf", "masked_leaf.gltf", "textured_box.gltf"})
    files.push_back(test::source_dir() + "/tests/data/blender/" + name);
  for (const std::string& file : files) {
    SCOPED_TRACE(file);
    const SceneDesc desc = read_scene_file(file);
    const RenderScene scene(desc);
    const LensArray cam(test::camera_at(desc, {}, 48, 8));
    RenderOptions opt;
    opt.style = TraceStyle::horizontal;
    RenderStats stats;
    const FrameBuffers single = render_frame(scene, cam, opt, stats);
    opt.style = TraceStyle::packet;
    const FrameBuffers packets = render_frame(scene, cam, opt, stats);
    EXPECT_GE(compare_images(single.colour, packets.colour).psnr_all(), 60.0);
  }
}

// Issue 54: the built scene is shared, the render's settings are its own. Two
// renders of one RenderScene at once, through two arrays and two depth
// limits, give the images each gives alone.
TEST(RenderContext, OneBuiltSceneServesTwoRendersAtOnce) {
  const SceneDesc desc = read_scene_file(test::source_dir() + "/examples/primitives.nff");
  const RenderScene scene(desc);
  const LensArrayDesc near = test::camera_at(desc, {}, 24, 8), far = test::camera_at(desc, {0.5, 0, 0.3}, 24, 8);
  RenderSettings shallow = file_settings(scene), deep = shallow;
  shallow.max_depth = 1;
  deep.max_depth = 6;
  RenderOptions one_thread;
  one_thread.threads = 1;
  auto render = [&](const LensArrayDesc& d, const RenderSettings& s) {
    RenderStats stats;
    return render_frame(RenderContext(scene, s), LensArray(d), one_thread, stats).colour.data;
  };
  const auto alone_a = render(near, shallow), alone_b = render(far, deep);
  decltype(render(near, shallow)) together_a, together_b;
  std::thread a([&] { together_a = render(near, shallow); });
  std::thread b([&] { together_b = render(far, deep); });
  a.join();
  b.join();
  EXPECT_EQ(together_a, alone_a);
  EXPECT_EQ(together_b, alone_b);
  EXPECT_NE(render(near, deep), alone_a) << "the depth limit should show in this scene's mirror";
}
