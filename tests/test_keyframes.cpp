// Keyframes placed by motion (temporal/keyframe_schedule.hpp, issue 12,
// `--keyframe-interval auto`): the schedule's own promise over every frame,
// long intervals where nothing moves, short ones where the camera is fast,
// a keyframe on each side of a cut, and the CLI running with it.
#include <gtest/gtest.h>
#include <fmt/format.h>

#include <algorithm>
#include <string>

#include "shot/shot_frames.hpp"
#include "shot/shot_reader.hpp"
#include "temporal/keyframe_schedule.hpp"
#include "test_util.hpp"

namespace holoray {
namespace {

constexpr const char* kScene = "l 5 -6 10\nf 0.9 0.3 0.2 1 0 0 0 0\ns 0 0 0 1\ns 1.5 0.5 0.3 0.5\n"
                               "p 4\n-3 -3 -1\n3 -3 -1\n3 3 -1\n-3 3 -1\n";

// A shot of `frames` frames over kScene, its [camera] part given.
ShotFrames shot_with(test::TempDir& dir, int frames, const std::string& camera) {
  test::write_text(dir.file("s.nff"), kScene);
  test::write_text(dir.file("shot.toml"), fmt::format("frames = {}\n[array]\nlenses = 16\npixels_per_lens = 8\n{}\n"
                                                      "[[object]]\nscene = \"s.nff\"\n",
                                                      frames, camera));
  return ShotFrames(read_shot_file(dir.file("shot.toml")));
}

std::string key(int frame, double x) {
  return fmt::format("[[camera.key]]\nframe = {}\nfrom = [{}, -8, 3]\nat = [{}, 0, 0]\nup = [0, 0, 1]\n", frame, x, x);
}

TEST(KeyframeSchedule, EveryFrameIsWithinTheMotionOfItsKeyframeAndFastStretchesGetMoreKeys) {
  test::TempDir dir;
  // Eased: slow at both ends, fastest in the middle.
  const ShotFrames shot = shot_with(dir, 61, "[camera]\ninterpolation = \"smooth\"\n" + key(0, -2) + key(60, 2));
  const KeyframePlanner planner(shot);
  const double max_px = 3;
  const std::vector<int> keys = planner.keyframes(max_px, 40);
  ASSERT_GE(keys.size(), 4u);
  EXPECT_EQ(keys.front(), 0);
  EXPECT_EQ(keys.back(), 60);
  for (size_t k = 0; k + 1 < keys.size(); ++k) {
    ASSERT_LT(keys[k], keys[k + 1]);
    for (int g = keys[k] + 2; g <= keys[k + 1]; ++g)
      EXPECT_LE(planner.image_motion(keys[k], g), max_px) << "frame " << g << " from keyframe " << keys[k];
    // Greedy: one frame more would have gone past the bound (or the shot's end).
    if (keys[k + 1] < 60) EXPECT_GT(planner.image_motion(keys[k], keys[k + 1] + 1), max_px);
  }
  // The first interval (slow) is longer than the one around frame 30 (fast).
  const auto mid = std::upper_bound(keys.begin(), keys.end(), 30);
  EXPECT_GT(keys[1] - keys[0], *mid - *(mid - 1));
}

TEST(KeyframeSchedule, WhereNothingMovesKeyframesAreTheLongestIntervalApart) {
  test::TempDir dir;
  const ShotFrames shot = shot_with(dir, 41, "[camera]\n" + key(0, 0));
  const KeyframePlanner planner(shot);
  EXPECT_EQ(planner.image_motion(0, 40), 0);
  EXPECT_EQ(planner.keyframes(1, 16), (std::vector<int>{0, 16, 32, 40}));
}

TEST(KeyframeSchedule, ACutGetsAKeyframeOnEachSide) {
  test::TempDir dir;
  // The camera holds at x = -2 to frame 9 and jumps to x = 2 at frame 10.
  const ShotFrames shot = shot_with(dir, 20, "[camera]\n" + key(0, -2) + key(9, -2) + key(10, 2) + key(19, 2));
  const std::vector<int> keys = KeyframePlanner(shot).keyframes(2, 64);
  EXPECT_EQ(keys, (std::vector<int>{0, 9, 10, 19}));
}

TEST(KeyframeSchedule, RefusesANonPositiveMotionOrInterval) {
  test::TempDir dir;
  const ShotFrames shot = shot_with(dir, 5, "[camera]\n" + key(0, 0));
  const KeyframePlanner planner(shot);
  EXPECT_THROW(planner.keyframes(0, 8), std::invalid_argument);
  EXPECT_THROW(planner.keyframes(2, 0), std::invalid_argument);
}

TEST(AnimateCli, AutoKeyframesRenderEveryFrameAndSayWhereTheKeyframesWent) {
  test::TempDir dir;
  test::write_text(dir.file("s.nff"), kScene);
  test::write_text(dir.file("shot.toml"), "frames = 12\n[array]\nlenses = 8\npixels_per_lens = 4\n[camera]\n" + key(0, -1) +
                                              key(11, 1) + "[[object]]\nscene = \"s.nff\"\n");
  const auto r = test::run_cli("animate " + dir.file("shot.toml") + " -o " + dir.file("out") +
                               " --keyframe-interval auto --keyframe-motion 2");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("keyframes placed by motion (at most 2 px, 32 frames apart)"), std::string::npos) << r.output;
  for (int f = 0; f < 12; ++f)
    EXPECT_TRUE(std::filesystem::exists(dir.file(fmt::format("out/frame_{:04}.png", f)))) << f;
}

// A shot where nothing moves: the frames between keyframes are copies of a
// keyframe, and the run says so instead of reporting reuse and tracing.
TEST(AnimateCli, FramesOfAStillShotAreReportedAsCopiesOfTheirKeyframe) {
  test::TempDir dir;
  test::write_text(dir.file("s.nff"), kScene);
  test::write_text(dir.file("shot.toml"), "frames = 5\n[array]\nlenses = 8\npixels_per_lens = 4\n[camera]\n" + key(0, 0) +
                                              "[[object]]\nscene = \"s.nff\"\n");
  const auto r = test::run_cli("animate " + dir.file("shot.toml") + " -o " + dir.file("out") + " --report " +
                               dir.file("r.md"));
  ASSERT_EQ(r.status, 0) << r.output;
  for (int f = 1; f < 4; ++f)
    EXPECT_NE(r.output.find(fmt::format("frame {:>5}  copied ", f)), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("keyframe 0 (same camera, nothing moved), PSNR inf dB"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("% traced"), std::string::npos) << r.output;
  const std::string report = test::read_bytes(dir.file("r.md"));
  EXPECT_NE(report.find("| 1 | copy of key 0 |"), std::string::npos) << report;
}

}  // namespace
}  // namespace holoray
