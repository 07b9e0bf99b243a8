// Skinned and morphed meshes (scene/mesh_reader.hpp,
// MeshAnimation::DeformingMesh): linear blend skinning and morph targets on
// hand-made meshes with known answers, a glTF arm bent by two joints and a
// box morphed by two targets against Blender's render of the same frames
// (the independent oracle, tests/data/blender/render_oracle.py), and reuse
// in shots, where a deforming mesh is a moving object.
#include <gtest/gtest.h>
#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "camera/pinhole.hpp"
#include "image/image_io.hpp"
#include "image/metrics.hpp"
#include "render/view_renderer.hpp"
#include "scene/mesh_reader.hpp"
#include "shot/shot_frames.hpp"
#include "shot/shot_reader.hpp"
#include "test_util.hpp"

namespace holoray {
namespace {

const std::string kData = std::string(HOLORAY_SOURCE_DIR) + "/tests/data/blender/";

double distance(const Vec3& a, const Vec3& b) { return length(a - b); }

// Joint 0 stands at the origin; joint 1 sits at x = 1 and turns 90 degrees
// about z over one second. Bound where they stand at rest (inverse bind =
// the inverse of the rest frame), so at t = 0 every vertex stays put.
MeshAnimation two_joint_skin() {
  MeshAnimation a;
  NodeTrack turn;
  const double h = std::numbers::pi / 4;  // half of 90 degrees
  turn.rotation = {{0.0, Quaternion{}}, {1.0, Quaternion{std::cos(h), 0, 0, std::sin(h)}}};
  a.tracks.push_back(turn);
  MeshAnimation::DeformingMesh s;
  s.vertices = {{2, 0, 0}, {2, 0, 0}, {0.5, 0, 0}};
  s.normals = {{1, 0, 0}, {0, 0, 1}, {1, 0, 0}};
  MeshAnimation::DeformingMesh::Joint root;  // identity everywhere
  MeshAnimation::DeformingMesh::Joint elbow;
  elbow.chain = {{Affine::translate({1, 0, 0}), 0}};
  elbow.inverse_bind = Affine::translate({-1, 0, 0});
  s.joints = {root, elbow};
  // Vertex 0 follows the elbow; vertex 1 half each; vertex 2 the root.
  s.influences = {{1, 1.0}, {0, 0.5}, {1, 0.5}, {0, 1.0}};
  s.first = {0, 1, 3, 4};
  a.deforming.push_back(s);
  return a;
}

TEST(Skinning, AVertexMovesByTheWeightedBlendOfItsJointsMatrices) {
  const MeshAnimation a = two_joint_skin();
  std::vector<Vec3> v, n;
  a.pose(0, 0.0, v, n);
  ASSERT_EQ(v.size(), 3u);
  for (size_t k = 0; k < 3; ++k) EXPECT_LT(distance(v[k], a.deforming[0].vertices[k]), 1e-12) << "bind pose, vertex " << k;
  a.pose(0, 1.0, v, n);
  // The elbow's vertex: (2, 0, 0) is 1 past the elbow, turned 90 degrees to (1, 1, 0).
  EXPECT_LT(distance(v[0], {1, 1, 0}), 1e-12);
  EXPECT_LT(distance(n[0], {0, 1, 0}), 1e-12);
  // Half and half: the mean of (2, 0, 0) and (1, 1, 0), matrices blended (not positions slerped).
  EXPECT_LT(distance(v[1], {1.5, 0.5, 0}), 1e-12);
  EXPECT_LT(distance(n[1], {0, 0, 1}), 1e-12) << "a normal along the turning axis stays";
  EXPECT_LT(distance(v[2], {0.5, 0, 0}), 1e-12) << "the root's vertex stays";
  // Halfway in time: 45 degrees.
  a.pose(0, 0.5, v, n);
  EXPECT_LT(distance(v[0], Vec3{1, 0, 0} + Vec3{std::sqrt(0.5), std::sqrt(0.5), 0}), 1e-12);
}

TEST(Skinning, AFileReadForAShotKeepsEachSkinnedPrimitiveAsADeformablePart) {
  MeshAnimation anim;
  const SceneDesc still = read_mesh_file(kData + "skinned_arm.gltf", {}, &anim);
  // The arm's two primitives (two materials) are two skinned meshes; the floor stands still.
  ASSERT_EQ(anim.deforming.size(), 2u);
  EXPECT_EQ(still.objects.size(), 1u);
  for (const MeshAnimation::DeformingMesh& s : anim.deforming) {
    EXPECT_EQ(s.joints.size(), 3u) << "shoulder, elbow, and the mesh's node for unweighted vertices";
    EXPECT_TRUE(anim.parts.at(s.part).chain.empty()) << "posed in the file frame";
    ASSERT_EQ(s.first.size(), s.vertices.size() + 1);
    for (size_t v = 0; v < s.vertices.size(); ++v) {
      double sum = 0;
      for (uint32_t k = s.first[v]; k < s.first[v + 1]; ++k) sum += s.influences[k].second;
      EXPECT_NEAR(sum, 1, 1e-6) << "vertex " << v;
    }
  }
}

// The arm bends, the box's top lifts and slides, at frames 0, 5 and 9 of a
// shot at the files' 24 fps (one key per frame): holoray's pinhole albedo
// from the file's camera against Blender's DiffCol at the same frames.
class BlenderDeforming : public ::testing::TestWithParam<const char*> {};

TEST_P(BlenderDeforming, FramesMatchBlendersAlbedoAtFramesZeroFiveAndNine) {
  test::TempDir dir;
  test::write_text(dir.file("shot.toml"), fmt::format("frames = 10\nfps = 24\n[array]\nlenses = 24\npixels_per_lens = 6\n"
                                                      "[[object]]\nscene = \"{}{}.gltf\"\n",
                                                      kData, GetParam()));
  ShotFrames shot(read_shot_file(dir.file("shot.toml")));
  RenderOptions options;
  options.aovs.albedo = true;
  std::vector<ImageBuffer> ours;
  for (int f : {0, 5, 9}) {
    shot.seek(f);
    RenderStats stats;
    const FrameBuffers fb = render_view(shot.scene(), PinholeCamera(view_of(shot.viewpoint(f), 128, 128)), options, stats);
    const ImageBuffer blender = as_rgb(read_image(fmt::format("{}{}.f{}.albedo.exr", kData, GetParam(), f)));
    const double psnr = compare_images(fb.albedo, blender).psnr_all();
    RecordProperty(fmt::format("psnr_db_frame_{}", f), fmt::format("{:.2f}", psnr));
    EXPECT_GE(psnr, 30) << GetParam() << ", frame " << f;
    ours.push_back(fb.albedo);
  }
  // The mesh moved (else the test proves nothing): frames 0 and 9 differ.
  EXPECT_LT(compare_images(ours.front(), ours.back()).psnr_all(), 25);
}

INSTANTIATE_TEST_SUITE_P(Fixtures, BlenderDeforming, ::testing::Values("skinned_arm", "morph_box"));

TEST(Morphing, TargetsBlendLinearlyInTheirWeightsAndWeightKeysInTime) {
  MeshAnimation a;
  MeshAnimation::DeformingMesh m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}};
  m.normals = {{0, 0, 1}, {0, 0, 1}};
  m.targets = {{{{0, 2, 0}, {1, 0, 0}}, {{0, 0, 1}, {0, 0, 1}}}, {{{0, 0, 0}, {1, 0, 4}}, {{1, 0, 0}, {0, 0, 1}}}};
  m.weights = {0.5, 0.25};
  m.weight_keys = {{1.0, {0.0, 1.0}}, {3.0, {1.0, 0.0}}};
  MeshAnimation::DeformingMesh::Joint node;  // unskinned: the mesh's node, here the identity
  m.joints = {node};
  m.influences = {{0, 1.0}, {0, 1.0}};
  m.first = {0, 1, 2};
  a.deforming.push_back(m);
  std::vector<Vec3> v, n;
  // A still: the default weights, 0.5 of target 0 and 0.25 of target 1.
  pose_mesh(m, m.weights, {}, 0, v, n);
  EXPECT_LT(distance(v[0], {0, 1, 0}), 1e-12);
  EXPECT_LT(distance(v[1], {1, 0, 1}), 1e-12);
  EXPECT_LT(distance(n[0], normalize(Vec3{0.25, 0, 0.75})), 1e-12) << "normals blend, then are normalised";
  // Keys: held before the first, linear between, held after the last.
  a.pose(0, 0.0, v, n);
  EXPECT_LT(distance(v[1], {1, 0, 4}), 1e-12);
  a.pose(0, 2.5, v, n);  // weights (0.75, 0.25)
  EXPECT_LT(distance(v[0], {0, 1.5, 0}), 1e-12);
  EXPECT_LT(distance(v[1], {1, 0, 1}), 1e-12);
  a.pose(0, 9.0, v, n);
  EXPECT_LT(distance(v[0], {0, 2, 0}), 1e-12);
}

// Reuse in a shot of the bending arm (locked-off camera: the file's): a
// deforming mesh has no transform that maps its keyframe points, so its
// pixels are traced afresh. Reverse reprojection stays within colour
// reuse's usual error of the full trace; forward reprojection retraces
// every elemental image that can see the arm (here: all). Without the pose
// check both showed the keyframe's arm; with the array at the arm (the file
// camera's focal plane at the scene's centre), a keyframe's own image scores
// 23.0 to 28.9 dB against frames 1 to 7, reverse reprojection 32.0 to 43.8.
TEST(Skinning, ReuseNeverShowsAStalePoseOfADeformingMesh) {
  test::TempDir dir;
  test::write_text(dir.file("arm.toml"), fmt::format("frames = 9\nfps = 24\n[array]\nlenses = 32\npixels_per_lens = 8\n"
                                                     "[[object]]\nscene = \"{}skinned_arm.gltf\"\n",
                                                     kData));
  auto frames = [&](const std::string& method) {
    const std::string out = dir.file(method);
    const auto r = test::run_cli(fmt::format("animate {} --method {} --format exr -q -o {}", dir.file("arm.toml"), method, out));
    EXPECT_EQ(r.status, 0) << r.output;
    std::vector<ImageBuffer> images;
    for (int f = 0; f < 9; ++f) images.push_back(read_image(fmt::format("{}/frame_{:04d}.exr", out, f)));
    return images;
  };
  const std::vector<ImageBuffer> full = frames("full"), reverse = frames("reverse"), forward = frames("reproject");
  for (int f = 1; f < 8; ++f) {
    EXPECT_GE(compare_images(reverse[f], full[f]).psnr_all(), 31) << "reverse, frame " << f;
    EXPECT_GE(compare_images(forward[f], full[f]).psnr_all(), 60) << "reproject, frame " << f;
  }
  EXPECT_LT(compare_images(full[0], full[7]).psnr_all(), 25) << "the arm moved";
}

// After its last key the arm holds its pose: the frames whose vertices are
// the same keep one pose tag, and reverse reprojection copies them from a
// keyframe (a locked-off shot where nothing moved) instead of tracing them.
TEST(Skinning, AHeldPoseIsStillAndItsFramesAreCopied) {
  test::TempDir dir;
  test::write_text(dir.file("arm.toml"), fmt::format("frames = 20\nfps = 24\n[array]\nlenses = 16\npixels_per_lens = 6\n"
                                                     "[[object]]\nscene = \"{}skinned_arm.gltf\"\n",
                                                     kData));
  const auto reverse = test::run_cli(
      fmt::format("animate {} --method reverse --format exr -o {}", dir.file("arm.toml"), dir.file("reverse")));
  ASSERT_EQ(reverse.status, 0) << reverse.output;
  const auto full =
      test::run_cli(fmt::format("animate {} --method full --format exr -q -o {}", dir.file("arm.toml"), dir.file("full")));
  ASSERT_EQ(full.status, 0) << full.output;
  // Frames 10 to 15 lie past the last key (frame 9) and before keyframe 16.
  for (int f = 10; f <= 15; ++f) {
    EXPECT_NE(reverse.output.find(fmt::format("frame {:>5}  copied", f)), std::string::npos) << "frame " << f;
    EXPECT_EQ(read_image(fmt::format("{}/frame_{:04d}.exr", dir.file("reverse"), f)).data,
              read_image(fmt::format("{}/frame_{:04d}.exr", dir.file("full"), f)).data)
        << "frame " << f;
  }
}

}  // namespace
}  // namespace holoray
