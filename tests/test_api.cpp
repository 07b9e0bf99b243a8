// The public C++ API (include/holoray/): what every front end calls. Its
// renders are checked against the CLI's files and against each other (a
// mesh built in code against the same mesh read from a file, bands against
// the whole image), its errors by type and position.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstring>
#include <stop_token>
#include <thread>
#include <vector>

#include "api/renderer_state.hpp"
#include "holoray/holoray.hpp"
#include "test_util.hpp"

namespace api = holoray::api;
using holoray::test::TempDir;

namespace {

std::string primitives() { return holoray::test::source_dir() + "/examples/primitives.nff"; }

bool same_samples(const api::Image& a, const api::Image& b) {
  if (a.width() != b.width() || a.height() != b.height() || a.channels() != b.channels()) return false;
  for (size_t k = 0; k < a.size(); ++k) {
    const float x = a.data()[k], y = b.data()[k];
    if (!(x == y || (std::isnan(x) && std::isnan(y)))) return false;
  }
  return true;
}

// A unit cube's 8 corners and 12 triangles, wound counter-clockwise from outside.
api::Mesh cube(const api::Vec3d& colour) {
  api::Mesh m;
  for (int k = 0; k < 8; ++k) m.vertices.push_back({k & 1 ? 0.5 : -0.5, k & 2 ? 0.5 : -0.5, k & 4 ? 0.5 : -0.5});
  m.faces = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
             {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  m.colour = colour;
  return m;
}

api::LensArray small_array(int lenses = 16, int pixels = 4) {
  api::LensArray a;
  a.lenses_x = a.lenses_y = lenses;
  a.pixels_per_lens = pixels;
  return a;
}

}  // namespace

TEST(Api, RenderGivesTheSameFloatsAsTheCliExr) {
  TempDir dir;
  const auto r = holoray::test::run_cli("render " + primitives() + " --lenses 16x16 --pixels-per-lens 4 --aov depth -o " +
                                        dir.file("eia.exr") + " -q");
  ASSERT_EQ(r.status, 0) << r.output;
  api::RenderOptions o;
  o.aovs.depth = true;
  const api::Result out = api::render(api::Scene::load(primitives()), small_array(), o);
  EXPECT_TRUE(same_samples(out.colour, api::read_image(dir.file("eia.exr"))));
  const api::Image depth = api::read_image(dir.file("eia.depth.exr"));
  ASSERT_EQ(depth.channels(), 1);
  EXPECT_TRUE(same_samples(out.depth, depth));
}

TEST(Api, AMeshBuiltInCodeRendersAsTheSameMeshReadFromAnObjFile) {
  TempDir dir;
  holoray::test::write_text(dir.file("cube.mtl"), "newmtl red\nKd 0.7 0.2 0.1\n");
  std::string obj = "mtllib cube.mtl\nusemtl red\n";
  const api::Mesh mesh = cube({0.7, 0.2, 0.1});
  for (const auto& v : mesh.vertices) obj += fmt::format("v {} {} {}\n", v[0], v[1], v[2]);
  for (const auto& f : mesh.faces) obj += fmt::format("f {} {} {}\n", f[0] + 1, f[1] + 1, f[2] + 1);
  holoray::test::write_text(dir.file("cube.obj"), obj);

  api::Scene built;
  built.add_mesh(mesh);
  api::Scene loaded = api::Scene::load(dir.file("cube.obj"));
  for (api::Scene* s : {&built, &loaded}) s->set_viewpoint({2, 1.5, 3}, {0, 0, 0}, {0, 1, 0}, 40);
  api::RenderOptions o;
  o.aovs.depth = o.aovs.albedo = o.aovs.id = true;
  const api::Result a = api::render(built, small_array(), o), b = api::render(loaded, small_array(), o);
  EXPECT_TRUE(same_samples(a.depth, b.depth));
  EXPECT_TRUE(same_samples(a.albedo, b.albedo));
  EXPECT_TRUE(same_samples(a.id, b.id));
  // The cube is seen: some depth is finite and some pixel has its albedo.
  int hits = 0;
  for (size_t k = 0; k < a.depth.size(); ++k) hits += std::isfinite(a.depth.data()[k]);
  EXPECT_GT(hits, 0);
}

// A World is built once and rendered by many cameras: each renders what a
// Renderer that built the scene for itself renders, bit for bit, and all
// of them read the one build.
TEST(World, EachCameraOnAWorldRendersWhatItsOwnBuildRenders) {
  const api::Scene scene = api::Scene::load(primitives());
  const api::World world(scene);
  api::Pinhole view;
  view.width = 64, view.height = 48;
  const std::vector<api::Camera> cameras = {small_array(), small_array(8, 6), view};
  for (size_t k = 0; k < cameras.size(); ++k) {
    api::RenderOptions o;
    o.aovs.depth = o.aovs.id = true;
    const api::Result shared = api::Renderer(world, cameras[k], o).render(), own = api::render(scene, cameras[k], o);
    EXPECT_TRUE(same_samples(shared.colour, own.colour)) << "camera " << k;
    EXPECT_TRUE(same_samples(shared.depth, own.depth)) << "camera " << k;
    EXPECT_TRUE(same_samples(shared.id, own.id)) << "camera " << k;
  }
  // Two renderers on one world hold the same built scene.
  const api::Renderer a(world, small_array()), b(world, view);
  EXPECT_EQ(api::detail::RendererAccess::state(a).world->render_scene.get(),
            api::detail::RendererAccess::state(b).world->render_scene.get());
}

// Renderers on one world render at once, each on threads of its own (the
// first to trace builds the CPU's hierarchy; the other waits for it), and
// give what they give one after the other.
TEST(World, RenderersOnOneWorldRenderAtOnce) {
  const api::World world(api::Scene::load(primitives()));
  const std::vector<api::Camera> cameras = {small_array(16, 4), small_array(12, 6), small_array(8, 8), small_array(6, 10)};
  std::vector<api::Result> together(cameras.size());
  {
    std::vector<std::jthread> threads;
    for (size_t k = 0; k < cameras.size(); ++k)
      threads.emplace_back([&, k] {
        api::RenderOptions o;
        o.threads = 2;
        together[k] = api::Renderer(world, cameras[k], o).render();
      });
  }
  for (size_t k = 0; k < cameras.size(); ++k)
    EXPECT_TRUE(same_samples(together[k].colour, api::Renderer(world, cameras[k]).render().colour)) << "camera " << k;
}

// A world's light options are fixed when it is built: a render's, left at
// their defaults, take them; one given otherwise is refused, naming it.
TEST(World, ARenderTakesTheWorldsLightAndRefusesOther) {
  const api::Scene scene = api::Scene::load(primitives());
  api::RenderOptions path;
  path.integrator = api::Integrator::path;
  path.environment.colour = std::array<double, 3>{0.2, 0.3, 0.4};
  path.max_depth = 3;
  path.spp = 4;
  const api::World world(scene, path);
  api::RenderOptions plain;
  plain.spp = 4;
  const api::Image on_world = api::Renderer(world, small_array(), plain).render().colour;
  EXPECT_TRUE(same_samples(on_world, api::render(scene, small_array(), path).colour));
  EXPECT_FALSE(same_samples(on_world, api::render(scene, small_array(), plain).colour));  // Whitted's light differs
  api::RenderOptions deeper = plain;
  deeper.max_depth = 5;
  try {
    api::Renderer(world, small_array(), deeper);
    ADD_FAILURE() << "a depth other than the world's was taken";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "max_depth: the world was built with other light options: build a World with these, or leave it at "
                           "its default to take the world's");
  }
  api::RenderOptions other_sky = plain;
  other_sky.environment.strength = 2;
  EXPECT_THROW(api::Renderer(world, small_array(), other_sky), std::invalid_argument);
  // The same values as the world's are the world's.
  EXPECT_NO_THROW(api::Renderer(world, small_array(), path));
}

TEST(Api, ABandOfRowsHoldsExactlyThoseRowsOfTheWholeImage) {
  const api::Renderer r(api::Scene::load(primitives()), small_array());
  const api::Result whole = r.render(), band = r.render(std::array<int, 2>{12, 28});
  ASSERT_EQ(band.colour.height(), 16);
  ASSERT_EQ(band.colour.width(), whole.colour.width());
  EXPECT_EQ(std::memcmp(band.colour.data(), whole.colour.at(0, 12), band.colour.size() * sizeof(float)), 0);
}

TEST(Api, AStopRequestEndsTheRenderWithCancelled) {
  std::stop_source stop;
  std::atomic<int> calls{0};
  api::RenderOptions o;
  o.stop = stop.get_token();
  o.progress = [&](double) {
    if (++calls == 1) stop.request_stop();
  };
  const api::Renderer r(api::Scene::load(primitives()), small_array(64, 8), o);
  EXPECT_THROW(r.render(), api::Cancelled);
  // Stopped after the first tile of 64 (another thread may have been past
  // the check already), not at the end.
  EXPECT_LE(calls.load(), 2);
  EXPECT_THROW(r.render(), api::Cancelled);  // requested before it starts
}

TEST(Api, AMalformedSceneFileIsASceneErrorAtItsLineAndColumn) {
  TempDir dir;
  holoray::test::write_text(dir.file("bad.nff"), "b 0 0 0\ns 0 0 zero 1\n");
  try {
    api::Scene::load(dir.file("bad.nff"));
    FAIL() << "no error";
  } catch (const api::SceneError& e) {
    EXPECT_EQ(e.file(), dir.file("bad.nff"));
    EXPECT_EQ(e.line(), 2);
    EXPECT_EQ(e.column(), 7);
    EXPECT_NE(std::string(e.what()).find(dir.file("bad.nff") + ":2:7: error: "), std::string::npos) << e.what();
  }
}

TEST(Api, BadMeshesAreRefusedNamingTheField) {
  api::Scene s;
  api::Mesh m = cube({1, 1, 1});
  m.faces.push_back({0, 1, 8});
  try {
    s.add_mesh(m);
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "faces: row 12 refers to vertex 8, but there are 8 vertices");
  }
  m = cube({1, 1, 1});
  m.vertices[3][1] = NAN;
  EXPECT_THROW(s.add_mesh(m), std::invalid_argument);
  EXPECT_THROW(s.add_sphere({0, 0, 0}, -1), std::invalid_argument);
  EXPECT_EQ(s.object_count(), 0);
}

TEST(Api, AnAbsurdSizeIsRefusedBeforeAnythingIsAllocated) {
  api::Scene s;
  s.add_sphere({0, 0, 0}, 1);
  s.set_viewpoint({0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 40);
  EXPECT_THROW(api::Renderer(s, small_array(100000, 64)), std::length_error);
}

TEST(Api, ASceneWithoutAViewpointCannotPlaceACamera) {
  api::Scene s;
  s.add_sphere({0, 0, 0}, 1);
  EXPECT_THROW(api::render(s, small_array()), std::invalid_argument);
}

TEST(Api, AResultsSamplesOutliveTheResultWhileTheirStorageIsHeld) {
  std::shared_ptr<void> keep;
  const float* data = nullptr;
  {
    const api::Result r = api::render(api::Scene::load(primitives()), small_array());
    keep = r.colour.storage();
    data = r.colour.data();
  }
  const api::Result again = api::render(api::Scene::load(primitives()), small_array());
  EXPECT_EQ(std::memcmp(data, again.colour.data(), again.colour.size() * sizeof(float)), 0);  // ASan: not freed
}

TEST(Api, AQuiltsFocusDistanceIsTheViewpointsAtThatDistance) {
  // The same viewpoint looking at a point 1 unit away, its quilt focused at
  // 4, and one looking at a point 4 away: the same views, bit for bit.
  api::Scene near, far;
  for (api::Scene* s : {&near, &far}) {
    s->add_sphere({0, 0, 0}, 1, {0.9, 0.4, 0.2});
    s->add_sphere({1.2, 0.5, -2}, 0.7);
    s->add_light({3, 4, 5});
  }
  near.set_viewpoint({0, 0, 4}, {0, 0, 3}, {0, 1, 0}, 40);
  far.set_viewpoint({0, 0, 4}, {0, 0, 0}, {0, 1, 0}, 40);
  api::Quilt q;
  q.columns = 4, q.rows = 2, q.view_width = 24, q.view_height = 32;
  const api::Result unfocused = api::render(near, q);
  q.focus_distance = 4;
  const api::Result focused = api::render(near, q);
  q.focus_distance = std::nullopt;
  const api::Result reference = api::render(far, q);
  EXPECT_TRUE(same_samples(focused.colour, reference.colour));
  EXPECT_FALSE(same_samples(unfocused.colour, reference.colour));  // the distance matters: the test can fail
}

TEST(Api, APinholesLensShiftMovesItsWindowOverTheSameImagePlane) {
  // Shifted right by 10 pixels and up by 6, a 40x30 view is columns 20 to
  // 59 and rows 0 to 29 of a centred 60x42 view with pixels of the same size
  // (its field of view widened to 42 rows): the window slides over one plane.
  api::Scene s;
  s.add_sphere({0, 0, 0}, 1, {0.9, 0.4, 0.2});
  s.add_sphere({1.5, 0.8, -2}, 0.7);
  s.set_viewpoint({0, 0, 6}, {0, 0, 0}, {0, 1, 0}, 30);
  const double pixel = 2 * std::tan(30 * M_PI / 360) / 30;  // the 40x30 view's pixel on the plane at 1
  api::Pinhole shifted;
  shifted.width = 40, shifted.height = 30;
  const double larger = pixel * 40;
  shifted.shift_x = 10 * pixel / larger, shifted.shift_y = 6 * pixel / larger;
  api::RenderOptions o;
  o.aovs.depth = true;
  const api::Result a = api::render(s, shifted, o);
  api::Scene wide = s;
  wide.set_viewpoint({0, 0, 6}, {0, 0, 0}, {0, 1, 0}, 2 * std::atan(pixel * 42 / 2) * 180 / M_PI);
  api::Pinhole big;
  big.width = 60, big.height = 42;
  const api::Result b = api::render(wide, big, o);
  int hits = 0;
  for (int y = 0; y < 30; ++y)
    for (int x = 0; x < 40; ++x) {
      const float ta = *a.depth.at(x, y), tb = *b.depth.at(x + 20, y + 0);
      ASSERT_EQ(std::isnan(ta), std::isnan(tb)) << x << "," << y;
      if (std::isnan(ta)) continue;
      EXPECT_NEAR(ta, tb, 1e-4) << x << "," << y;
      ++hits;
    }
  EXPECT_GT(hits, 100);
}

TEST(Api, AnimationEmitsEveryFrameInOrderWithItsRow) {
  api::AnimateOptions o;
  o.frames = std::array<int, 2>{0, 5};
  api::Animation a(holoray::test::source_dir() + "/examples/shots/swinging_box.toml", o);
  std::vector<int> seen;
  a.run([&](int f, const api::Image& colour, const api::FrameRow& row) {
    seen.push_back(f);
    EXPECT_EQ(row.frame, f);
    EXPECT_EQ(colour.width(), a.width());
    EXPECT_EQ(colour.height(), a.height());
  });
  EXPECT_EQ(seen, (std::vector<int>{0, 1, 2, 3, 4, 5}));
}
