// Node animation from mesh files (scene/mesh_reader.hpp, math/node_track.hpp,
// issue 13 item 4): glTF's interpolation rules on their own, and a glTF
// whose node is animated renders, frame by frame, what the same motion
// written as shot keys (docs/shot-format.md) renders, the independent path.
#include <gtest/gtest.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>
#include <string>
#include <vector>

#include "image/metrics.hpp"
#include "math/node_track.hpp"
#include "render/renderer.hpp"
#include "scene/mesh_reader.hpp"
#include "shot/shot_frames.hpp"
#include "shot/shot_reader.hpp"
#include "test_util.hpp"

namespace holoray {
namespace {

constexpr double kPi = std::numbers::pi;

Quaternion about_z(double degrees) {
  const double h = degrees * kPi / 360;
  return {std::cos(h), 0, 0, std::sin(h)};
}

TEST(NodeTrack, SlerpTurnsAtAConstantRateAndKeysHoldOutsideTheirTimes) {
  NodeTrack t;
  t.rotation = {{0.0, about_z(0)}, {2.0, about_z(90)}};
  t.translation = {{1.0, {0, 0, 0}}, {3.0, {4, 0, 0}}};
  t.scale = {{0.0, {1, 1, 1}}, {2.0, {3, 3, 3}}};
  // Halfway in time: 45 degrees, scale 2, translation 1 (its keys start at 1 s).
  const Affine m = t.at(1.0);
  const Vec3 x = m.dir({1, 0, 0});
  EXPECT_NEAR(std::atan2(x.y, x.x) * 180 / kPi, 45, 1e-9);
  EXPECT_NEAR(length(x), 2, 1e-12);
  EXPECT_NEAR(length(m.translation - Vec3{0, 0, 0}), 0, 1e-12);
  EXPECT_NEAR(length(t.at(2.0).translation - Vec3{2, 0, 0}), 0, 1e-12);
  // Before the first key and after the last: held.
  EXPECT_NEAR(length(t.at(-5.0).dir({1, 0, 0}) - Vec3{1, 0, 0}), 0, 1e-12);
  EXPECT_NEAR(length(t.at(9.0).dir({1, 0, 0}) - Vec3{0, 3, 0}), 0, 1e-12);
  EXPECT_NEAR(length(t.at(9.0).translation - Vec3{4, 0, 0}), 0, 1e-12);
}

TEST(NodeTrack, SlerpTakesTheShorterArc) {
  // q and -q are one rotation: from 0 to -(170 degrees) as a quaternion of
  // the other sign must still turn +85 degrees halfway, not -95.
  Quaternion far = about_z(170);
  far = {-far.w, -far.x, -far.y, -far.z};
  const Vec3 x = rotation_of(slerp(about_z(0), far, 0.5)).dir({1, 0, 0});
  EXPECT_NEAR(std::atan2(x.y, x.x) * 180 / kPi, 85, 1e-9);
}

// A glTF file assembled from float and index arrays (one buffer, one view
// per accessor): its accessors, and the JSON around them.
struct Gltf {
  std::vector<uint8_t> buffer;
  std::vector<std::string> views, accessors;

  template <class T>
  int accessor(const std::vector<T>& values, const char* type, int component, int count) {
    const size_t offset = buffer.size();
    buffer.resize(offset + values.size() * sizeof(T));
    std::memcpy(buffer.data() + offset, values.data(), values.size() * sizeof(T));
    views.push_back(fmt::format(R"({{"buffer": 0, "byteOffset": {}, "byteLength": {}}})", offset, values.size() * sizeof(T)));
    std::string minmax;
    if (std::string(type) == "SCALAR" && component == 5126) {  // animation input times need min and max
      const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
      minmax = fmt::format(R"(, "min": [{}], "max": [{}])", *lo, *hi);
    }
    accessors.push_back(fmt::format(R"({{"bufferView": {}, "componentType": {}, "count": {}, "type": "{}"{}}})",
                                    views.size() - 1, component, count, type, minmax));
    return static_cast<int>(accessors.size() - 1);
  }

  std::string json(const std::string& body) const {
    return fmt::format(R"({{"asset": {{"version": "2.0"}}, {},
 "buffers": [{{"byteLength": {}, "uri": "data:application/octet-stream;base64,{}"}}],
 "bufferViews": [{}], "accessors": [{}]}})",
                       body, buffer.size(), test::base64(buffer), fmt::join(views, ", "), fmt::join(accessors, ", "));
  }
};

// A unit box standing on z = 0 and a floor below it, as triangles.
const std::vector<float> kBoxPositions = {-0.5f, -0.5f, 0, 0.5f, -0.5f, 0, 0.5f, 0.5f, 0, -0.5f, 0.5f, 0,
                                          -0.5f, -0.5f, 1, 0.5f, -0.5f, 1, 0.5f, 0.5f, 1, -0.5f, 0.5f, 1};
const std::vector<uint32_t> kBoxIndices = {0, 3, 2, 0, 2, 1, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4,
                                           1, 2, 6, 1, 6, 5, 2, 3, 7, 2, 7, 6, 3, 0, 4, 3, 4, 7};
const std::vector<float> kFloorPositions = {-3, -3, -0.01f, 3, -3, -0.01f, 3, 3, -0.01f, -3, 3, -0.01f};
const std::vector<uint32_t> kFloorIndices = {0, 1, 2, 0, 2, 3};
const char* kMaterials = R"("materials": [
  {"name": "red", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.2, 0.2, 1], "metallicFactor": 0}},
  {"name": "grey", "pbrMetallicRoughness": {"baseColorFactor": [0.7, 0.7, 0.7, 1], "metallicFactor": 0}}])";

// The box's motion: keys at 0 s and 1 s (shot frames 0 and 4 at 4 fps).
const Vec3 kFrom{-1, 0, 0}, kTo{1, 0.5, 0};
const double kTurnDeg = 90;
const Vec3 kScaleTo{1, 1, 1.5};
// The box hangs under a still node lifted by this much (the chain of nodes).
const double kPivotZ = 0.25;

std::string mesh_json(Gltf& g, const std::vector<float>& p, const std::vector<uint32_t>& i, int material) {
  const int pa = g.accessor(p, "VEC3", 5126, static_cast<int>(p.size() / 3));
  const int ia = g.accessor(i, "SCALAR", 5125, static_cast<int>(i.size()));
  return fmt::format(R"({{"primitives": [{{"attributes": {{"POSITION": {}}}, "indices": {}, "material": {}}}]}})", pa, ia,
                     material);
}

std::string animated_gltf() {
  Gltf g;
  const std::string box = mesh_json(g, kBoxPositions, kBoxIndices, 0);
  const std::string floor = mesh_json(g, kFloorPositions, kFloorIndices, 1);
  const Quaternion q0 = about_z(0), q1 = about_z(kTurnDeg);
  const int times = g.accessor(std::vector<float>{0, 1}, "SCALAR", 5126, 2);
  const int moves = g.accessor(std::vector<float>{float(kFrom.x), float(kFrom.y), float(kFrom.z), float(kTo.x),
                                                  float(kTo.y), float(kTo.z)},
                               "VEC3", 5126, 2);
  const int turns = g.accessor(std::vector<float>{float(q0.x), float(q0.y), float(q0.z), float(q0.w), float(q1.x),
                                                  float(q1.y), float(q1.z), float(q1.w)},
                               "VEC4", 5126, 2);
  const int scales = g.accessor(std::vector<float>{1, 1, 1, float(kScaleTo.x), float(kScaleTo.y), float(kScaleTo.z)},
                                "VEC3", 5126, 2);
  return g.json(fmt::format(R"("scene": 0, "scenes": [{{"nodes": [0, 1]}}],
 "nodes": [{{"name": "floor", "mesh": 1}}, {{"name": "pivot", "translation": [0, 0, {}], "children": [2]}},
           {{"name": "box", "mesh": 0}}],
 "meshes": [{}, {}], {},
 "animations": [{{"channels": [{{"sampler": 0, "target": {{"node": 2, "path": "translation"}}}},
                               {{"sampler": 1, "target": {{"node": 2, "path": "rotation"}}}},
                               {{"sampler": 2, "target": {{"node": 2, "path": "scale"}}}}],
                 "samplers": [{{"input": {}, "output": {}}}, {{"input": {}, "output": {}}}, {{"input": {}, "output": {}}}]}}])",
                            kPivotZ, box, floor, kMaterials, times, moves, times, turns, times, scales));
}

std::string still_gltf(const std::vector<float>& p, const std::vector<uint32_t>& i, int material) {
  Gltf g;
  const std::string mesh = mesh_json(g, p, i, material);
  return g.json(fmt::format(R"("scene": 0, "scenes": [{{"nodes": [0]}}], "nodes": [{{"mesh": 0}}], "meshes": [{}], {})",
                            mesh, kMaterials));
}

constexpr const char* kShotHead = R"(frames = 5
fps = 4
[array]
lenses = 24
pixels_per_lens = 6
[camera]
[[camera.key]]
frame = 0
from = [1, -7, 4]
at = [0, 0, 0.5]
up = [0, 0, 1]
angle = 40
[[object]]
scene = "light.nff"
)";

std::vector<ImageBuffer> render_shot(const std::string& path) {
  ShotFrames shot(read_shot_file(path));
  std::vector<ImageBuffer> frames;
  for (int f = 0; f < shot.frame_count(); ++f) {
    shot.seek(f);
    RenderStats stats;
    frames.push_back(render_frame(shot.scene(), LensArray(shot.camera(f)), RenderOptions{}, stats).colour);
  }
  return frames;
}

TEST(MeshAnimation, AnimatedGltfNodeRendersAsTheSameMotionWrittenAsShotKeys) {
  test::TempDir dir;
  test::write_text(dir.file("light.nff"), "l 3 -4 6\n");
  test::write_text(dir.file("anim.gltf"), animated_gltf());
  test::write_text(dir.file("box.gltf"), still_gltf(kBoxPositions, kBoxIndices, 0));
  test::write_text(dir.file("floor.gltf"), still_gltf(kFloorPositions, kFloorIndices, 1));
  test::write_text(dir.file("a.toml"), std::string(kShotHead) + "[[object]]\nscene = \"anim.gltf\"\n");
  test::write_text(dir.file("b.toml"),
                   std::string(kShotHead) +
                       fmt::format(R"([[object]]
scene = "floor.gltf"
[[object]]
scene = "box.gltf"
[[object.key]]
frame = 0
translate = [{}, {}, {}]
[[object.key]]
frame = 4
translate = [{}, {}, {}]
rotate = [0, 0, {}]
scale = [{}, {}, {}]
)",
                                   kFrom.x, kFrom.y, kFrom.z + kPivotZ, kTo.x, kTo.y, kTo.z + kPivotZ, kTurnDeg,
                                   kScaleTo.x, kScaleTo.y, kScaleTo.z));
  MeshAnimation anim;
  const SceneDesc still = read_mesh_file(dir.file("anim.gltf"), {}, &anim);
  ASSERT_EQ(anim.parts.size(), 1u);
  EXPECT_EQ(anim.parts[0].node, "box");
  EXPECT_EQ(still.objects.size(), 1u) << "the floor stands still";
  EXPECT_NEAR(anim.duration_s, 1.0, 1e-9);

  const std::vector<ImageBuffer> a = render_shot(dir.file("a.toml")), b = render_shot(dir.file("b.toml"));
  ASSERT_EQ(a.size(), 5u);
  ASSERT_EQ(b.size(), 5u);
  for (size_t f = 0; f < a.size(); ++f)
    EXPECT_GE(compare_images(a[f], b[f]).psnr_all(), 60) << "frame " << f;
  // The box moved: the first and last frames differ (else the test proves nothing).
  EXPECT_LT(compare_images(a.front(), a.back()).psnr_all(), 30);
}

// A glTF whose camera node slides over a box, looking down -z: the shot
// without [camera] follows it, frame for frame as the same motion written
// as camera keys.
std::string moving_camera_gltf() {
  Gltf g;
  const std::string box = mesh_json(g, kBoxPositions, kBoxIndices, 0);
  const std::string floor = mesh_json(g, kFloorPositions, kFloorIndices, 1);
  const int times = g.accessor(std::vector<float>{0, 1}, "SCALAR", 5126, 2);
  const int moves = g.accessor(std::vector<float>{-1, 0, 6, 1, 0.5f, 6}, "VEC3", 5126, 2);
  return g.json(fmt::format(R"("scene": 0, "scenes": [{{"nodes": [0, 1, 2]}}],
 "nodes": [{{"name": "floor", "mesh": 1}}, {{"name": "box", "mesh": 0}}, {{"name": "eye", "camera": 0}}],
 "cameras": [{{"type": "perspective", "perspective": {{"yfov": 0.7, "aspectRatio": 1.0, "znear": 0.1}}}}],
 "meshes": [{}, {}], {},
 "animations": [{{"channels": [{{"sampler": 0, "target": {{"node": 2, "path": "translation"}}}}],
                 "samplers": [{{"input": {}, "output": {}}}]}}])",
                            box, floor, kMaterials, times, moves));
}

TEST(MeshAnimation, AnimatedGltfCameraPlacesTheArrayAsTheSameCameraKeys) {
  test::TempDir dir;
  test::write_text(dir.file("light.nff"), "l 3 -4 6\n");
  test::write_text(dir.file("cam.gltf"), moving_camera_gltf());
  MeshAnimation anim;
  const SceneDesc still = read_mesh_file(dir.file("cam.gltf"), {}, &anim);
  ASSERT_TRUE(anim.camera);
  ASSERT_TRUE(still.viewpoint);
  const double angle = still.viewpoint->angle_deg;
  // A file camera's focal plane: the depth of the scene's centre at rest,
  // held as the camera moves.
  const double focus = length(still.viewpoint->at - still.viewpoint->from);
  const std::string head = "frames = 5\nfps = 4\n[array]\nlenses = 24\npixels_per_lens = 6\n";
  const std::string objects = "[[object]]\nscene = \"light.nff\"\n[[object]]\nscene = \"cam.gltf\"\n";
  test::write_text(dir.file("a.toml"), head + objects);
  test::write_text(dir.file("b.toml"),
                   head + fmt::format(R"([camera]
[[camera.key]]
frame = 0
from = [-1, 0, 6]
at = [-1, 0, {1:.17g}]
up = [0, 1, 0]
angle = {0:.17g}
[[camera.key]]
frame = 4
from = [1, 0.5, 6]
at = [1, 0.5, {1:.17g}]
up = [0, 1, 0]
angle = {0:.17g}
)",
                                      angle, 6 - focus) +
                       objects);
  const std::vector<ImageBuffer> a = render_shot(dir.file("a.toml")), b = render_shot(dir.file("b.toml"));
  ASSERT_EQ(a.size(), 5u);
  for (size_t f = 0; f < a.size(); ++f) EXPECT_GE(compare_images(a[f], b[f]).psnr_all(), 60) << "frame " << f;
  // The camera moved: the first and last frames differ.
  EXPECT_LT(compare_images(a.front(), a.back()).psnr_all(), 30);
}

TEST(MeshAnimation, WithoutTheRequestNodesStandAtRest) {
  test::TempDir dir;
  test::write_text(dir.file("anim.gltf"), animated_gltf());
  const SceneDesc d = read_mesh_file(dir.file("anim.gltf"));
  ASSERT_EQ(d.objects.size(), 2u);
  // The box at its rest transform: under the pivot, no track applied.
  const auto& box = std::get<TriangleMeshDesc>(d.objects[1].shape);  // after the floor, in node order
  EXPECT_NEAR(box.vertices[0].z, kPivotZ, 1e-6);
}

}  // namespace
}  // namespace holoray
