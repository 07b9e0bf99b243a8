// The command line end to end: outputs, messages and exit statuses.
#include <gtest/gtest.h>
#include <fmt/format.h>

#include <cstring>
#include <filesystem>

#include "image/image_io.hpp"
#include "test_util.hpp"

using namespace holoray;
namespace fs = std::filesystem;

namespace {
const char* kScene =
    "v from 0 0 10 at 0 0 0 up 0 1 0 angle 30\n"
    "b 0.2 0.3 0.4\nl 5 5 10\nf 1 0.5 0.2 0.8 0.2 20 0 1\ns 0 0 0 1.5\n";
}

TEST(Cli, RendersPngWithAovsAndReportsRays) {
  test::TempDir dir;
  test::write_text(dir.file("s.nff"), kScene);
  const auto r = test::run_cli("render " + dir.file("s.nff") + " -o " + dir.file("eia.png") +
                               " --lenses 16x12 --pixels-per-lens 5 --aov albedo,depth,normal,id");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("EIA        80x60 px, square grid, 16x12 lenses x 5 px, orthoscopic"), std::string::npos) << r.output;
  // Eye rays are cast only for pixel lines that cross the scene's bounds.
  const auto at = r.output.find("rays       eye ");
  ASSERT_NE(at, std::string::npos) << r.output;
  const long eye = std::stol(r.output.substr(at + 15));
  EXPECT_GT(eye, 0);
  EXPECT_LE(eye, 80 * 60);
  for (const char* f : {"eia.png", "eia.albedo.png", "eia.depth.exr", "eia.normal.exr", "eia.id.exr"})
    EXPECT_TRUE(fs::exists(dir.file(f))) << f;
  const ImageBuffer id = read_image(dir.file("eia.id.exr"));
  EXPECT_EQ(id.channels, 1);
  EXPECT_EQ(id.width, 80);
  // The centre pixel of the centre lens looks straight at the sphere.
  EXPECT_EQ(*id.at(8 * 5 + 2, 6 * 5 + 2), 0.0f);
  EXPECT_EQ(*id.at(0, 0), -1.0f);
}

// --exr-compression reaches the image and every AOV file, and changes no value.
TEST(Cli, ExrCompressionAppliesToTheImageAndItsAovsAndKeepsTheirValues) {
  test::TempDir dir;
  test::write_text(dir.file("s.nff"), kScene);
  const std::string base = "render " + dir.file("s.nff") + " --lenses 16x12 --pixels-per-lens 5 --aov albedo,depth,normal,id -q";
  ASSERT_EQ(test::run_cli(base + " -o " + dir.file("zip.exr")).status, 0);
  const auto r = test::run_cli(base + " --exr-compression none -o " + dir.file("none.exr"));
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* plane : {"", ".albedo", ".depth", ".normal", ".id"}) {
    const std::string none = dir.file(std::string("none") + plane + ".exr"), zip = dir.file(std::string("zip") + plane + ".exr");
    const auto info = test::run_shell("oiiotool --info -v '" + none + "'");
    EXPECT_NE(info.output.find("compression: \"none\""), std::string::npos) << plane << info.output;
    const ImageBuffer a = read_image(none), b = read_image(zip);
    ASSERT_EQ(a.data.size(), b.data.size()) << plane;
    EXPECT_EQ(std::memcmp(a.data.data(), b.data.data(), a.data.size() * sizeof(float)), 0) << plane;
    EXPECT_LT(fs::file_size(zip), fs::file_size(none)) << plane;
  }
}

TEST(Cli, MalformedSceneGivesFileLineColAndNoOutput) {
  test::TempDir dir;
  test::write_text(dir.file("bad.nff"), "s 0 0 0 1\nf 1 1 oops 1 0 0 0 0\n");
  const auto r = test::run_cli("render " + dir.file("bad.nff") + " -o " + dir.file("o.png"));
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.output, dir.file("bad.nff") + ":2:7: error: expected a fill colour component, found 'oops'\n"
                                            "  f 1 1 oops 1 0 0 0 0\n"
                                            "        ^\n");
  EXPECT_FALSE(fs::exists(dir.file("o.png")));
}

TEST(Cli, RefusesNonsenseCameraParameters) {
  test::TempDir dir;
  test::write_text(dir.file("s.nff"), kScene);
  const std::string base = "render " + dir.file("s.nff") + " -o " + dir.file("o.png") + " ";
  // Values CLI11 checks are usage errors (status 2); the rules between them, 1.
  const std::tuple<std::string, std::string, int> cases[] = {
      {"--gap 0", "holoray: error: gap must be positive and finite, got 0\n", 1},
      {"--pitch -1", "holoray: error: lens pitch must be positive and finite, got -1\n", 1},
      {"--fov-lens 180", "holoray: error: lens field of view must be between 0 and 180 degrees, got 180\n", 1},
      {"--lenses 0x10", "holoray: error: --lenses: lens counts must be at least 1, got '0x10'\n", 2},
      {"--lenses 10by10", "holoray: error: --lenses: expected NXxNY (e.g. 64x64), got '10by10'\n", 2},
      {"--pixels-per-lens 0", "holoray: error: --pixels-per-lens: must be at least 1, got 0\n", 2},
      {"--grid triangle", "holoray: error: --grid: expected square, hex or lenticular, got 'triangle'\n", 2},
      {"--aov albedo,motion", "holoray: error: --aov: unknown AOV 'motion' (expected albedo, depth, normal, id)\n", 2},
      {"--origin 0,0 --normal 0,0,1 --up 0,1,0 --pitch 1",
       "holoray: error: --origin: expected X,Y,Z (three finite numbers), got '0,0'\n", 2},
      {"--origin 0,0,0 --up 0,1,0 --pitch 1", "holoray: error: --origin requires --normal\n", 2},
      {"--view-cone 30", "holoray: error: --view-cone requires --quilt\n", 2},
      {"--lenses 100000x100000 --pixels-per-lens 64",
       // 6400000^2 px * (12 B colour + 12 B output copy) = 915527.34 GiB
       "holoray: error: a 6400000x6400000 image needs 915527.34 GiB of buffers, more than 80% of this machine's ", 1},
  };
  for (const auto& [args, message, status] : cases) {
    const auto r = test::run_cli(base + args);
    EXPECT_EQ(r.status, status) << args;
    EXPECT_EQ(r.output.substr(0, message.size()), message) << args;
    EXPECT_FALSE(fs::exists(dir.file("o.png"))) << args;
  }
}

TEST(Cli, UnsupportedOutputAndMissingFolderAreRefusedBeforeRendering) {
  test::TempDir dir;
  test::write_text(dir.file("s.nff"), kScene);
  const std::string usage = "Run with --help for more information.\n";
  auto r = test::run_cli("render " + dir.file("s.nff") + " -o " + dir.file("o.jpg"));
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.output, "holoray: error: --output: unsupported output '" + dir.file("o.jpg") + "' (use .png or .exr)\n" + usage);
  r = test::run_cli("render " + dir.file("s.nff") + " -o " + dir.file("nowhere/o.png"));
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.output, "holoray: error: --output: folder '" + dir.file("nowhere") + "' does not exist\n" + usage);
}

// --encoding auto (the default): a mesh scene's PNG is sRGB-encoded, an
// NFF scene's linear; the codes prove which: the sRGB code of a linear
// value v < 1 is above 255 v.
TEST(Cli, EncodingAutoIsSrgbForMeshScenesAndLinearForNff) {
  test::TempDir dir;
  test::write_text(dir.file("s.nff"), kScene);
  test::write_text(dir.file("m.obj"), "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n");
  auto codes = [&](const std::string& scene, const std::string& encoding) {
    const std::string out = dir.file(fs::path(scene).stem().string() + encoding + ".png");
    const auto r = test::run_cli(fmt::format("render {} --lenses 8x8 --pixels-per-lens 4 -q{} -o {}", dir.file(scene),
                                             encoding.empty() ? "" : " --encoding " + encoding, out));
    EXPECT_EQ(r.status, 0) << r.output;
    return read_image(out).data;
  };
  EXPECT_EQ(codes("m.obj", ""), codes("m.obj", "srgb"));
  EXPECT_NE(codes("m.obj", ""), codes("m.obj", "linear"));
  EXPECT_EQ(codes("s.nff", ""), codes("s.nff", "linear"));
  EXPECT_NE(codes("s.nff", ""), codes("s.nff", "srgb"));
  const auto r = test::run_cli("render " + dir.file("s.nff") + " --encoding gamma -o " + dir.file("o.png"));
  EXPECT_EQ(r.output, "holoray: error: --encoding: expected auto, linear or srgb, got 'gamma'\n"
                      "Run with --help for more information.\n");
}

TEST(Cli, SubapertureRefusesUnknownGridAndEncoding) {
  test::TempDir dir;
  write_image(dir.file("e.png"), ImageBuffer(8, 8, 3));
  auto r = test::run_cli("subaperture " + dir.file("e.png") + " --pixels-per-lens 4 --encoding gamma -o " + dir.file("v.png"));
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.output, "holoray: error: --encoding: expected linear or srgb, got 'gamma'\n");
  r = test::run_cli("subaperture " + dir.file("e.png") + " --pixels-per-lens 4 --grid round -o " + dir.file("v.png"));
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.output, "holoray: error: --grid: expected square, hex or lenticular, got 'round'\n");
  EXPECT_FALSE(fs::exists(dir.file("v.png")));
}

TEST(Cli, MissingSceneAndUnknownOptions) {
  test::TempDir dir;
  auto r = test::run_cli("render " + dir.file("none.nff") + " -o " + dir.file("o.png"));
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.output, "holoray: error: scene: cannot read '" + dir.file("none.nff") + "': no such file\n"
                      "Run with --help for more information.\n");
  test::write_text(dir.file("s.nff"), kScene);
  r = test::run_cli("render " + dir.file("s.nff") + " -o " + dir.file("o.png") + " --frobnicate");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("--frobnicate"), std::string::npos) << r.output;
}

TEST(Cli, SubapertureOfASquareEiaIsOnePixelPerLens) {
  test::TempDir dir;
  test::write_text(dir.file("s.nff"), kScene);
  ASSERT_EQ(test::run_cli("render " + dir.file("s.nff") + " -o " + dir.file("e.exr") + " --lenses 20x10 --pixels-per-lens 4 -q").status, 0);
  const auto r = test::run_cli("subaperture " + dir.file("e.exr") + " --pixels-per-lens 4 --u 1 --v 3 -o " + dir.file("v.exr"));
  ASSERT_EQ(r.status, 0) << r.output;
  const ImageBuffer eia = read_image(dir.file("e.exr")), view = read_image(dir.file("v.exr"));
  ASSERT_EQ(view.width, 20);
  ASSERT_EQ(view.height, 10);
  for (int ly = 0; ly < 10; ++ly)
    for (int lx = 0; lx < 20; ++lx)
      for (int c = 0; c < 3; ++c) ASSERT_EQ(view.at(lx, ly)[c], eia.at(lx * 4 + 1, ly * 4 + 3)[c]);
}

// Done-when of issue 2: every shipped NFF renders at 64x64 lenses x 8 px in
// both modes and all three grids, with no error.
TEST(CliScenes, EveryShippedSceneRendersInEveryGridAndMode) {
  if (!test::have_shared_scenes()) GTEST_SKIP() << "no ../shared/scenes";
  test::TempDir dir;
  for (const auto& entry : fs::directory_iterator(test::shared_dir() + "/scenes/nff")) {
    for (const char* grid : {"square", "hex", "lenticular"})
      for (const char* mode : {"orthoscopic", "pseudoscopic"}) {
        const auto r = test::run_cli("render " + entry.path().string() + " -o " + dir.file("o.png") +
                                     " --lenses 64x64 --pixels-per-lens 8 -q --grid " + grid + " --mode " + mode);
        EXPECT_EQ(r.status, 0) << entry.path() << " " << grid << " " << mode << "\n" << r.output;
        EXPECT_EQ(r.output, "");
      }
  }
}

// Built without MPI, holoray refuses to run as one of several MPI ranks
// (each would render the same frames into the same files) and writes
// nothing; as the only rank it runs (issue 15, item 5).
TEST(Cli, RefusesToRunAsOneOfSeveralMpiRanksWithoutMpi) {
#ifdef HOLORAY_TESTS_WITH_MPI
  GTEST_SKIP() << "this build has MPI; the sanitizer builds, built without it, run this test";
#endif
  test::TempDir dir;
  test::write_text(dir.file("s.nff"), kScene);
  const std::string render = std::string(HOLORAY_CLI) + " render " + dir.file("s.nff") + " --lenses 4x4 -q -o ";
  const auto r = test::run_shell("OMPI_COMM_WORLD_SIZE=3 " + render + dir.file("a.png"));
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("holoray: error: launched as one of 3 MPI processes, but this holoray is built without MPI"),
            std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(dir.file("a.png")));
  const auto slurm = test::run_shell("PMI_SIZE=2 " + render + dir.file("b.png"));
  EXPECT_EQ(slurm.status, 1) << slurm.output;
  const auto alone = test::run_shell("OMPI_COMM_WORLD_SIZE=1 " + render + dir.file("c.png"));
  EXPECT_EQ(alone.status, 0) << alone.output;
  EXPECT_TRUE(fs::exists(dir.file("c.png")));
}
