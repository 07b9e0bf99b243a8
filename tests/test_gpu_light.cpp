// The path integrator on the GPU (src/gpu/shaders/path.glsl) against the
// CPU's (src/render/path_tracer.cpp), on lavapipe where there is no GPU:
// both draw each pixel's samples from the same shared sampler and shade
// with the same shared headers (src/shading/), so the two images agree to
// float rounding, sample for sample, not only in expectation. Each light
// kind, the environment, every camera kind and the sample passes are held
// to the CPU's image (PSNR on the 8-bit scale), their AOVs too.
#include <holoray/holoray.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include "gltf_squares.hpp"
#include "test_util.hpp"

namespace holoray::test {
namespace {

using api::Camera;
using api::RenderOptions;
using api::Result;
using api::Scene;

// Path traced on both devices with every AOV; the GPU's result in `gpu_out`.
double both_devices(const Scene& scene, const Camera& camera, RenderOptions o, Result* gpu_out = nullptr,
                    Result* cpu_out = nullptr) {
  o.integrator = api::Integrator::path;
  o.device = "cpu";
  Result cpu = api::render(scene, camera, o);
  o.device = "gpu";
  Result gpu = api::render(scene, camera, o);
  EXPECT_EQ(gpu.colour.width(), cpu.colour.width());
  EXPECT_EQ(gpu.colour.height(), cpu.colour.height());
  // Nothing agrees trivially: the scene shows light.
  double sum = 0;
  const size_t samples = size_t(gpu.colour.width()) * gpu.colour.height() * gpu.colour.channels();
  for (size_t k = 0; k < samples; ++k) sum += gpu.colour.data()[k];
  EXPECT_GT(sum / double(samples), 0.01) << "a black image";
  const double psnr = api::psnr(cpu.colour, gpu.colour);
  if (gpu_out) *gpu_out = std::move(gpu);
  if (cpu_out) *cpu_out = std::move(cpu);
  return psnr;
}

api::Pinhole view(int w, int h) {
  api::Pinhole p;
  p.width = w, p.height = h;
  return p;
}

// The bar: the GPU's image within float rounding of the CPU's. A path
// that float sends one way and double the other (a Russian roulette or
// lobe choice at its threshold) changes a sample, so not bit for bit.
constexpr double kAgree = 50;

TEST(GpuPathIntegrator, AnAreaLightFromALightsFileLightsTheCornellBoxAsOnTheCpu) {
  Scene scene = Scene::load(source_dir() + "/examples/lights/cornell_box.nff");
  scene.add_lights(source_dir() + "/examples/lights/cornell_box.toml");
  RenderOptions o;
  o.spp = 16;
  o.aovs = api::Aovs{true, true, true, true};
  Result gpu, cpu;
  EXPECT_GE(both_devices(scene, view(48, 48), o, &gpu, &cpu), kAgree);
  // Sample 0's first hits: the same surfaces at the same depths.
  size_t same = 0;
  const size_t n = size_t(cpu.id.width()) * cpu.id.height();
  for (size_t k = 0; k < n; ++k) same += cpu.id.data()[k] == gpu.id.data()[k];
  EXPECT_GE(double(same) / n, 0.999);
  double worst_depth = 0;
  for (size_t k = 0; k < n; ++k)
    if (!std::isnan(cpu.depth.data()[k])) worst_depth = std::max(worst_depth, double(std::fabs(cpu.depth.data()[k] - gpu.depth.data()[k])));
  EXPECT_LT(worst_depth, 1e-3);
  // And the light is there: the room is lit (its mean brightness).
  double sum = 0;
  for (size_t k = 0; k < n * 3; ++k) sum += gpu.colour.data()[k];
  EXPECT_GT(sum / double(n * 3), 0.05);
}

// A floor lit only by an emissive square above it (an OBJ's Ke).
Scene lamp_over_floor(const TempDir& dir) {
  write_text(dir.file("s.mtl"), "newmtl floor\nKd 0.8 0.8 0.8\nnewmtl lamp\nKd 0 0 0\nKe 4 3 2\n");
  write_text(dir.file("s.obj"),
             "mtllib s.mtl\nv -2 0 -2\nv 2 0 -2\nv 2 0 2\nv -2 0 2\nv -0.3 1 -0.3\nv 0.3 1 -0.3\nv 0.3 1 0.3\nv -0.3 1 0.3\n"
             "usemtl floor\nf 1 4 3 2\nusemtl lamp\nf 5 6 7 8\n");
  return Scene::load(dir.file("s.obj"));
}

// Emissive triangles are drawn as lights by power (render/emitters.hpp) on
// both devices, and met by the BSDF's rays with the same MIS weights.
TEST(GpuPathIntegrator, EmissiveSurfacesLightAsOnTheCpu) {
  TempDir dir;
  const Scene scene = lamp_over_floor(dir);
  RenderOptions o;
  o.spp = 16;
  EXPECT_GE(both_devices(scene, view(40, 30), o), kAgree);
}

// A seed draws the same samples on both devices: seeded, the two images
// agree as unseeded ones do, and differ from the unseeded.
TEST(GpuPathIntegrator, ASeedDrawsTheSameSamplesOnBothDevices) {
  TempDir dir;
  const Scene scene = lamp_over_floor(dir);
  RenderOptions o;
  o.spp = 4;
  Result unseeded, seeded;
  EXPECT_GE(both_devices(scene, view(40, 30), o, &unseeded), kAgree);
  o.seed = 12345;
  EXPECT_GE(both_devices(scene, view(40, 30), o, &seeded), kAgree);
  EXPECT_LT(api::psnr(unseeded.colour, seeded.colour), kAgree - 10);
}

// glTF's rough thin-walled transmission (shading/bsdf.h): a rough glass
// square in front of a glowing one, lit through the glass by both the
// BSDF's rays and the light sampling from behind it.
TEST(GpuPathIntegrator, RoughTransmissionMatchesTheCpu) {
  TempDir dir;
  GltfSquares s;
  s.materials = R"({"name": "glass", "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1}},
 "pbrMetallicRoughness": {"baseColorFactor": [1, 0.8, 0.6, 1], "metallicFactor": 0, "roughnessFactor": 0.4}},
 {"name": "glow", "emissiveFactor": [1, 1, 1], "pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1], "metallicFactor": 1}})";
  s.squares = {{1.5, 0}, {0.4, -1}};
  s.lights = "";
  s.light_node = "{}";
  write_text(dir.file("s.gltf"), gltf(s));
  const Scene scene = Scene::load(dir.file("s.gltf"));
  RenderOptions o;
  o.spp = 16;
  EXPECT_GE(both_devices(scene, view(32, 32), o), kAgree);
}

// An equirectangular image, importance-sampled by its alias table on the
// device, turned and scaled as on the CPU; seen directly and lighting the
// scene.
TEST(GpuPathIntegrator, AnEnvironmentImageLightsAsOnTheCpu) {
  TempDir dir;
  // A dim sky with one bright patch (a sun), so that sampling by the image matters.
  write_image_of(dir.file("sky.exr"), 64, 32, [](int x, int y, int c) {
    const bool sun = x >= 40 && x < 44 && y >= 8 && y < 11;
    return sun ? 200.0f : 0.2f + 0.1f * float(c) + 0.01f * float(y);
  });
  const Scene scene = Scene::load(source_dir() + "/examples/primitives.nff");
  RenderOptions o;
  o.spp = 8;
  o.environment.file = dir.file("sky.exr");
  o.environment.strength = 0.7;
  o.environment.rotation_deg = 30;
  o.aovs = api::Aovs{true, true, true, true};
  EXPECT_GE(both_devices(scene, view(48, 36), o), kAgree);
  o.environment = {};
  o.environment.colour = std::array<double, 3>{0.3, 0.4, 0.5};
  EXPECT_GE(both_devices(scene, view(48, 36), o), kAgree) << "a constant environment";
}

// Every camera the GPU path renders: lens arrays of each grid in both
// recording modes, a quilt, a display's panel and a Looking Glass's native
// image (subpixels), each sample placed by the pixel's sampler.
TEST(GpuPathIntegrator, EveryCameraMatchesTheCpu) {
  const Scene scene = Scene::load(source_dir() + "/examples/primitives.nff");
  RenderOptions o;
  o.spp = 2;
  for (const api::Grid grid : {api::Grid::square, api::Grid::hex, api::Grid::lenticular})
    for (const api::Mode mode : {api::Mode::orthoscopic, api::Mode::pseudoscopic}) {
      api::LensArray a;
      a.grid = grid, a.mode = mode;
      a.lenses_x = a.lenses_y = 16;
      a.pixels_per_lens = 6;
      if (grid == api::Grid::lenticular) a.lenses_x = 24, a.rows = 64, a.view_distance = 30;
      EXPECT_GE(both_devices(scene, a, o), kAgree) << int(grid) << " " << int(mode);
    }
  api::Quilt q;
  q.columns = 4, q.rows = 2, q.view_width = 32, q.view_height = 24;
  EXPECT_GE(both_devices(scene, q, o), kAgree) << "quilt";
  // Small panels (a sheet's pitch no multiple of a subpixel, as in
  // GpuPath.DisplayPanelsMatchTheCpuPath; the Portrait's calibration shrunk).
  TempDir dir;
  write_text(dir.file("d.toml"), "[panel]\nresolution = [120, 80]\npixel_pitch_mm = 0.1\nsubpixels = \"bgr\"\n[lens]\n"
                                 "grid = \"lenticular\"\npitch_mm = 0.4317\nslant_deg = 9.46\nfocal_length_mm = 1.2\n");
  EXPECT_GE(both_devices(scene, api::Display{dir.file("d.toml")}, o), kAgree) << "display";
  std::string calibration = read_bytes(source_dir() + "/examples/displays/looking_glass_example_calibration.json");
  for (const auto& [from, to] : {std::pair{"\"screenW\": {\"value\": 1536.0}", "\"screenW\": {\"value\": 96.0}"},
                                 std::pair{"\"screenH\": {\"value\": 2048.0}", "\"screenH\": {\"value\": 128.0}"},
                                 std::pair{"\"DPI\": {\"value\": 324.0}", "\"DPI\": {\"value\": 20.25}"}})
    calibration.replace(calibration.find(from), std::string(from).size(), to);
  write_text(dir.file("lg.json"), calibration);
  EXPECT_GE(both_devices(scene, api::LookingGlass{dir.file("lg.json")}, o), kAgree) << "Looking Glass";
}

// Tachyon's materials (texfuncs, light spheres, transparency) path trace
// on both devices alike.
TEST(GpuPathIntegrator, TachyonScenesMatchTheCpu) {
  if (!have_shared_scenes()) GTEST_SKIP() << "needs ../shared/scenes";
  const Scene scene = Scene::load(shared_dir() + "/scenes/tachyon/teapot.dat");
  RenderOptions o;
  o.spp = 4;
  EXPECT_GE(both_devices(scene, view(64, 64), o), kAgree);
}

// Tachyon's texture functions (checker, wood, the cylindrical, spherical
// and planar image maps) colour what the paths meet on both devices: before the CPU's
// hook read them, its image was the materials' plain colours, 7 dB from
// the GPU's.
TEST(GpuPathIntegrator, TachyonTexturesColourThePathsAsOnTheCpu) {
  const Scene scene = Scene::load(source_dir() + "/tests/data/tachyon/features.dat");
  RenderOptions o;
  o.spp = 4;
  EXPECT_GE(both_devices(scene, view(64, 64), o), kAgree);
}

// The light issue's bar: at equal samples, each device's image against a
// converged reference (the CPU's at 64 times the samples) is within 0.5 dB
// of the other's.
TEST(GpuPathIntegrator, BothDevicesAreEquallyFarFromTheConvergedImage) {
  Scene scene = Scene::load(source_dir() + "/examples/lights/cornell_box.nff");
  scene.add_lights(source_dir() + "/examples/lights/cornell_box.toml");
  RenderOptions o;
  o.integrator = api::Integrator::path;
  o.spp = 1024;
  const Result reference = api::render(scene, view(24, 24), o);
  o.spp = 16;
  Result gpu, cpu;
  both_devices(scene, view(24, 24), o, &gpu, &cpu);
  const double cpu_db = api::psnr(reference.colour, cpu.colour), gpu_db = api::psnr(reference.colour, gpu.colour);
  EXPECT_NEAR(cpu_db, gpu_db, 0.5);
  EXPECT_LT(cpu_db, 45) << "16 samples are still noisy: the bar is not met trivially";
}

// One sample of every pixel a pass: many samples per pixel stay inside
// lavapipe's loop cap (65535 iterations an invocation, shared/docs/
// gpu-notes.md), which one invocation looping over them all would pass,
// and the passes add up to the CPU's mean.
TEST(GpuPathIntegrator, ManySamplesAddUpToTheCpusMean) {
  Scene scene = Scene::load(source_dir() + "/examples/lights/cornell_box.nff");
  scene.add_lights(source_dir() + "/examples/lights/cornell_box.toml");
  RenderOptions o;
  o.spp = 256;
  o.max_depth = 8;
  EXPECT_GE(both_devices(scene, view(12, 12), o), kAgree);
}

// A path-traced shot on the GPU: each frame as the CPU traces it, its
// emitters where that frame's transforms put them.
TEST(GpuPathIntegrator, AnimatedFramesMatchTheCpu) {
  TempDir dir;
  const std::string scene = source_dir() + "/tests/data/pinhole/spheres.nff";
  write_text(dir.file("shot.toml"), "frames = 2\nspp = 4\n[[object]]\nscene = \"" + scene +
                                        "\"\n[[object.key]]\nframe = 0\ntranslate = [0, 0, 0]\n[[object.key]]\nframe = 1\n"
                                        "translate = [0.3, 0, 0]\n");
  const std::string common = " --camera pinhole --resolution 40x30 --integrator path --environment-colour 0.3,0.4,0.5 --format exr -q";
  for (const char* device : {"cpu", "gpu"}) {
    const auto run = run_cli("animate " + dir.file("shot.toml") + common + " --device " + device + " -o " + dir.file(device));
    ASSERT_EQ(run.status, 0) << run.output;
  }
  int frames = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir.file("cpu"))) {
    const std::string name = entry.path().filename().string();
    if (entry.path().extension() != ".exr") continue;
    ++frames;
    EXPECT_GE(api::compare_images(api::read_image(entry.path().string()), api::read_image(dir.file("gpu") + "/" + name)).psnr(),
              kAgree)
        << name;
  }
  EXPECT_EQ(frames, 2);
}

}  // namespace
}  // namespace holoray::test
