// Nothing lost (issue 5): a sequence stopped by SIGINT, SIGTERM or SIGKILL
// leaves only complete frames, and a resumed run ends with exactly the files
// of an uninterrupted one. Also: the same shot gives bit-identical frames for
// any thread count.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <map>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "test_util.hpp"

namespace holoray {
namespace {

using test::TempDir;
namespace fs = std::filesystem;

// 60 frames of a reflective scene at 256x256: long enough (about a second
// or more) to be caught in the middle.
void write_shot(const TempDir& dir) {
  test::write_text(dir.file("scene.nff"),
                   "v\nfrom 0 -10 2\nat 0 0 0\nup 0 0 1\nangle 40\nhither 1\nresolution 64 64\n"
                   "l 5 -6 10\nl -5 -6 8\nf 0.9 0.3 0.2 1 0 0 0 0\ns 0 0 0 1\nf 0.8 0.8 0.8 0.4 0.5 20 0 0\n"
                   "s 1.5 0.5 0.3 0.6\ns -1.4 0.8 -0.2 0.7\np 4\n-4 -4 -1\n4 -4 -1\n4 4 -1\n-4 4 -1\n");
  test::write_text(dir.file("shot.toml"), R"(
frames = 60
[array]
lenses = 32
pixels_per_lens = 8
[camera]
[[camera.key]]
frame = 0
from = [0, -10, 2]
at = [0, 0, 0]
up = [0, 0, 1]
[[camera.key]]
frame = 59
from = [1, -10, 2]
at = [0.5, 0, 0]
up = [0, 0, 1]
[[object]]
scene = "scene.nff"
)");
}

using test::folder_bytes;
using test::frame_count;

// Starts `holoray args...` with its output in `log`; returns the pid.
pid_t spawn_cli(const std::vector<std::string>& args, const std::string& log) {
  std::vector<std::string> argv{HOLORAY_CLI};
  argv.insert(argv.end(), args.begin(), args.end());
  return test::spawn(argv, log);
}

struct KillCase {
  int signal;
  const char* method;
};

class AnimateInterrupted : public ::testing::TestWithParam<KillCase> {};

TEST_P(AnimateInterrupted, LeavesOnlyCompleteFramesAndResumesToTheSameFiles) {
  const KillCase kc = GetParam();
  TempDir dir;
  write_shot(dir);
  const std::vector<std::string> common{"animate", dir.file("shot.toml"), "--method", kc.method, "--keyframe-interval", "4", "-q"};
  auto with_output = [&](const std::string& out, std::vector<std::string> extra = {}) {
    std::vector<std::string> a = common;
    a.push_back("-o");
    a.push_back(out);
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
  };
  auto run_to_end = [&](const std::vector<std::string>& args) {
    return test::wait_exit(spawn_cli(args, dir.file("log_end.txt")));
  };
  ASSERT_EQ(run_to_end(with_output(dir.file("whole"))), 0) << test::read_bytes(dir.file("log_end.txt"));
  const auto whole = folder_bytes(dir.file("whole"));
  ASSERT_EQ(whole.size(), 60u);

  const std::string out = dir.file("cut");
  const pid_t pid = spawn_cli(with_output(out), dir.file("log_cut.txt"));
  ASSERT_GT(pid, 0);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (frame_count(out) < 3 && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  ::kill(pid, kc.signal);
  int st = 0;
  waitpid(pid, &st, 0);
  const size_t present = frame_count(out);
  ASSERT_LT(present, 60u) << "the run ended before the signal; the test needs a longer shot";
  if (kc.signal == SIGKILL) {
    EXPECT_TRUE(WIFSIGNALED(st));
  } else {
    ASSERT_TRUE(WIFEXITED(st)) << test::read_bytes(dir.file("log_cut.txt"));
    EXPECT_EQ(WEXITSTATUS(st), 128 + kc.signal);
    EXPECT_NE(test::read_bytes(dir.file("log_cut.txt")).find("rerun with --resume"), std::string::npos);
  }
  // Every frame there is complete: byte for byte the uninterrupted run's.
  for (const auto& [name, bytes] : folder_bytes(out)) {
    if (kc.signal != SIGKILL || name.starts_with("frame_")) {
      ASSERT_TRUE(whole.count(name)) << "unexpected file " << name;
      EXPECT_EQ(bytes, whole.at(name)) << name << " is not complete";
    }
  }
  ASSERT_EQ(run_to_end(with_output(out, {"--resume"})), 0) << test::read_bytes(dir.file("log_end.txt"));
  EXPECT_EQ(folder_bytes(out), whole) << "a resumed run must leave exactly the uninterrupted run's files";
}

// With --video: a run stopped by SIGINT leaves its frames and no video (not
// even a temporary one); --resume finishes the frames and writes the video,
// byte for byte the uninterrupted run's.
TEST(AnimateInterruptedWithVideo, LeavesNoVideoAndTheResumedRunWritesTheSameOne) {
  TempDir dir;
  write_shot(dir);
  auto args = [&](const std::string& out, const std::string& video, bool resume) {
    std::vector<std::string> a{"animate", dir.file("shot.toml"), "--method", "full", "-q", "-o", out, "--video", video};
    if (resume) a.push_back("--resume");
    return a;
  };
  auto run_to_end = [&](const std::vector<std::string>& a) {
    return test::wait_exit(spawn_cli(a, dir.file("log_end.txt")));
  };
  ASSERT_EQ(run_to_end(args(dir.file("whole"), dir.file("whole.mkv"), false)), 0) << test::read_bytes(dir.file("log_end.txt"));
  fs::create_directories(dir.file("videos"));
  const pid_t pid = spawn_cli(args(dir.file("cut"), dir.file("videos/cut.mkv"), false), dir.file("log_cut.txt"));
  ASSERT_GT(pid, 0);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (frame_count(dir.file("cut")) < 3 && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  ::kill(pid, SIGINT);
  test::wait_exit(pid);
  ASSERT_LT(frame_count(dir.file("cut")), 60u) << "the run ended before the signal; the test needs a longer shot";
  EXPECT_TRUE(fs::is_empty(dir.file("videos"))) << "an interrupted run left a video file";
  ASSERT_EQ(run_to_end(args(dir.file("cut"), dir.file("videos/cut.mkv"), true)), 0) << test::read_bytes(dir.file("log_end.txt"));
  EXPECT_EQ(test::read_bytes(dir.file("videos/cut.mkv")), test::read_bytes(dir.file("whole.mkv")));
}

// --frames for render farms (issue 15, item 3): ranges whose ends fall
// inside keyframe segments, two of them run at the same time into the same
// folder, give byte for byte the folder of one run; a range past the shot is
// refused.
TEST(AnimateFrames, RangesRunApartGiveTheFolderOfOneRun) {
  TempDir dir;
  write_shot(dir);
  auto args = [&](const std::string& out, const std::string& range) {
    std::vector<std::string> a{"animate", dir.file("shot.toml"), "--method", "reverse", "--keyframe-interval", "8", "-q", "-o", out};
    if (!range.empty()) a.insert(a.end(), {"--frames", range});
    return a;
  };
  ASSERT_EQ(test::wait_exit(spawn_cli(args(dir.file("whole"), ""), dir.file("log_whole.txt"))), 0) << test::read_bytes(dir.file("log_whole.txt"));
  const pid_t a = spawn_cli(args(dir.file("parts"), "0:21"), dir.file("log_a.txt"));
  const pid_t b = spawn_cli(args(dir.file("parts"), "22:45"), dir.file("log_b.txt"));
  ASSERT_EQ(test::wait_exit(a), 0) << test::read_bytes(dir.file("log_a.txt"));
  ASSERT_EQ(test::wait_exit(b), 0) << test::read_bytes(dir.file("log_b.txt"));
  EXPECT_EQ(frame_count(dir.file("parts")), 46u);
  ASSERT_EQ(test::wait_exit(spawn_cli(args(dir.file("parts"), "46:59"), dir.file("log_c.txt"))), 0) << test::read_bytes(dir.file("log_c.txt"));
  EXPECT_EQ(folder_bytes(dir.file("parts")), folder_bytes(dir.file("whole")));
  const auto r = test::run_cli("animate " + dir.file("shot.toml") + " -o " + dir.file("bad") + " --frames 50:60 -q");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("--frames: the shot has frames 0 to 59, got '50:60'"), std::string::npos) << r.output;
}

INSTANTIATE_TEST_SUITE_P(Signals, AnimateInterrupted,
                         ::testing::Values(KillCase{SIGINT, "reproject"}, KillCase{SIGTERM, "full"},
                                           KillCase{SIGKILL, "reverse"}),
                         [](const auto& info) {
                           const char* sig = info.param.signal == SIGINT    ? "sigint"
                                             : info.param.signal == SIGTERM ? "sigterm"
                                                                            : "sigkill";
                           return std::string(sig) + "_" + info.param.method;
                         });

TEST(AnimateDeterminism, SameFramesForAnyThreadCount) {
  TempDir dir;
  write_shot(dir);
  // Fewer frames: the property does not need sixty.
  std::string shot = test::read_bytes(dir.file("shot.toml"));
  shot.replace(shot.find("frames = 60"), 11, "frames = 9");
  shot.replace(shot.find("frame = 59"), 10, "frame = 8");
  test::write_text(dir.file("shot.toml"), shot);
  const std::pair<const char*, const char*> methods[] = {
      {"reproject", "color"}, {"reproject", "geometry"}, {"reverse", "color"}, {"reverse", "visibility"}};
  for (const auto& [method, reuse] : methods) {
    SCOPED_TRACE(std::string(method) + " " + reuse);
    std::map<std::string, std::string> first;
    for (const int threads : {1, 2, 5}) {
      const std::string out = dir.file(std::string(method) + reuse + std::to_string(threads));
      const auto r = test::run_cli("animate " + dir.file("shot.toml") + " -o " + out + " --keyframe-interval 4 --method " +
                                   method + " --reuse " + reuse + " --threads " + std::to_string(threads) + " -q");
      ASSERT_EQ(r.status, 0) << r.output;
      const auto files = folder_bytes(out);
      ASSERT_EQ(files.size(), 9u);
      if (first.empty()) first = files;
      else EXPECT_EQ(files, first) << threads << " threads";
    }
  }
}

}  // namespace
}  // namespace holoray
