// File cameras (issue 53): each format's field of view read as the format
// defines it, the camera picked by name, the focal plane of a camera that
// has no point it looks at, orthographic views, and textures found as other
// tools find them. Blender's framing of the same sample files is checked in
// tests/blender/test_file_cameras.py.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>

#include "camera/pinhole.hpp"
#include "render/frame_camera.hpp"
#include "render/render_scene.hpp"
#include "render/view_renderer.hpp"
#include "scene/mesh_reader.hpp"
#include "scene/nff_reader.hpp"
#include "scene/texture_search.hpp"
#include "test_util.hpp"

namespace holoray {
namespace {

constexpr double kDeg = 180 / std::numbers::pi;
const std::string kModels = "/usr/share/assimp/models/";

// Debian's assimp-testmodels (scripts/setup.sh installs it).
#define NEED_MODELS()                                                                                \
  if (!std::filesystem::is_directory(kModels)) GTEST_SKIP() << "assimp-testmodels is not installed"

// A glTF triangle spanning [-1, 1] x [-1, 1] at z = 0 and two cameras at
// (0, 0.5, 5) looking down -z: "near" (yfov 0.6, aspect 1.5) and "top",
// orthographic (xmag 2, ymag 1).
std::string two_camera_gltf(const test::TempDir& dir) {
  test::write_text(dir.file("c.gltf"), R"({"asset": {"version": "2.0"},
 "scene": 0, "scenes": [{"nodes": [0, 1, 2]}],
 "nodes": [{"mesh": 0}, {"name": "near", "camera": 0, "translation": [0, 0.5, 5]},
           {"name": "top", "camera": 1, "translation": [0, 0.5, 5]}],
 "cameras": [{"type": "perspective", "perspective": {"yfov": 0.6, "aspectRatio": 1.5, "znear": 0.1}},
             {"type": "orthographic", "orthographic": {"xmag": 2, "ymag": 1, "znear": 0.1, "zfar": 100}}],
 "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
 "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,AACAvwAAgL8AAAAAAACAPwAAgL8AAAAAAAAAAAAAgD8AAAAA"}],
 "bufferViews": [{"buffer": 0, "byteLength": 36}],
 "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [-1, -1, 0], "max": [1, 1, 0]}]})");
  return dir.file("c.gltf");
}

TEST(FileCamera, FocalPlaneStandsAtTheDepthOfTheScenesCentre) {
  test::TempDir dir;
  const SceneDesc d = read_mesh_file(two_camera_gltf(dir));
  ASSERT_TRUE(d.viewpoint);
  const Viewpoint& v = *d.viewpoint;
  EXPECT_EQ(v.camera, "near") << "the file's first camera";
  EXPECT_EQ(v.focus, Viewpoint::Focus::scene_centre_depth);
  // The box's centre (0, 0, 0) lies 5 along -z from the eye: at = (0, 0.5, 0).
  EXPECT_NEAR(length(v.at - Vec3{0, 0.5, 0}), 0, 1e-6);
  EXPECT_EQ(v.fov_axis, Viewpoint::FovAxis::vertical);
  EXPECT_NEAR(v.angle_deg, 0.6 * kDeg, 1e-3);
  EXPECT_EQ(v.xres, 768) << "the camera's aspect, 512 px tall";
  EXPECT_EQ(v.yres, 512);
}

TEST(FileCamera, CameraNamePicksAnOrthographicCameraAndAnUnknownNameListsThem) {
  test::TempDir dir;
  const std::string path = two_camera_gltf(dir);
  const SceneDesc d = read_mesh_file(path, {}, nullptr, {"top", {}});
  ASSERT_TRUE(d.viewpoint);
  EXPECT_EQ(d.viewpoint->camera, "top");
  EXPECT_DOUBLE_EQ(d.viewpoint->ortho_size, 4) << "glTF's xmag is half the width";
  EXPECT_EQ(d.viewpoint->fov_axis, Viewpoint::FovAxis::horizontal);
  try {
    read_mesh_file(path, {}, nullptr, {"far", {}});
    FAIL() << "no camera 'far'";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "camera name: '" + path + "' has no camera 'far' (its cameras: 'near', 'top')");
  }
  test::write_text(dir.file("s.nff"), "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 40\nhither 1\nresolution 8 8\ns 0 0 0 1\n");
  EXPECT_THROW(read_scene_file(dir.file("s.nff"), nullptr, {"near", {}}), std::invalid_argument);
}

TEST(FileCamera, OrthographicViewCastsParallelRaysAndProjectsBack) {
  test::TempDir dir;
  const SceneDesc d = read_mesh_file(two_camera_gltf(dir), {}, nullptr, {"top", {}});
  // 200 x 100 px at the camera's own aspect (xmag / ymag = 2): 4 wide, 2 tall.
  const PinholeDesc pd = view_of(*d.viewpoint, 200, 100);
  EXPECT_DOUBLE_EQ(pd.ortho_height, 2);
  const PinholeCamera cam(pd);
  const PixelLine a = cam.line(0, 0, 0.5, 0.5), b = cam.line(199, 99, 0.5, 0.5);
  EXPECT_NEAR(length(a.dir - Vec3{0, 0, -1}), 0, 1e-12);
  EXPECT_NEAR(length(b.dir - a.dir), 0, 1e-12) << "parallel rays";
  EXPECT_NEAR(b.origin.x - a.origin.x, 4 * 199.0 / 200, 1e-9);
  EXPECT_NEAR(a.origin.y - b.origin.y, 2 * 99.0 / 100, 1e-9);
  PanelHit h;
  ASSERT_TRUE(cam.project(b.origin + b.dir * 3.0, h));
  EXPECT_EQ(h.i, 199);
  EXPECT_EQ(h.j, 99);
  EXPECT_NEAR(h.t, 3, 1e-9);
}

TEST(FileCamera, TheAngleSpansTheAxisItsFormatNames) {
  Viewpoint v;
  v.angle_deg = 90;
  v.fov_axis = Viewpoint::FovAxis::horizontal;
  EXPECT_NEAR(v.vertical_angle_deg(200, 100), 2 * std::atan(0.5) * kDeg, 1e-9);
  EXPECT_NEAR(v.vertical_angle_deg(100, 200), 2 * std::atan(2.0) * kDeg, 1e-9);
  v.fov_axis = Viewpoint::FovAxis::larger;  // Blender's sensor fit "auto"
  EXPECT_NEAR(v.vertical_angle_deg(200, 100), 2 * std::atan(0.5) * kDeg, 1e-9);
  EXPECT_NEAR(v.vertical_angle_deg(100, 200), 90, 1e-9);
  v.fov_axis = Viewpoint::FovAxis::vertical;
  EXPECT_NEAR(v.vertical_angle_deg(200, 100), 90, 1e-9);
}

TEST(FileCamera, ColladaXfovAndFbxFieldOfViewAreHorizontalBlendersOnTheLargerSide) {
  NEED_MODELS();
  // duck.dae: yfov 37.8492 with aspect_ratio 1.5 (Blender: 54.43 deg wide).
  const SceneDesc duck = read_mesh_file(kModels + "Collada/duck.dae");
  EXPECT_NEAR(duck.viewpoint->vertical_angle_deg(duck.viewpoint->xres, duck.viewpoint->yres), 37.8492, 1e-3);
  EXPECT_EQ(duck.viewpoint->fov_axis, Viewpoint::FovAxis::horizontal);
  // Blender's default scene: a 35 mm lens on a 32 mm sensor, 49.13 deg.
  const SceneDesc blend = read_mesh_file(kModels + "BLEND/BlenderDefault_276.blend");
  EXPECT_NEAR(blend.viewpoint->angle_deg, 2 * std::atan(16.0 / 35) * kDeg, 1e-3);
  EXPECT_EQ(blend.viewpoint->fov_axis, Viewpoint::FovAxis::larger);
  // Written by Blender's FBX exporter: FieldOfView = the horizontal angle.
  const SceneDesc fbx = read_mesh_file(kModels + "FBX/global_settings.fbx");
  EXPECT_NEAR(fbx.viewpoint->angle_deg, 49.1343, 1e-3);
  EXPECT_EQ(fbx.viewpoint->fov_axis, Viewpoint::FovAxis::horizontal);
}

TEST(FileCamera, ThreeDsAndAseCamerasOfOneSceneAgree) {
  NEED_MODELS();
  // 3ds Max wrote the same scene as 3DS (lens 53.33) and ASE (CAMERA_FOV
  // 0.7854 rad): both are 45 degrees wide.
  const SceneDesc tds = read_mesh_file(kModels + "3DS/CameraRollAnim.3ds");
  const SceneDesc ase = read_mesh_file(kModels + "ASE/CameraRollAnim.ase");
  EXPECT_NEAR(tds.viewpoint->angle_deg, 45, 0.01);
  EXPECT_NEAR(ase.viewpoint->angle_deg, 45, 0.01);
  EXPECT_EQ(tds.viewpoint->fov_axis, Viewpoint::FovAxis::horizontal);
}

TEST(FileCamera, FocusDistancePlacesTheLensArrayAlongTheView) {
  test::TempDir dir;
  const SceneDesc d = read_mesh_file(two_camera_gltf(dir));
  FrameCameraDesc fd;
  ArraySettings array;
  array.lenses_x = array.lenses_y = 4;
  fd.kind = FrameCameraDesc::Integral{array};
  const FrameCamera at_centre = make_frame_camera(fd, d.viewpoint, "c.gltf");
  fd.focus_distance = 2;
  const FrameCamera at_two = make_frame_camera(fd, d.viewpoint, "c.gltf");
  EXPECT_NEAR(length(at_centre.lens_array()->desc().frame.origin - Vec3{0, 0.5, 0}), 0, 1e-9);
  EXPECT_NEAR(length(at_two.lens_array()->desc().frame.origin - Vec3{0, 0.5, 3}), 0, 1e-9);
  // The array spans the camera's field where it stands: 2 d tan(yfov / 2).
  EXPECT_NEAR(at_two.lens_array()->desc().pitch * 4, 2 * 2 * std::tan(0.3), 1e-6);  // yfov in float
  fd.focus_distance = -1;
  EXPECT_THROW(make_frame_camera(fd, d.viewpoint, "c.gltf"), std::invalid_argument);
}

TEST(FileCamera, ClippingPlanesBoundWhatThePinholeViewSees) {
  // A unit sphere 4 ahead: its surface lies 3 to 5 along the axis.
  const SceneDesc desc = parse_nff("v\nfrom 0 -4 0\nat 0 0 0\nup 0 0 1\nangle 50\nhither 0\nresolution 32 32\n"
                                   "l 0 -5 5\nf 1 1 1 1 0 0 0 1\ns 0 0 0 1\n",
                                   "sphere.nff");
  const RenderScene scene(desc);
  auto view = [&](double near, double far) {
    PinholeDesc d{desc.viewpoint->from, desc.viewpoint->at, desc.viewpoint->up, 50, 32, 32};
    d.clip_near = near, d.clip_far = far;
    RenderOptions ro;
    ro.aovs.id = ro.aovs.depth = true;
    RenderStats stats;
    return render_view(scene, PinholeCamera(d), ro, stats);
  };
  auto hits = [](const FrameBuffers& fb) {
    int n = 0;
    for (int j = 0; j < 32; ++j)
      for (int i = 0; i < 32; ++i) n += *fb.id.at(i, j) >= 0;
    return n;
  };
  const int whole = hits(view(0, INFINITY));
  EXPECT_GT(whole, 100);
  EXPECT_EQ(hits(view(0, 2.9)), 0) << "the sphere lies beyond the far plane";
  EXPECT_EQ(hits(view(5.1, INFINITY)), 0) << "the sphere lies before the near plane";
  // Past the near plane at 4 the view meets the sphere's far side (depth > 4).
  const FrameBuffers cut = view(4, INFINITY);
  EXPECT_GT(hits(cut), 0);
  for (int j = 0; j < 32; ++j)
    for (int i = 0; i < 32; ++i)
      if (*cut.id.at(i, j) >= 0) EXPECT_GT(*cut.depth.at(i, j), 4) << i << "," << j;
  EXPECT_THROW(PinholeCamera(PinholeDesc{{0, 0, 0}, {0, 1, 0}, {0, 0, 1}, 50, 8, 8, false, 0.5, 0.5, 0, 0, 0, 3, 2}),
               std::invalid_argument);
}

TEST(FileCamera, GltfCameraWithoutZfarIsNotClippedFar) {
  test::TempDir dir;
  const SceneDesc d = read_mesh_file(two_camera_gltf(dir));  // "near": znear 0.1, no zfar
  EXPECT_NEAR(d.viewpoint->clip_near, 0.1, 1e-7);
  EXPECT_EQ(d.viewpoint->clip_far, INFINITY) << "glTF 2.0 §5.12: an infinite projection";
  const SceneDesc top = read_mesh_file(dir.file("c.gltf"), {}, nullptr, {"top", {}});
  EXPECT_NEAR(top.viewpoint->clip_far, 100, 1e-5);
}

// ---- textures ----

TEST(TextureSearch, WindowsPathIsFoundByItsBaseNameBesideTheFileThenInTheSearchFolders) {
  test::TempDir dir;
  std::filesystem::create_directories(dir.path / "models" / "FBX");
  std::filesystem::create_directories(dir.path / "models" / "OBJ");
  test::write_text(dir.file("models/OBJ/drkwood2.jpg"), "x");
  const std::string scene = dir.file("models/FBX/spider.fbx");
  const std::string named = R"(D:\projects\assimp\OBJ\drkwood2.jpg)";
  const TextureLookup none = find_texture(named, scene, {});
  EXPECT_FALSE(none.found);
  ASSERT_EQ(none.tried.size(), 1u) << "another machine's drive: only the base name is looked for";
  EXPECT_EQ(none.tried[0], dir.file("models/FBX/drkwood2.jpg"));
  const TextureLookup found = find_texture(named, scene, {dir.file("models/none"), dir.file("models/OBJ")});
  ASSERT_TRUE(found.found);
  EXPECT_EQ(*found.found, dir.file("models/OBJ/drkwood2.jpg"));
  EXPECT_EQ(found.tried.size(), 3u);
}

TEST(TextureSearch, RelativeAndBackslashedPathsComeFirstAndCaseIsForgivenByBaseName) {
  test::TempDir dir;
  std::filesystem::create_directories(dir.path / "tex");
  test::write_text(dir.file("tex/Wood.JPG"), "x");
  test::write_text(dir.file("wood.jpg"), "y");
  const std::string scene = dir.file("s.obj");
  EXPECT_EQ(find_texture(R"(tex\Wood.JPG)", scene, {}).found.value_or(""), dir.file("tex/Wood.JPG"));
  EXPECT_EQ(find_texture("/elsewhere/tex/WOOD.jpg", scene, {}).found.value_or(""), dir.file("wood.jpg"));
  EXPECT_EQ(find_texture("/elsewhere/WOOD.JPG", dir.file("tex/s.obj"), {}).found.value_or(""), dir.file("tex/Wood.JPG"));
  EXPECT_EQ(texture_base_name(R"(C:\a/b\c.png)"), "c.png");
}

TEST(TextureSearch, AMissingTextureWarnsNamingEveryPlaceLookedAt) {
  NEED_MODELS();
  const std::string spider = kModels + "FBX/spider.fbx";
  const SceneDesc lost = read_mesh_file(spider);
  bool named = false;
  for (const std::string& w : lost.warnings)
    if (w.find("cannot read texture 'D:\\projects\\assimp_int\\test\\models\\OBJ\\drkwood2.jpg' (not found; looked for " +
               kModels + "FBX/drkwood2.jpg)") != std::string::npos)
      named = true;
  EXPECT_TRUE(named) << (lost.warnings.empty() ? "no warning" : lost.warnings[0]);
  const SceneDesc found = read_mesh_file(spider, {}, nullptr, {"", {kModels + "OBJ"}});
  for (const std::string& w : found.warnings) EXPECT_EQ(w.find("texture"), std::string::npos) << w;
}

}  // namespace
}  // namespace holoray
