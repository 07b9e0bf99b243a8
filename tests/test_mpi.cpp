// Scale-out over MPI (issue 15), through `mpirun --oversubscribe -np N
// holoray`: on loopback, N ranks write byte for byte the files of one
// process; frame ranges run apart give the same folder; a killed rank or a
// SIGTERM on mpirun loses at most the frames in flight and --resume
// completes the same folder; errors are printed once and name the file.
#include <signal.h>

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "api/gpu_executor.hpp"
#include "image/image_io.hpp"
#include "test_util.hpp"

namespace holoray {
namespace {

using test::TempDir;
namespace fs = std::filesystem;

// Containers run tests as root, which mpirun refuses unless told.
struct MpiEnvironment {
  MpiEnvironment() {
    ::setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 1);
    ::setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 1);
  }
};
const MpiEnvironment mpi_environment;

std::vector<std::string> mpirun(int ranks, const std::vector<std::string>& args) {
  std::vector<std::string> a{MPIEXEC, "--oversubscribe", "--bind-to", "none", "-np", std::to_string(ranks), HOLORAY_CLI};
  a.insert(a.end(), args.begin(), args.end());
  return a;
}

std::vector<std::string> one_process(const std::vector<std::string>& args) {
  std::vector<std::string> a{HOLORAY_CLI};
  a.insert(a.end(), args.begin(), args.end());
  return a;
}

int run(const std::vector<std::string>& argv, const std::string& log) { return test::wait_exit(test::spawn(argv, log)); }

const char* kScene =
    "v\nfrom 0 -10 2\nat 0 0 0\nup 0 0 1\nangle 40\nhither 1\nresolution 64 64\n"
    "l 5 -6 10\nl -5 -6 8\nf 0.9 0.3 0.2 1 0 0 0 0\ns 0 0 0 1\nf 0.8 0.8 0.8 0.4 0.5 20 0 0\n"
    "s 1.5 0.5 0.3 0.6\ns -1.4 0.8 -0.2 0.7\np 4\n-4 -4 -1\n4 -4 -1\n4 4 -1\n-4 4 -1\n";

// `frames` frames of a camera move at lenses x 8 px.
void write_shot(const TempDir& dir, int frames, int lenses) {
  test::write_text(dir.file("scene.nff"), kScene);
  test::write_text(dir.file("shot.toml"),
                   "frames = " + std::to_string(frames) + "\n[array]\nlenses = " + std::to_string(lenses) +
                       "\npixels_per_lens = 8\n[camera]\n"
                       "[[camera.key]]\nframe = 0\nfrom = [0, -10, 2]\nat = [0, 0, 0]\nup = [0, 0, 1]\n"
                       "[[camera.key]]\nframe = " + std::to_string(frames - 1) +
                       "\nfrom = [1, -10, 2]\nat = [0.5, 0, 0]\nup = [0, 0, 1]\n[[object]]\nscene = \"scene.nff\"\n");
}

std::vector<std::string> animate(const TempDir& dir, const std::string& out, const std::string& method,
                                 std::vector<std::string> extra = {}) {
  std::vector<std::string> a{"animate", dir.file("shot.toml"), "-o", out, "--method", method, "--keyframe-interval", "4",
                             "--threads", "1", "-q"};
  a.insert(a.end(), extra.begin(), extra.end());
  return a;
}

// Done when: a 24-frame shot with reprojection, three ranks against one
// process; the paper's forward reprojection and the reverse one.
TEST(MpiAnimate, ThreeRanksWriteTheFolderOfOneProcess) {
  TempDir dir;
  write_shot(dir, 24, 32);
  for (const std::string method : {"reproject", "reverse"}) {
    const std::string one = dir.file("one_" + method), three = dir.file("three_" + method);
    ASSERT_EQ(run(one_process(animate(dir, one, method)), dir.file("log1")), 0) << test::read_bytes(dir.file("log1"));
    ASSERT_EQ(run(mpirun(3, animate(dir, three, method)), dir.file("log3")), 0) << test::read_bytes(dir.file("log3"));
    EXPECT_EQ(test::frame_count(three), 24u);
    EXPECT_EQ(test::folder_bytes(three), test::folder_bytes(one)) << method;
  }
}

// The per-frame table of a report (the paper's Table 1) without its two
// timing columns, which differ from run to run.
std::vector<std::string> quality_rows(const std::string& report) {
  std::vector<std::string> rows;
  std::istringstream in(test::read_bytes(report));
  bool table = false;
  for (std::string line; std::getline(in, line);) {
    if (line.starts_with("## Per frame")) table = true;
    if (!table || !line.starts_with("| ") || line.starts_with("| frame")) continue;
    for (int cut = 0; cut < 3; ++cut) line = line.substr(0, line.find_last_of('|'));
    rows.push_back(line);
  }
  return rows;
}

// --report under mpirun: every rank's frames, gathered on rank 0 in frame
// order, with the quality and pixel counts of one process's report.
TEST(MpiAnimate, ReportHoldsEveryFrameInOrderAsOneProcessMeasuresThem) {
  TempDir dir;
  write_shot(dir, 24, 32);
  ASSERT_EQ(run(one_process(animate(dir, dir.file("one"), "reverse", {"--report", dir.file("one.md")})), dir.file("log")), 0);
  ASSERT_EQ(run(mpirun(3, animate(dir, dir.file("three"), "reverse", {"--report", dir.file("three.md")})), dir.file("log")), 0)
      << test::read_bytes(dir.file("log"));
  const auto one = quality_rows(dir.file("one.md")), three = quality_rows(dir.file("three.md"));
  ASSERT_EQ(one.size(), 24u);
  EXPECT_EQ(three, one);
  EXPECT_NE(test::read_bytes(dir.file("three.md")).find("- command: `mpirun -np 3 holoray animate"), std::string::npos);
}

// Done when: ranges 0:7, 8:15 and 16:23 in three separate runs (the middle
// one itself over two ranks) give the folder of one run.
TEST(MpiAnimate, FrameRangesRunApartGiveTheFolderOfOneRun) {
  TempDir dir;
  write_shot(dir, 24, 32);
  ASSERT_EQ(run(one_process(animate(dir, dir.file("whole"), "reproject")), dir.file("log")), 0);
  ASSERT_EQ(run(one_process(animate(dir, dir.file("parts"), "reproject", {"--frames", "0:7"})), dir.file("log")), 0);
  ASSERT_EQ(run(mpirun(2, animate(dir, dir.file("parts"), "reproject", {"--frames", "8:15"})), dir.file("log")), 0)
      << test::read_bytes(dir.file("log"));
  EXPECT_EQ(test::frame_count(dir.file("parts")), 16u);
  ASSERT_EQ(run(one_process(animate(dir, dir.file("parts"), "reproject", {"--frames", "16:23"})), dir.file("log")), 0);
  EXPECT_EQ(test::folder_bytes(dir.file("parts")), test::folder_bytes(dir.file("whole")));
}

// The program users run links no MPI (its libraries cost every command
// start-up time); under mpirun it becomes holoray-mpi, which does, and which
// the tests above run through it.
TEST(MpiProgram, HolorayLinksNoMpiAndNamesTheProgramThatDoes) {
  const auto ldd = test::run_shell(std::string("ldd ") + HOLORAY_CLI);
  ASSERT_EQ(ldd.status, 0) << ldd.output;
  EXPECT_EQ(ldd.output.find("libmpi"), std::string::npos) << ldd.output;
  const auto version = test::run_cli("--version");
  EXPECT_NE(version.output.find("built with: MPI yes (holoray-mpi, under mpirun)"), std::string::npos)
      << version.output;
  const auto mpi_ldd = test::run_shell("ldd " + (fs::path(HOLORAY_CLI).parent_path() / "holoray-mpi").string());
  EXPECT_NE(mpi_ldd.output.find("libmpi"), std::string::npos) << mpi_ldd.output;
}

// Done when: a still over three ranks, square, hex and lenticular, colour
// and every AOV, bit for bit one process's pixels (NaN depth included).
TEST(MpiRender, ThreeRanksWriteTheStillOfOneProcess) {
  TempDir dir;
  test::write_text(dir.file("scene.nff"), kScene);
  // The shadow cache too: each rank classifies the cells its bands reach,
  // from the cells' fixed samples, so the pixels cannot depend on the split.
  for (const std::string grid : {"square", "hex", "lenticular", "square --cache on"}) {
    auto args = [&](const std::string& out) {
      std::vector<std::string> a{"render", dir.file("scene.nff"), "-o", out, "--lenses", "30", "--pixels-per-lens", "9",
                                 "--aov", "albedo,depth,normal,id", "--threads", "1", "-q", "--grid"};
      std::istringstream words(grid);
      for (std::string w; words >> w;) a.push_back(w);
      return a;
    };
    ASSERT_EQ(run(one_process(args(dir.file("one.exr"))), dir.file("log")), 0) << test::read_bytes(dir.file("log"));
    ASSERT_EQ(run(mpirun(3, args(dir.file("three.exr"))), dir.file("log")), 0) << test::read_bytes(dir.file("log"));
    // Pixels, not bytes: an EXR header carries the time it was written.
    for (const std::string aov : {"", ".albedo", ".depth", ".normal", ".id"}) {
      const ImageBuffer a = read_image(dir.file("one" + aov + ".exr")), b = read_image(dir.file("three" + aov + ".exr"));
      EXPECT_EQ(a.width, b.width);
      EXPECT_EQ(a.channels, b.channels);
      EXPECT_TRUE(std::memcmp(a.data.data(), b.data.data(), a.data.size() * sizeof(float)) == 0 && a.data.size() == b.data.size())
          << grid << aov;
    }
  }
}

// --device gpu over two ranks: each rank takes a device (lavapipe here, the
// machine's GPUs in turn where it has several) and renders its bands there;
// the still is one GPU process's, bit for bit (a pixel's rays do not depend
// on the band it is in), and an animation's frames likewise.
TEST(MpiRender, TwoRanksOnTheGpuWriteWhatOneProcessWrites) {
  TempDir dir;
  test::write_text(dir.file("scene.nff"), kScene);
  auto args = [&](const std::string& out) {
    return std::vector<std::string>{"render", dir.file("scene.nff"), "-o", out, "--lenses", "20", "--pixels-per-lens", "8",
                                    "--device", "gpu", "-q"};
  };
  ASSERT_EQ(run(one_process(args(dir.file("one.exr"))), dir.file("log")), 0) << test::read_bytes(dir.file("log"));
  ASSERT_EQ(run(mpirun(2, args(dir.file("two.exr"))), dir.file("log")), 0) << test::read_bytes(dir.file("log"));
  const ImageBuffer a = read_image(dir.file("one.exr")), b = read_image(dir.file("two.exr"));
  ASSERT_EQ(a.data.size(), b.data.size());
  EXPECT_TRUE(std::memcmp(a.data.data(), b.data.data(), a.data.size() * sizeof(float)) == 0);
  write_shot(dir, 4, 12);
  ASSERT_EQ(run(one_process(animate(dir, dir.file("one"), "full", {"--device", "gpu"})), dir.file("log")), 0)
      << test::read_bytes(dir.file("log"));
  ASSERT_EQ(run(mpirun(2, animate(dir, dir.file("two"), "full", {"--device", "gpu"})), dir.file("log")), 0)
      << test::read_bytes(dir.file("log"));
  EXPECT_EQ(test::folder_bytes(dir.file("one")), test::folder_bytes(dir.file("two")));
  EXPECT_EQ(test::folder_bytes(dir.file("one")).size(), 4u);
}

// The local rank's device: the machine's GPUs in turn, the first device
// where there is no GPU.
TEST(MpiRender, EachLocalRankTakesTheNextGpu) {
  EXPECT_EQ(api::gpu_of_local_rank({false, true, true}, 0), 1);
  EXPECT_EQ(api::gpu_of_local_rank({false, true, true}, 1), 2);
  EXPECT_EQ(api::gpu_of_local_rank({false, true, true}, 2), 1);
  EXPECT_EQ(api::gpu_of_local_rank({true, false, true, true}, 5), 3);  // GPUs 0, 2, 3: the third
  EXPECT_EQ(api::gpu_of_local_rank({false}, 3), -1);
  EXPECT_EQ(api::device_of_local_rank("cpu", 3), "cpu");
  EXPECT_EQ(api::device_of_local_rank("gpu:7", 3), "gpu:7");
}

// The shipped Slurm scripts (examples/cluster/), run outside Slurm as a
// batch would run them: the MPI one with mpirun's default ranks (this
// machine's cores), the job array's tasks one after another; each gives the
// folder of one process.
TEST(ClusterExamples, SlurmScriptsGiveTheFolderOfOneProcess) {
  TempDir dir;
  write_shot(dir, 24, 16);
  ASSERT_EQ(run(one_process({"animate", dir.file("shot.toml"), "-o", dir.file("one"), "-q"}), dir.file("log")), 0);
  const std::string bin_dir = fs::path(HOLORAY_CLI).parent_path().string();
  const std::string env = "PATH=" + bin_dir + ":$PATH ";
  const std::string examples = test::source_dir() + "/examples/cluster/";
  const auto mpi = test::run_shell(env + "bash " + examples + "animate_mpi.sbatch " + dir.file("shot.toml") + " " +
                                   dir.file("mpi") + " > /dev/null");
  ASSERT_EQ(mpi.status, 0) << mpi.output;
  EXPECT_EQ(test::folder_bytes(dir.file("mpi")), test::folder_bytes(dir.file("one")));
  for (int task = 0; task < 3; ++task) {
    const auto r = test::run_shell(env + "SLURM_ARRAY_TASK_ID=" + std::to_string(task) + " bash " + examples +
                                   "frames_array.sbatch " + dir.file("shot.toml") + " " + dir.file("array") + " 8 > /dev/null");
    ASSERT_EQ(r.status, 0) << r.output;
  }
  EXPECT_EQ(test::folder_bytes(dir.file("array")), test::folder_bytes(dir.file("one")));
}

// Every other camera splits the same way, in bands of 32 rows: a pinhole
// view, a quilt and a slanted-lenticular panel with RGB subpixels.
TEST(MpiRender, ViewsQuiltsAndPanelsOverThreeRanksAreOneProcessesPixels) {
  TempDir dir;
  test::write_text(dir.file("scene.nff"), kScene);
  test::write_text(dir.file("panel.toml"),
                   "name = \"small slanted lenticular\"\n[panel]\nresolution = [200, 150]\npixel_pitch_mm = 0.0897\n"
                   "subpixels = \"rgb\"\n[lens]\ngrid = \"lenticular\"\npitch_mm = 0.398158\nslant_deg = 9.4623\n"
                   "focal_length_mm = 1.2\n");
  const std::vector<std::vector<std::string>> cases{{"--camera", "pinhole", "--resolution", "90x70", "--aov", "depth"},
                                                     {"--quilt", "3x2", "--resolution", "40x30"},
                                                     {"--display", dir.file("panel.toml")}};
  for (const auto& c : cases) {
    for (const std::string who : {"one", "three"}) {
      fs::create_directories(dir.file(who));
      std::vector<std::string> args{"render", dir.file("scene.nff"), "-o", dir.file(who + "/out.png"), "--threads", "1", "-q"};
      args.insert(args.end(), c.begin(), c.end());
      ASSERT_EQ(run(who == "one" ? one_process(args) : mpirun(3, args), dir.file("log")), 0)
          << c[0] << "\n" << test::read_bytes(dir.file("log"));
    }
    // Every file (a quilt's name carries its layout; the pinhole's depth AOV).
    const auto one = test::folder_bytes(dir.file("one")), three = test::folder_bytes(dir.file("three"));
    ASSERT_EQ(three.size(), one.size()) << c[0];
    for (const auto& [name, bytes] : one) {
      const ImageBuffer a = read_image(dir.file("one/" + name)), b = read_image(dir.file("three/" + name));
      EXPECT_GT(a.width, 0) << name;
      EXPECT_TRUE(a.data.size() == b.data.size() &&
                  std::memcmp(a.data.data(), b.data.data(), a.data.size() * sizeof(float)) == 0)
          << c[0] << " " << name;
    }
    fs::remove_all(dir.file("one"));
    fs::remove_all(dir.file("three"));
  }
}

// The ranks mpirun started (its children), for the fault tests.
std::vector<pid_t> ranks_of(pid_t mpirun_pid) {
  const auto r = test::run_shell("pgrep -P " + std::to_string(mpirun_pid));
  std::vector<pid_t> pids;
  size_t at = 0;
  while (at < r.output.size()) {
    const size_t end = r.output.find('\n', at);
    const std::string line = r.output.substr(at, end == std::string::npos ? std::string::npos : end - at);
    if (!line.empty()) pids.push_back(static_cast<pid_t>(std::stol(line)));
    if (end == std::string::npos) break;
    at = end + 1;
  }
  return pids;
}

bool alive(pid_t pid) { return ::kill(pid, 0) == 0; }

struct Fault {
  const char* name;
  bool kill_one_rank;  // SIGKILL one rank; else SIGTERM to mpirun
};

class MpiFault : public ::testing::TestWithParam<Fault> {};

// Done when: one rank killed mid-run (or SIGTERM on mpirun) leaves only
// complete frames, no rank left running, and --resume over three ranks
// completes the folder of one uninterrupted process.
TEST_P(MpiFault, LosesOnlyFramesInFlightAndResumeCompletesTheSameFolder) {
  TempDir dir;
  // Long enough to outlast mpirun's delay in passing SIGTERM on (about 1 s):
  // 60 frames ran out in 1.6 s here, ending before the signal arrived.
  constexpr unsigned kFrames = 150;
  write_shot(dir, kFrames, 96);
  const std::string out = dir.file("cut");
  ASSERT_EQ(run(one_process(animate(dir, dir.file("whole"), "reverse")), dir.file("log")), 0);
  const pid_t pid = test::spawn(mpirun(3, animate(dir, out, "reverse")), dir.file("log_cut"));
  ASSERT_GT(pid, 0);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (test::frame_count(out) < 6 && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  const std::vector<pid_t> ranks = ranks_of(pid);
  ASSERT_EQ(ranks.size(), 3u) << "mpirun's children";
  if (GetParam().kill_one_rank) ::kill(ranks.back(), SIGKILL);
  else ::kill(pid, SIGTERM);
  const int status = test::wait_exit(pid);
  EXPECT_NE(status, 0) << test::read_bytes(dir.file("log_cut"));
  ASSERT_LT(test::frame_count(out), kFrames) << "the run ended before the fault; the test needs a longer shot";
  for (int i = 0; i < 500 && (alive(ranks[0]) || alive(ranks[1]) || alive(ranks[2])); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  for (pid_t r : ranks) EXPECT_FALSE(alive(r)) << "rank " << r << " outlived mpirun";
  // Every frame there is whole: each equals the uninterrupted run's.
  const auto whole = test::folder_bytes(dir.file("whole"));
  for (const auto& [name, bytes] : test::folder_bytes(out))
    if (name.starts_with("frame_")) EXPECT_EQ(bytes, whole.at(name)) << name;
  ASSERT_EQ(run(mpirun(3, animate(dir, out, "reverse", {"--resume"})), dir.file("log_resume")), 0)
      << test::read_bytes(dir.file("log_resume"));
  EXPECT_EQ(test::folder_bytes(out), whole);
}

INSTANTIATE_TEST_SUITE_P(Faults, MpiFault,
                         ::testing::Values(Fault{"sigkill_one_rank", true}, Fault{"sigterm_mpirun", false}),
                         [](const auto& info) { return std::string(info.param.name); });

// A setup error is the same on every rank: printed once, not three times.
TEST(MpiErrors, ASetupErrorIsPrintedOnceAndAWriteErrorNamesTheFile) {
  TempDir dir;
  write_shot(dir, 24, 16);
  ASSERT_EQ(run(mpirun(3, {"render", dir.file("missing.nff"), "-o", dir.file("a.png")}), dir.file("log")), 2);
  const std::string log = test::read_bytes(dir.file("log"));
  const std::string message = "holoray: error: scene: cannot read '" + dir.file("missing.nff") + "'";
  ASSERT_NE(log.find(message), std::string::npos) << log;
  EXPECT_EQ(log.find(message, log.find(message) + 1), std::string::npos) << "printed more than once:\n" << log;
  // A still too large for this machine: each rank would hold its own bands
  // (rank 0 one more), so the refusal counts rank 0's share, not the whole.
  ASSERT_EQ(run(mpirun(4, {"render", dir.file("scene.nff"), "-o", dir.file("big.png"), "--lenses", "200000",
                           "--pixels-per-lens", "10"}),
                dir.file("log")),
            1);
  const std::string big = test::read_bytes(dir.file("log"));
  EXPECT_NE(big.find("holoray: error: a 2000000x2000000 image needs 16763.81 GiB of buffers on rank 0 of 4, more than 80% of"),
            std::string::npos)
      << big;
  // A frame's name taken by a folder: the rank that writes it stops the run.
  fs::create_directories(dir.file("out/frame_0013.png/x"));
  EXPECT_NE(run(mpirun(3, animate(dir, dir.file("out"), "reproject")), dir.file("log")), 0);
  const std::string write_log = test::read_bytes(dir.file("log"));
  EXPECT_NE(write_log.find("holoray: error: cannot write '" + dir.file("out/frame_0013.png") + "': Is a directory (rank "),
            std::string::npos)
      << write_log;
}

}  // namespace
}  // namespace holoray
