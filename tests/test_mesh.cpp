// Meshes through assimp (scene/mesh_reader.hpp, issue 13 item 4): the same
// mesh written in every format renders the same EIA, an OBJ gives the image
// of the same triangles written as NFF (the independent reader), the MTL
// values land where docs/mesh-import.md says, the default view frames the
// mesh, and bad files are refused with the file named.
#include <gtest/gtest.h>

#include <assimp/Exporter.hpp>
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <fmt/format.h>

#include <algorithm>

#include "camera/pinhole.hpp"
#include "image/metrics.hpp"
#include "render/renderer.hpp"
#include "render/view_renderer.hpp"
#include "scene/mesh_reader.hpp"
#include "scene/nff_reader.hpp"
#include "test_util.hpp"

namespace holoray {
namespace {

// A box on a floor, as triangles, no material (each format's importer makes
// up its own: the reader must map them all to holoray's default).
constexpr const char* kBoxObj =
    "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
    "v -4 -1.01 -4\nv 4 -1.01 -4\nv 4 -1.01 4\nv -4 -1.01 4\n"
    "f 1 4 3\nf 1 3 2\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n"
    "f 9 12 11\nf 9 11 10\n";

FrameBuffers render_eia(const SceneDesc& desc) {
  ArraySettings s;
  s.lenses_x = s.lenses_y = 24;
  s.pixels_per_lens = 8;
  const RenderScene scene(desc);
  RenderStats stats;
  return render_frame(scene, LensArray(place_array(s, desc.viewpoint)), RenderOptions{}, stats);
}

TEST(MeshImport, SameMeshFromEveryFormatRendersTheSameEia) {
  test::TempDir dir;
  test::write_text(dir.file("box.obj"), kBoxObj);
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(dir.file("box.obj"), aiProcess_Triangulate);
  ASSERT_NE(scene, nullptr) << importer.GetErrorString();
  const FrameBuffers obj = render_eia(read_mesh_file(dir.file("box.obj")));
  ASSERT_GT(*std::max_element(obj.colour.data.begin(), obj.colour.data.end()), 0.2f) << "the box is seen and lit";
  Assimp::Exporter exporter;
  for (const auto& [format, ext] : {std::pair{"ply", "ply"}, {"stlb", "stl"}, {"gltf2", "gltf"}, {"glb2", "glb"}}) {
    SCOPED_TRACE(format);
    const std::string path = dir.file(std::string("box.") + ext);
    ASSERT_EQ(exporter.Export(scene, format, path), AI_SUCCESS) << exporter.GetErrorString();
    const FrameBuffers other = render_eia(read_mesh_file(path));
    EXPECT_GE(compare_images(obj.colour, other.colour).psnr_all(), 50);
  }
}

// The OBJ's triangles, its default view and light written out as NFF (17
// significant digits) and read by the NFF reader: the same image bit for bit.
TEST(MeshImport, ObjRendersAsTheSameTrianglesWrittenAsNff) {
  test::TempDir dir;
  test::write_text(dir.file("box.obj"), kBoxObj);
  const SceneDesc mesh = read_mesh_file(dir.file("box.obj"));
  ASSERT_TRUE(mesh.viewpoint);
  const Viewpoint& v = *mesh.viewpoint;
  auto vec = [](const Vec3& p) { return fmt::format("{:.17g} {:.17g} {:.17g}", p.x, p.y, p.z); };
  std::string nff = fmt::format("v\nfrom {}\nat {}\nup {}\nangle {:.17g}\nhither 0\nresolution 64 64\n", vec(v.from),
                                vec(v.at), vec(v.up), v.angle_deg);
  ASSERT_EQ(mesh.lights.size(), 1u);
  nff += fmt::format("l {}\nf 0.8 0.8 0.8 1 0 0 0 1\n", vec(mesh.lights[0].position));
  for (const ObjectDesc& o : mesh.objects) {
    const auto& m = std::get<TriangleMeshDesc>(o.shape);
    for (const auto& t : m.triangles) {
      nff += "p 3\n";
      for (uint32_t k : t) nff += vec(m.vertices[k]) + "\n";
    }
  }
  const FrameBuffers a = render_eia(mesh), b = render_eia(parse_nff(nff, "box.nff"));
  EXPECT_EQ(a.colour.data, b.colour.data);
}

// One triangle in `dir`/m.obj using the first material of `mtl` (m.mtl).
SceneDesc triangle_with(const test::TempDir& dir, const std::string& mtl) {
  test::write_text(dir.file("m.mtl"), mtl);
  const std::string name = mtl.substr(7, mtl.find('\n') - 7);  // after "newmtl "
  test::write_text(dir.file("m.obj"), "mtllib m.mtl\nusemtl " + name + "\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  return read_mesh_file(dir.file("m.obj"));
}

TEST(MeshImport, MtlValuesMapToTheWhittedMaterial) {
  test::TempDir dir;
  const SceneDesc d = triangle_with(dir, "newmtl glass\nKd 0.25 0.5 0.75\nNs 40\nd 0.25\nNi 1.3\n");
  ASSERT_EQ(d.objects.size(), 1u);
  const Material& m = d.materials.at(static_cast<size_t>(d.objects[0].material));
  EXPECT_NEAR(m.colour.x, 0.25, 1e-6);
  EXPECT_NEAR(m.colour.y, 0.5, 1e-6);
  EXPECT_NEAR(m.colour.z, 0.75, 1e-6);
  EXPECT_EQ(m.kd, 1);
  EXPECT_EQ(m.ks, 0) << "no reflectivity: NFF's Ks would make it a mirror";
  EXPECT_NEAR(m.shine, 40, 1e-6);
  EXPECT_NEAR(m.transmittance, 0.75, 1e-6);
  EXPECT_NEAR(m.ior, 1.3, 1e-6);
}

TEST(MeshImport, DefaultViewShowsTheWholeMesh) {
  test::TempDir dir;
  test::write_text(dir.file("box.obj"), kBoxObj);
  const SceneDesc d = read_mesh_file(dir.file("box.obj"));
  const Viewpoint& v = *d.viewpoint;
  const PinholeCamera cam(PinholeDesc{v.from, v.at, v.up, v.angle_deg, 200, 200});
  for (const ObjectDesc& o : d.objects)
    for (const Vec3& p : std::get<TriangleMeshDesc>(o.shape).vertices) {
      PanelHit h;
      ASSERT_TRUE(cam.project(p, h));
      EXPECT_GT(h.i, 5);
      EXPECT_LT(h.i, 194);
      EXPECT_GT(h.j, 5);
      EXPECT_LT(h.j, 194);
    }
}

TEST(MeshImport, MissingTextureIsNamedInAWarningAndShownAsAChecker) {
  test::TempDir dir;
  test::write_text(dir.file("m.mtl"), "newmtl wood\nKd 0.6 0.4 0.2\nmap_Kd wood.png\n");
  test::write_text(dir.file("m.obj"),
                   "mtllib m.mtl\nusemtl wood\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n");
  const SceneDesc d = read_mesh_file(dir.file("m.obj"));
  ASSERT_EQ(d.warnings.size(), 1u);
  EXPECT_EQ(d.warnings[0], dir.file("m.obj") +
                               ": warning: material 'wood': cannot read texture 'wood.png' (not found; looked for " +
                               dir.file("wood.png") + "): a checker shows where it goes");
  const Material& m = d.materials.at(static_cast<size_t>(d.objects.at(0).material));
  ASSERT_GE(m.texture, 0);
  const ImageMap& img = d.images.at(static_cast<size_t>(d.textures.at(static_cast<size_t>(m.texture)).image));
  EXPECT_EQ(img.width, 8);
  EXPECT_EQ(img.rgb[0], 255);  // magenta
  EXPECT_EQ(img.rgb[1], 0);
  EXPECT_EQ(img.rgb[3], 40);  // dark grey beside it
}

TEST(MeshImport, TexturedMaterialOnAMeshWithoutTextureCoordinatesIsNamed) {
  test::TempDir dir;
  const SceneDesc d = triangle_with(dir, "newmtl wood\nKd 0.6 0.4 0.2\nmap_Kd wood.png\n");
  ASSERT_EQ(d.warnings.size(), 2u);
  EXPECT_EQ(d.warnings[1], dir.file("m.obj") +
                               ": warning: mesh 'defaultobject': its material's texture reads texture coordinate set "
                               "0, which the mesh does not have (it has 0): the texture is not applied");
  EXPECT_TRUE(std::get<TriangleMeshDesc>(d.objects.at(0).shape).uvs.empty());
}

// glTF materials need no name: an unnamed one keeps its base colour, and a
// primitive without a material takes holoray's grey (assimp's stand-in for
// it is unnamed too, and last).
TEST(MeshImport, UnnamedGltfMaterialKeepsItsColourAndNoMaterialIsTheDefaultGrey) {
  test::TempDir dir;
  test::write_text(dir.file("u.gltf"), R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
 "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "material": 0}, {"attributes": {"POSITION": 0}}]}],
 "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [1, 0, 0, 1]}}],
 "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,AACAvwAAgL8AAAAAAACAPwAAgL8AAAAAAAAAAAAAgD8AAAAA"}],
 "bufferViews": [{"buffer": 0, "byteLength": 36}],
 "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [-1, -1, 0], "max": [1, 1, 0]}]})");
  const SceneDesc d = read_mesh_file(dir.file("u.gltf"));
  ASSERT_EQ(d.objects.size(), 2u);
  const Material& red = d.materials.at(static_cast<size_t>(d.objects[0].material));
  const Material& none = d.materials.at(static_cast<size_t>(d.objects[1].material));
  EXPECT_EQ(red.colour.x, 1);
  EXPECT_EQ(red.colour.y, 0);
  EXPECT_DOUBLE_EQ(none.colour.x, 0.8);
  EXPECT_DOUBLE_EQ(none.colour.y, 0.8);
}

// A glTF with a camera node and a KHR_lights_punctual point light (both
// placed by their nodes' translations): the view and the light come from
// the file, not from the defaults.
TEST(MeshImport, GltfCameraAndPointLightPlaceTheViewAndLight) {
  test::TempDir dir;
  test::write_text(dir.file("c.gltf"), R"({"asset": {"version": "2.0"},
 "extensionsUsed": ["KHR_lights_punctual"],
 "extensions": {"KHR_lights_punctual": {"lights": [{"type": "point", "color": [1, 0.5, 0.25], "intensity": 1}]}},
 "scene": 0, "scenes": [{"nodes": [0, 1, 2]}],
 "nodes": [{"mesh": 0}, {"camera": 0, "translation": [0, 0.5, 5]},
           {"extensions": {"KHR_lights_punctual": {"light": 0}}, "translation": [1, 2, 3]}],
 "cameras": [{"type": "perspective", "perspective": {"yfov": 0.6, "aspectRatio": 1.5, "znear": 0.1}}],
 "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
 "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,AACAvwAAgL8AAAAAAACAPwAAgL8AAAAAAAAAAAAAgD8AAAAA"}],
 "bufferViews": [{"buffer": 0, "byteLength": 36}],
 "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [-1, -1, 0], "max": [1, 1, 0]}]})");
  const SceneDesc d = read_mesh_file(dir.file("c.gltf"));
  ASSERT_EQ(d.objects.size(), 1u);
  ASSERT_TRUE(d.viewpoint);
  const Viewpoint& v = *d.viewpoint;
  EXPECT_NEAR(length(v.from - Vec3{0, 0.5, 5}), 0, 1e-6);
  EXPECT_NEAR(length(normalize(v.at - v.from) - Vec3{0, 0, -1}), 0, 1e-6) << "glTF cameras look down -z";
  EXPECT_NEAR(length(normalize(v.up) - Vec3{0, 1, 0}), 0, 1e-6);
  // A wide view (aspect 1.5): assimp's horizontal angle is made from yfov
  // differently in each version; the vertical angle is the file's.
  EXPECT_NEAR(v.angle_deg, 0.6 * 180 / 3.14159265358979, 1e-3) << "the file's vertical angle";
  ASSERT_EQ(d.lights.size(), 1u);
  EXPECT_NEAR(length(d.lights[0].position - Vec3{1, 2, 3}), 0, 1e-6);
  EXPECT_NEAR(d.lights[0].colour.y / d.lights[0].colour.x, 0.5, 1e-6);
}

}  // namespace
}  // namespace holoray
