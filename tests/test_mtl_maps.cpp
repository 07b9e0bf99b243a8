// MTL's specular and bump maps (scene/bump_map.hpp, scene/mesh_reader,
// render/shading): a quad under the stand-in light at the eye, whose
// shading each map changes by an amount worked out here from the geometry.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <string>

#include "camera/pinhole.hpp"
#include "image/image_io.hpp"
#include "render/render_scene.hpp"
#include "render/view_renderer.hpp"
#include "scene/bump_map.hpp"
#include "scene/mesh_reader.hpp"
#include "test_util.hpp"

namespace holoray {
namespace {

// The red code of texel (x, y) of an 8-bit image map (rows v up).
int red_code(const ImageMap& m, int x, int y) { return m.rgb[(size_t(y) * size_t(m.width) + size_t(x)) * 3]; }

TEST(BumpMaps, AHeightRampBecomesTheNormalOfItsSlope) {
  ImageMap ramp;
  ramp.width = 12, ramp.height = 4;
  ramp.rgb.resize(12 * 4 * 3);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 12; ++x)
      for (int c = 0; c < 3; ++c) ramp.rgb[(size_t(y) * 12 + size_t(x)) * 3 + size_t(c)] = static_cast<unsigned char>(20 * x);
  ASSERT_TRUE(is_grey(ramp));
  const ImageMap n = normals_from_heights(ramp, 5);
  // Rising 20 codes a texel along u: the surface faces -u.
  const double s = 5 * 20 / 255.0, len = std::sqrt(s * s + 1);
  for (int x = 1; x < 11; ++x) {
    EXPECT_EQ(red_code(n, x, 2), std::lround((1 - s / len) * 0.5 * 255)) << x;
    EXPECT_EQ(n.rgb[(2 * 12 + size_t(x)) * 3 + 1], 128) << "no slope along v";
    EXPECT_EQ(n.rgb[(2 * 12 + size_t(x)) * 3 + 2], std::lround((1 + 1 / len) * 0.5 * 255));
  }
  EXPECT_GT(red_code(n, 0, 2), 128) << "the edge repeats: the drop from 220 to 0 faces +u";
  EXPECT_FALSE(n.srgb);
  ramp.rgb[5] = 0;  // one texel's blue differs
  EXPECT_FALSE(is_grey(ramp));
}

// A quad over [-1, 1]^2 at z = 0 with material `mtl` (its first `newmtl`),
// coordinates (0, 0) to (1, 1), seen from `eye` looking at the origin
// through 33x33 pixels (pixel 16 sees the origin), lit by the reader's
// stand-in light (at `light`, placed by the file's default view).
struct LitQuad {
  SceneDesc desc;
  ImageBuffer colour;
  double ambient = 0, intensity = 0;
  Vec3 light;
  std::optional<PinholeCamera> camera;
  /// Where pixel (i, 16)'s line meets the quad's plane.
  Vec3 hit(int i) const {
    const PixelLine l = camera->line(i, 16);
    return l.origin + l.dir * (-l.origin.z / l.dir.z);
  }
};

LitQuad lit_quad(const test::TempDir& dir, const std::string& name, const std::string& mtl, const Vec3& eye) {
  test::write_text(dir.file(name + ".mtl"), mtl);
  const std::string material = mtl.substr(7, mtl.find('\n') - 7);
  test::write_text(dir.file(name + ".obj"), "mtllib " + name + ".mtl\nusemtl " + material +
                                                "\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\n"
                                                "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\n"
                                                "f 1/1/1 2/2/1 3/3/1 4/4/1\n");
  LitQuad q;
  q.desc = read_mesh_file(dir.file(name + ".obj"));
  PinholeDesc pd;
  pd.from = eye;
  pd.at = {0, 0, 0};
  pd.up = {0, 1, 0};
  pd.fov_deg = 20;
  pd.width = pd.height = 33;
  const RenderScene scene(q.desc);
  q.ambient = scene.ambient().x;
  q.intensity = scene.lights().at(0).intensity.x;
  q.light = scene.lights().at(0).position;
  q.camera.emplace(pd);
  RenderStats stats;
  q.colour = render_view(scene, *q.camera, RenderOptions{}, stats).colour;
  return q;
}

// The quad's centre lit from L (the stand-in light's direction) at N.L =
// L.z when flat. A height ramp rising along u tilts the normal toward -x:
// N.L becomes (L.z - s L.x) / sqrt(1 + s^2), s the slope times -bm; a `norm`
// map holding that normal gives the same; the slope's sign reversed would
// give (L.z + s L.x) / sqrt(1 + s^2) instead.
TEST(BumpMaps, ABumpRampAndItsNormalMapTiltTheLightAsTheSlopeSays) {
  test::TempDir dir;
  test::write_image_of(dir.file("ramp.png"), 12, 12, [](int x, int, int) { return static_cast<float>(20 * x) / 255.0f; });
  const double s = 5 * 20 / 255.0, len = std::sqrt(1 + s * s);
  const float tilted[3] = {static_cast<float>((1 - s / len) / 2), 0.5f, static_cast<float>((1 + 1 / len) / 2)};
  test::write_image_of(dir.file("normals.png"), 12, 12, [&](int, int, int c) { return tilted[c]; });
  const Vec3 eye{0, 0, 5};
  const LitQuad flat = lit_quad(dir, "flat", "newmtl grey\nKd 0.8 0.8 0.8\n", eye);
  const LitQuad bump = lit_quad(dir, "bump", "newmtl grey\nKd 0.8 0.8 0.8\nbump -bm 5 ramp.png\n", eye);
  const LitQuad norm = lit_quad(dir, "norm", "newmtl grey\nKd 0.8 0.8 0.8\nnorm normals.png\n", eye);
  auto n_dot_l = [](const LitQuad& q) {
    return (q.colour.at(16, 16)[0] / 0.8 - q.ambient) / q.intensity;
  };
  const Vec3 l = normalize(flat.light);
  ASSERT_GT(l.x, 0.3) << "the light is off the axis: the tilt's sign shows";
  const double flat_cos = l.z, tilted_cos = (l.z - s * l.x) / len;
  EXPECT_NEAR(n_dot_l(flat), flat_cos, 1e-5);
  EXPECT_NEAR(n_dot_l(bump), tilted_cos, 5e-3) << "8-bit normals";
  EXPECT_NEAR(n_dot_l(norm), tilted_cos, 5e-3);
  // -bm scales a normal map's x and y: 0 leaves the flat normal.
  const LitQuad none = lit_quad(dir, "none", "newmtl grey\nKd 0.8 0.8 0.8\nnorm -bm 0 normals.png\n", eye);
  EXPECT_NEAR(n_dot_l(none), flat_cos, 5e-3);
}

// MTL's highlight adds Ks (N.H)^Ns times the light's intensity, H halfway
// between the directions to the eye and to the light at the hit. map_Ks
// scales it by its texel: none on its black right quarter. Without
// `illum 2`, or with Ns below 1, there is no highlight.
TEST(MtlHighlights, KsAddsTheBlinnPhongHighlightWhereMapKsAllowsIt) {
  test::TempDir dir;
  test::write_image_of(dir.file("spec.png"), 8, 8, [](int x, int, int) { return x < 6 ? 1.0f : 0.0f; });
  const Vec3 eye{0, 0, 5};
  const std::string base = "newmtl shiny\nKd 0.5 0.5 0.5\nKs 0.4 0.2 0.1\nNs 30\n";
  const LitQuad dull = lit_quad(dir, "dull", base, eye);
  const LitQuad shiny = lit_quad(dir, "shiny", base + "illum 2\n", eye);
  const LitQuad mapped = lit_quad(dir, "mapped", base + "illum 2\nmap_Ks spec.png\n", eye);
  auto highlight = [&](const LitQuad& q, int x, int c) { return q.colour.at(x, 16)[c] - dull.colour.at(x, 16)[c]; };
  auto expected = [&](int x, double ks) {
    const Vec3 p = shiny.hit(x);
    const Vec3 h = normalize(normalize(eye - p) + normalize(shiny.light - p));
    return ks * shiny.intensity * std::pow(h.z, 30);
  };
  const double ks[3] = {0.4, 0.2, 0.1};
  for (int x : {10, 16, 20})
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(highlight(shiny, x, c), expected(x, ks[c]), 1e-5) << x << " " << c;
      EXPECT_NEAR(highlight(mapped, x, c), expected(x, ks[c]), 1e-5) << "map_Ks is white there";
    }
  // Pixel 31 sees u = 0.9: map_Ks is black there.
  EXPECT_GT(highlight(shiny, 31, 0), 0.01);
  EXPECT_NEAR(highlight(mapped, 31, 0), 0, 1e-6);
  EXPECT_EQ(dull.desc.materials.back().model, ShadingModel::nff) << "no illum: no highlight";
  // Ns 0 (an exporter's "no gloss"): no highlight, not Ks added everywhere.
  const LitQuad flat = lit_quad(dir, "flat", "newmtl shiny\nKd 0.5 0.5 0.5\nKs 0.4 0.2 0.1\nNs 0\nillum 2\n", eye);
  EXPECT_EQ(flat.colour.data, dull.colour.data);
}

}  // namespace
}  // namespace holoray
