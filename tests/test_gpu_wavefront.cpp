// The path integrator as a wavefront on the GPU (src/gpu/wavefront.cpp,
// shaders/wavefront.glsl; HOLORAY_GPU_WAVEFRONT=1) against the megakernel
// (shaders/path.glsl's path_main), on lavapipe where there is no GPU. Both
// run the shared integrator's steps (render/path_integrator.h) in the same
// order on the same numbers; the wavefront only moves the paths through
// queues between its traversals and adds each vertex's shadow terms in the
// order they were made, so the two images agree to float rounding (each
// stage a kernel of its own, compiled apart), ray for ray. On lavapipe every
// frame takes the wavefront (on a GPU, as measured: FramesTake...); the GpuPathIntegrator suite
// holds it to the CPU, and that suite runs again under the megakernel
// (tests/CMakeLists.txt, GpuPathIntegrator.UnderTheMegakernel). Whitted's
// integrator on the same wavefront (shaders/whitted_wavefront.glsl) is held
// to its megakernel the same way (GpuWavefront.Whitted*).
#include <fmt/format.h>
#include <holoray/holoray.hpp>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <string>

#include "gpu/gpu_renderer.hpp"
#include "test_util.hpp"

namespace holoray::test {
namespace {

using api::Camera;
using api::RenderOptions;
using api::Result;
using api::Scene;

// A render on the GPU by the wavefront or the megakernel, with `o`'s
// integrator (Whitted's unless set), in bands of `band` pixels if given.
Result traced(const Scene& scene, const Camera& camera, RenderOptions o, bool wavefront, const char* band = nullptr) {
  o.device = "gpu";
  ScopedEnv wave("HOLORAY_GPU_WAVEFRONT", wavefront ? "1" : "0");
  std::optional<ScopedEnv> banded;
  if (band) banded.emplace("HOLORAY_GPU_BAND", band);
  return api::render(scene, camera, o);
}

Result path_traced(const Scene& scene, const Camera& camera, RenderOptions o, bool wavefront, const char* band = nullptr) {
  o.integrator = api::Integrator::path;
  return traced(scene, camera, o, wavefront, band);
}

// The largest difference between two images' samples, relative to 1 or
// the sample's size.
float worst_difference(const api::Image& a, const api::Image& b) {
  EXPECT_EQ(a.size(), b.size());
  float worst = 0;
  for (size_t k = 0; k < std::min(a.size(), b.size()); ++k) {
    const float x = a.data()[k], y = b.data()[k];
    if (std::isnan(x) && std::isnan(y)) continue;
    worst = std::fmax(worst, std::fabs(x - y) / std::fmax(1.0f, std::fabs(x)));
  }
  return worst;
}

bool same_bits(const api::Image& a, const api::Image& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

// The wavefront's image is the megakernel's within `tolerance` (relative),
// its rays of every kind as many, its AOVs alike.
void expect_the_megakernels_image(const Scene& scene, const Camera& camera, const RenderOptions& o, const char* what,
                                  float tolerance = 1e-4f) {
  const Result mega = traced(scene, camera, o, false), wave = traced(scene, camera, o, true);
  EXPECT_LE(worst_difference(wave.colour, mega.colour), tolerance) << what;
  EXPECT_EQ(wave.stats.rays.eye, mega.stats.rays.eye) << what;
  EXPECT_EQ(wave.stats.rays.shadow, mega.stats.rays.shadow) << what;
  EXPECT_EQ(wave.stats.rays.reflected, mega.stats.rays.reflected) << what;
  EXPECT_EQ(wave.stats.rays.refracted, mega.stats.rays.refracted) << what;
  EXPECT_GT(mega.stats.rays.total(), mega.stats.rays.eye) << what << ": no ray past the eye rays";
  for (const auto& [w, m] : {std::pair{&wave.albedo, &mega.albedo}, {&wave.depth, &mega.depth}, {&wave.normal, &mega.normal},
                             {&wave.id, &mega.id}})
    EXPECT_LE(worst_difference(*w, *m), tolerance) << what << ": an AOV";
}

api::Pinhole view(int w, int h) {
  api::Pinhole p;
  p.width = w, p.height = h;
  return p;
}

// Area lights in a closed room (many bounces, a shadow ray a vertex), an
// environment image (its importance sampling's shadow rays, escapes seen
// at every depth), and a lens array of the paper's kind: the wavefront's
// image is the megakernel's, its rays counted alike, its AOVs alike.
TEST(GpuWavefront, RendersWhatTheMegakernelRenders) {
  RenderOptions o;
  o.integrator = api::Integrator::path;
  o.spp = 4;
  o.aovs = api::Aovs{true, true, true, true};
  Scene room = Scene::load(source_dir() + "/examples/lights/cornell_box.nff");
  room.add_lights(source_dir() + "/examples/lights/cornell_box.toml");
  expect_the_megakernels_image(room, view(40, 40), o, "an area light in a closed room");
  TempDir dir;
  write_image_of(dir.file("sky.exr"), 32, 16, [](int x, int y, int c) {
    return x >= 20 && x < 22 && y >= 4 && y < 6 ? 100.0f : 0.2f + 0.1f * float(c);
  });
  const Scene primitives = Scene::load(source_dir() + "/examples/primitives.nff");
  RenderOptions lit = o;
  lit.environment.file = dir.file("sky.exr");
  expect_the_megakernels_image(primitives, view(40, 30), lit, "an environment image");
  api::LensArray a;
  a.lenses_x = a.lenses_y = 12;
  a.pixels_per_lens = 6;
  expect_the_megakernels_image(primitives, a, o, "a lens array");
}

// A path's shadow terms land in its own places and are summed in the order
// made, whatever order the lanes traced them in: the image is the same bit
// for bit from run to run and whatever the bands (HOLORAY_GPU_BAND: a band
// of 500 paths at a time, so each vertex's queues fill and drain 9 times).
TEST(GpuWavefront, TheImageIsTheSameRunToRunAndBandToBand) {
  Scene room = Scene::load(source_dir() + "/examples/lights/cornell_box.nff");
  room.add_lights(source_dir() + "/examples/lights/cornell_box.toml");
  RenderOptions o;
  o.spp = 2;
  const Result first = path_traced(room, view(64, 64), o, true), again = path_traced(room, view(64, 64), o, true);
  const Result banded = path_traced(room, view(64, 64), o, true, "500");
  EXPECT_TRUE(same_bits(first.colour, again.colour));
  EXPECT_TRUE(same_bits(first.colour, banded.colour));
  EXPECT_EQ(banded.stats.rays.total(), first.stats.rays.total());
}

Scene nested_glass(TempDir& dir);

// Which lane traces which ray changes nothing: one ray a lane in queue
// order (a GPU's default), or lanes that fetch again (lavapipe's 8, and 3),
// the image and its ray counts are the same bit for bit, both integrators
// (HOLORAY_GPU_RAYS_PER_LANE).
TEST(GpuWavefront, TheImageIsTheSameWhateverTheRaysALane) {
  TempDir dir;
  Scene room = Scene::load(source_dir() + "/examples/lights/cornell_box.nff");
  room.add_lights(source_dir() + "/examples/lights/cornell_box.toml");
  const Scene glass = nested_glass(dir);
  RenderOptions o;
  o.spp = 2;
  auto with_lanes = [&](const char* rays, bool path) {
    ScopedEnv lanes("HOLORAY_GPU_RAYS_PER_LANE", rays);
    return path ? path_traced(room, view(48, 48), o, true) : traced(glass, view(32, 32), o, true);
  };
  for (const bool path : {true, false}) {
    const Result eight = with_lanes("8", path);
    for (const char* rays : {"1", "3"}) {
      const Result other = with_lanes(rays, path);
      EXPECT_TRUE(same_bits(eight.colour, other.colour)) << rays << (path ? " (path)" : " (Whitted)");
      EXPECT_EQ(eight.stats.rays.total(), other.stats.rays.total()) << rays;
    }
  }
}

// Counted, the wavefront's traversals report their lanes' steps: each node
// visited is one busy lane's step, so there are at least as many steps,
// and the counting changes nothing in the image.
TEST(GpuWavefront, CountsItsLanesStepsWithoutChangingTheImage) {
  const Scene primitives = Scene::load(source_dir() + "/examples/primitives.nff");
  RenderOptions o;
  o.spp = 2;
  const Result plain = path_traced(primitives, view(48, 32), o, true);
  o.count_work = true;
  const Result counted = path_traced(primitives, view(48, 32), o, true);
  EXPECT_TRUE(same_bits(plain.colour, counted.colour));
  EXPECT_GT(counted.stats.nodes_visited, 0u);
  EXPECT_GE(counted.stats.lane_steps, counted.stats.nodes_visited);
  EXPECT_EQ(plain.stats.lane_steps, 0u);
  const Result mega = path_traced(primitives, view(48, 32), o, false);
  EXPECT_EQ(mega.stats.lane_steps, 0u) << "the megakernel's lanes fetch nothing";
}

// A sphere small against the sky: most paths end at their first ray.
Scene short_paths(TempDir& dir) {
  write_text(dir.file("far.nff"), "v\nfrom 0 0 10\nat 0 0 0\nup 0 1 0\nangle 45\nhither 1\nresolution 48 48\n"
                                  "b 0.2 0.3 0.4\nl 5 5 5\nf 0.8 0.8 0.8 1 0 0 0 0\ns 0 0 0 1\n");
  return Scene::load(dir.file("far.nff"));
}

// ---- Whitted's integrator as a wavefront (shaders/whitted_wavefront.glsl) ----

void expect_whitted(const Scene& scene, const Camera& camera, const RenderOptions& o, const char* what) {
  expect_the_megakernels_image(scene, camera, o, what, 1e-5f);
}

// Glass spheres one inside the other around the eye: every hit sends a
// mirror ray and a refracted one on, so a pixel's tree at max_depth 5 holds
// up to 31 rays, walked one a step (more steps than the wavefront has queue
// heads: they take turns).
Scene nested_glass(TempDir& dir) {
  write_text(dir.file("glass.nff"), "v\nfrom 0 0 0\nat 0 0 -1\nup 0 1 0\nangle 60\nhither 0.01\nresolution 32 32\n"
                                    "b 0.1 0.2 0.3\nl 0.5 0.5 0.5\nf 0.9 0.7 0.5 0.5 0.4 20 0.5 1.3\ns 0 0 0 2\n"
                                    "f 0.5 0.8 0.6 0.5 0.3 20 0.6 1.1\ns 0 0 0 4\ns 1 0.5 -1.2 0.4\n");
  return Scene::load(dir.file("glass.nff"));
}

// Whitted's scenes and shading models, a lens array, AOVs and two samples
// a pixel: the glass of a branching tree, a lens array over the SPD's
// mirror balls, and a Tachyon scene (its own filtered shadows traced where
// shaded). The wavefront's image
// is the megakernel's (the same sums in the same order), its rays counted
// alike, its AOVs alike.
TEST(GpuWavefront, WhittedRendersWhatTheMegakernelRenders) {
  RenderOptions o;
  o.spp = 2;
  o.aovs = api::Aovs{true, true, true, true};
  TempDir dir;
  expect_whitted(nested_glass(dir), view(32, 32), o, "glass in glass (trees that branch)");
  if (!have_shared_scenes()) GTEST_SKIP() << "no SPD or Tachyon scenes at " << shared_dir();
  api::LensArray a;
  a.lenses_x = a.lenses_y = 12;
  a.pixels_per_lens = 6;
  expect_whitted(Scene::load(shared_dir() + "/scenes/nff/balls_s2.nff"), a, o, "mirror balls, a lens array");
  expect_whitted(Scene::load(shared_dir() + "/scenes/tachyon/teapot.dat"), view(40, 30), o, "Tachyon");
}

// The glass's trees walked to their last ray, and the image the same bit
// for bit from run to run and whatever the bands (HOLORAY_GPU_BAND: 300
// pixels at a time); a tree that may hold more rays than the wavefront
// takes steps for (max_depth 7: 127) is the megakernel's (no lane steps
// counted), its image the same.
TEST(GpuWavefront, WhittedTreesThatBranchAreWalkedToTheirLastRay) {
  TempDir dir;
  const Scene glass = nested_glass(dir);
  RenderOptions o;
  o.count_work = true;
  const Result mega = traced(glass, view(32, 32), o, false), first = traced(glass, view(32, 32), o, true);
  const Result again = traced(glass, view(32, 32), o, true), banded = traced(glass, view(32, 32), o, true, "300");
  ASSERT_GT(double(mega.stats.rays.total()) / (32.0 * 32.0), 20.0) << "trees of more rays than the queues' heads";
  EXPECT_EQ(first.stats.rays.total(), mega.stats.rays.total());
  EXPECT_EQ(banded.stats.rays.total(), mega.stats.rays.total());
  EXPECT_GT(first.stats.lane_steps, 0u);
  EXPECT_EQ(mega.stats.lane_steps, 0u);
  EXPECT_LE(worst_difference(first.colour, mega.colour), 1e-5f);
  EXPECT_TRUE(same_bits(first.colour, again.colour));
  EXPECT_TRUE(same_bits(first.colour, banded.colour));
  o.max_depth = 7;
  const Result deep = traced(glass, view(32, 32), o, true), deep_mega = traced(glass, view(32, 32), o, false);
  EXPECT_EQ(deep.stats.lane_steps, 0u) << "127 steps a band: the megakernel";
  EXPECT_TRUE(same_bits(deep.colour, deep_mega.colour));
}

// The rule measured (wave_rule, design/gpu.md "Which schedule a frame
// takes"): on a CPU device (lavapipe) every frame takes the wavefront,
// short rays or long, a still's and the frames after; on a GPU Whitted's
// frames take the megakernel, and the path integrator's the wavefront only
// after a frame of at least 8 rays a pixel a sample (glass in glass; not
// the sky's short paths, and not a first frame, which has no count before it).
TEST(GpuWavefront, FramesTakeTheScheduleMeasuredFasterOnTheirDevice) {
  if (std::getenv("HOLORAY_GPU_WAVEFRONT")) GTEST_SKIP() << "HOLORAY_GPU_WAVEFRONT chooses the schedule";
  bool on_gpu = false;
  for (const gpu::DeviceInfo& d : gpu::list_devices()) on_gpu = on_gpu || d.is_gpu;
  TempDir dir;
  RenderOptions o;
  o.device = "gpu";
  o.count_work = true;
  for (const api::Integrator integrator : {api::Integrator::whitted, api::Integrator::path}) {
    o.integrator = integrator;
    for (const bool long_paths : {false, true}) {
      const Scene scene = long_paths ? nested_glass(dir) : short_paths(dir);
      api::Renderer r(scene, view(32, 32), o);
      const Result first = r.render(), second = r.render();
      const double rays = double(first.stats.rays.total()) / (32 * 32);
      const bool path = integrator == api::Integrator::path;
      EXPECT_EQ(long_paths, rays >= 8) << rays << " rays a pixel";
      const bool wave_first = !on_gpu, wave_second = !on_gpu || (path && long_paths);
      const std::string what = fmt::format("{}, {} paths", path ? "path" : "Whitted", long_paths ? "long" : "short");
      EXPECT_EQ(first.stats.lane_steps > 0, wave_first) << what << " (lanes fetch rays only in the wavefront)";
      EXPECT_EQ(second.stats.lane_steps > 0, wave_second) << what;
      if (wave_first == wave_second) EXPECT_TRUE(same_bits(first.colour, second.colour)) << what;
    }
  }
}

}  // namespace
}  // namespace holoray::test
