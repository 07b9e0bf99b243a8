// Scale-out without MPI (issue 15): the group scheduler's dealing, the row
// bands of a still, a still rendered band by band, and a shot rendered with
// its groups dealt out of order, each against the one-process result.
#include <algorithm>
#include <cstring>
#include <map>
#include <numeric>
#include <set>

#include <gtest/gtest.h>

#include "cluster/group_scheduler.hpp"
#include "cluster/row_bands.hpp"
#include "camera/pinhole.hpp"
#include "render/view_renderer.hpp"
#include "scene/nff_reader.hpp"
#include "shot/shot_reader.hpp"
#include "temporal/sequence.hpp"
#include "test_util.hpp"

namespace holoray {
namespace {

// Runs a scheduler as `costs.size()` workers would: each asks again when its
// group is done (seconds = weight x the worker's cost per unit), earliest
// first. Returns each group's worker and fills the finishing time.
std::map<size_t, int> simulate(GroupScheduler& s, const std::vector<double>& weights, const std::vector<double>& costs,
                               double& makespan) {
  std::map<size_t, int> owner;
  std::vector<double> free_at(costs.size(), 0), last(costs.size(), 0);
  std::vector<bool> done(costs.size(), false);
  makespan = 0;
  while (std::find(done.begin(), done.end(), false) != done.end()) {
    int w = -1;
    for (int k = 0; k < static_cast<int>(costs.size()); ++k)
      if (!done[k] && (w < 0 || free_at[k] < free_at[w])) w = k;
    const auto g = s.next(w, last[w]);
    if (!g) {
      done[w] = true;
      continue;
    }
    EXPECT_FALSE(owner.count(*g)) << "group " << *g << " dealt twice";
    EXPECT_LT(*g, weights.size());
    if (*g < weights.size()) EXPECT_GT(weights[*g], 0) << "group " << *g << " has no work";
    owner[*g] = w;
    last[w] = weights[*g] * costs[w];
    free_at[w] += last[w];
    makespan = std::max(makespan, free_at[w]);
  }
  return owner;
}

TEST(GroupScheduler, DealsEveryGroupWithWorkExactlyOnceAndNoEmptyOne) {
  // Empty groups (frames already there under --resume) inside and at the
  // ends of the runs, and a slow worker, so that runs are stolen.
  for (const std::vector<double>& weights :
       {std::vector<double>{7, 7, 0, 7, 7, 3, 0, 7, 7, 7, 7, 7, 7, 7, 1}, std::vector<double>{5, 0, 0},
        std::vector<double>{9, 0, 0, 0, 1, 0, 0}, std::vector<double>{0, 0, 4, 4, 0, 0, 4, 4, 0}})
  for (int workers : {1, 2, 3, 5, 20}) {
    GroupScheduler s(weights, workers);
    double makespan = 0;
    std::vector<double> costs(workers, 1.0);
    costs[0] = 5;
    const auto owner = simulate(s, weights, costs, makespan);
    std::set<size_t> expected;
    for (size_t g = 0; g < weights.size(); ++g)
      if (weights[g] > 0) expected.insert(g);
    std::set<size_t> got;
    for (const auto& [g, w] : owner) got.insert(g);
    EXPECT_EQ(got, expected) << workers << " workers";
  }
}

TEST(GroupScheduler, OneWorkerGetsTheGroupsInOrderWithNoKeyframeTracedTwice) {
  const std::vector<double> weights{8, 8, 8, 8, 9};
  GroupScheduler s(weights, 1);
  for (size_t g = 0; g < weights.size(); ++g) EXPECT_EQ(s.next(0, 1.0), g);
  EXPECT_EQ(s.next(0, 1.0), std::nullopt);
  EXPECT_EQ(s.unchained_starts(), 0);
  EXPECT_EQ(s.steals(), 0);
}

// Workers start on contiguous runs: with equal costs nobody steals and each
// worker's groups follow on, so only the first group of each run but the
// first traces a keyframe that another worker traces too.
TEST(GroupScheduler, EqualWorkersKeepContiguousRunsAndTraceNKeyframesTwiceAtMost) {
  const std::vector<double> weights(16, 7.0);
  GroupScheduler s(weights, 4);
  double makespan = 0;
  const auto owner = simulate(s, weights, {1, 1, 1, 1}, makespan);
  for (size_t g = 1; g < weights.size(); ++g) EXPECT_LE(owner.at(g - 1), owner.at(g)) << "runs are contiguous";
  EXPECT_EQ(s.steals(), 0);
  EXPECT_EQ(s.unchained_starts(), 3);
  EXPECT_DOUBLE_EQ(makespan, 4 * 7.0);
}

// A slow worker (a node 5x slower, or a costlier part of the shot) has its
// run taken over: the shot ends close to the ideal, far before a static
// split would let it.
TEST(GroupScheduler, StealsFromTheSlowestSoTheShotEndsNearTheIdeal) {
  const std::vector<double> weights(30, 4.0);
  const std::vector<double> costs{5, 1, 1};
  GroupScheduler s(weights, 3);
  double makespan = 0;
  simulate(s, weights, costs, makespan);
  const double total = std::accumulate(weights.begin(), weights.end(), 0.0);
  const double ideal = total / (1 / 5.0 + 1 + 1);      // every worker busy to the end
  const double static_split = total / 3 * 5;           // the slow worker's third alone
  EXPECT_GT(s.steals(), 0);
  EXPECT_LT(makespan, ideal + 5 * 4.0) << "within one slow group of the ideal";
  EXPECT_LT(makespan, static_split / 2);
}

TEST(GroupScheduler, HandsOutNothingAfterStop) {
  GroupScheduler s(std::vector<double>(6, 1.0), 2);
  EXPECT_TRUE(s.next(0, 0).has_value());
  s.stop();
  EXPECT_EQ(s.next(1, 0), std::nullopt);
  EXPECT_EQ(s.next(0, 1), std::nullopt);
}

TEST(GroupScheduler, RefusesNegativeWeightsAndNoWorkers) {
  EXPECT_THROW(GroupScheduler({1, -1}, 2), std::invalid_argument);
  EXPECT_THROW(GroupScheduler({1, 1}, 0), std::invalid_argument);
}

TEST(RowBands, CoverEveryRowOnceInWholeLensRowsDealtRoundRobin) {
  for (int height : {1, 7, 80, 256, 1000})
    for (int ppl : {1, 8, 16})
      for (int ranks : {1, 2, 3, 7}) {
        const auto bands = row_bands(height, ppl, ranks);
        ASSERT_FALSE(bands.empty());
        int y = 0;
        for (size_t b = 0; b < bands.size(); ++b) {
          EXPECT_EQ(bands[b].y0, y);
          EXPECT_GT(bands[b].y1, bands[b].y0);
          EXPECT_EQ(bands[b].y0 % ppl, 0) << "bands start on a lens row";
          EXPECT_EQ(bands[b].rank, static_cast<int>(b % ranks));
          y = bands[b].y1;
        }
        EXPECT_EQ(y, height);
        const int lens_rows = (height + ppl - 1) / ppl;
        EXPECT_EQ(static_cast<int>(bands.size()), std::min(lens_rows, 4 * ranks));
      }
  EXPECT_THROW(row_bands(0, 8, 2), std::invalid_argument);
}

const char* kScene =
    "v\nfrom 0 -10 2\nat 0 0 0\nup 0 0 1\nangle 40\nhither 1\nresolution 64 64\n"
    "l 5 -6 10\nl -5 -6 8\nf 0.9 0.3 0.2 1 0 0 0 0\ns 0 0 0 1\nf 0.8 0.8 0.8 0.4 0.5 20 0 0\n"
    "s 1.5 0.5 0.3 0.6\ns -1.4 0.8 -0.2 0.7\np 4\n-4 -4 -1\n4 -4 -1\n4 4 -1\n-4 4 -1\n";

// A band of rows holds bit for bit the same pixels, AOVs included, as
// those rows of the whole image: an EIA and a pinhole view.
TEST(RenderBands, ABandIsTheSameRowsOfTheWholeImage) {
  const SceneDesc desc = parse_nff(kScene, "bands.nff");
  RenderScene scene(desc);
  const LensArray camera(test::camera_at(desc, {0, 0, 0}, 20, 8));
  RenderOptions ro;
  ro.aovs = {true, true, true, true};
  RenderStats stats;
  const FrameBuffers whole = render_frame(scene, camera, ro, stats);
  for (const auto& [y0, y1] : {std::pair{0, 8}, std::pair{48, 104}, std::pair{152, 160}, std::pair{3, 5}}) {
    ro.rows = std::array<int, 2>{y0, y1};
    const FrameBuffers band = render_frame(scene, camera, ro, stats);
    ASSERT_EQ(band.colour.height, y1 - y0);
    for (const auto& [a, b] : {std::pair{&whole.colour, &band.colour}, std::pair{&whole.albedo, &band.albedo},
                               std::pair{&whole.depth, &band.depth}, std::pair{&whole.normal, &band.normal},
                               std::pair{&whole.id, &band.id}}) {
      const size_t row = static_cast<size_t>(a->width) * a->channels;
      ASSERT_EQ(b->data.size(), row * (y1 - y0));
      EXPECT_EQ(std::memcmp(a->at(0, y0), b->data.data(), b->data.size() * sizeof(float)), 0)
          << "rows " << y0 << " to " << y1;
    }
  }
  ro.rows = std::array<int, 2>{100, 200};
  EXPECT_THROW(render_frame(scene, camera, ro, stats), std::invalid_argument);
  // The line renderers (pinhole view, quilt, panels) take bands the same way.
  const PinholeCamera view(view_of(*desc.viewpoint, 70, 90));
  ro.rows.reset();
  ro.aovs = {false, true, false, false};
  const FrameBuffers view_whole = render_view(scene, view, ro, stats);
  for (const auto& [y0, y1] : {std::pair{0, 32}, std::pair{32, 90}, std::pair{17, 18}}) {
    ro.rows = std::array<int, 2>{y0, y1};
    const FrameBuffers band = render_view(scene, view, ro, stats);
    for (const auto& [a, b] : {std::pair{&view_whole.colour, &band.colour}, std::pair{&view_whole.depth, &band.depth}}) {
      ASSERT_EQ(b->data.size(), static_cast<size_t>(a->width) * a->channels * (y1 - y0));
      EXPECT_EQ(std::memcmp(a->at(0, y0), b->data.data(), b->data.size() * sizeof(float)), 0) << "view rows " << y0 << " to " << y1;
    }
  }
  ro.rows = std::array<int, 2>{80, 91};
  EXPECT_THROW(render_view(scene, view, ro, stats), std::invalid_argument);
}

// Groups dealt in any order, each worker tracing the first keyframe of a
// group that does not follow on from its previous one, give the frames of
// the in-order run bit for bit (reuse never crosses a worker).
TEST(FrameGroups, GroupsRenderedInAnyOrderGiveTheInOrderFrames) {
  test::TempDir dir;
  test::write_text(dir.file("scene.nff"), kScene);
  test::write_text(dir.file("shot.toml"),
                   "frames = 13\n[array]\nlenses = 16\npixels_per_lens = 8\n[camera]\n"
                   "[[camera.key]]\nframe = 0\nfrom = [0, -10, 2]\nat = [0, 0, 0]\nup = [0, 0, 1]\n"
                   "[[camera.key]]\nframe = 12\nfrom = [1, -10, 2]\nat = [0.5, 0, 0]\nup = [0, 0, 1]\n"
                   "[[object]]\nscene = \"scene.nff\"\n");
  for (Method method : {Method::reproject, Method::reverse, Method::full}) {
    SequenceOptions so;
    so.method = method;
    so.keyframe_interval = 4;
    const std::vector<FrameGroup> groups = frame_groups(13, so);
    if (method == Method::full) ASSERT_EQ(groups.size(), 13u);
    else ASSERT_EQ(groups.size(), 3u);  // keyframes 0, 4, 8, 12: 0-3, 4-7, 8-12
    auto render = [&](std::vector<size_t> order) {
      ShotFrames shot(read_shot_file(dir.file("shot.toml")));
      std::map<int, FloatSamples> frames;
      SequenceOptions o = so;
      if (!order.empty()) {
        std::reverse(order.begin(), order.end());
        o.next_group = [order]() mutable -> std::optional<size_t> {
          if (order.empty()) return std::nullopt;
          const size_t g = order.back();
          order.pop_back();
          return g;
        };
      }
      render_sequence(shot, o, [&](int f, const ImageBuffer& c, const FrameReport&) {
        EXPECT_FALSE(frames.count(f)) << "frame " << f << " emitted twice";
        frames[f] = c.data;
      });
      return frames;
    };
    const auto in_order = render({});
    ASSERT_EQ(in_order.size(), 13u);
    std::vector<size_t> shuffled(groups.size());
    std::iota(shuffled.begin(), shuffled.end(), 0);
    std::reverse(shuffled.begin(), shuffled.end());
    std::swap(shuffled.front(), shuffled[shuffled.size() / 2]);
    EXPECT_EQ(render(shuffled), in_order);
    // Only some groups: exactly their frames.
    const auto part = render({groups.size() - 1});
    std::set<int> got;
    for (const auto& [f, data] : part) got.insert(f);
    std::set<int> want;
    for (int f = groups.back().first; f <= groups.back().last; ++f) want.insert(f);
    EXPECT_EQ(got, want);
  }
}

}  // namespace
}  // namespace holoray
