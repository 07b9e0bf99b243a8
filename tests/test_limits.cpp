// Pathological scenes (issue 5, limits): a scene that would recurse forever
// ends with a ray tree bounded by kMaxRayDepth; counts past the reader's
// limits are refused at the object that crosses them, with its location;
// tens of thousands of primitives render correctly.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include <fmt/format.h>

#include "camera/lens_array.hpp"
#include "render/renderer.hpp"
#include "render/shading.hpp"
#include "scene/nff_reader.hpp"
#include "scene/parse_error.hpp"

using namespace holoray;

namespace {

LensArrayDesc small_array() {
  LensArrayDesc d;
  d.lenses_x = d.lenses_y = 12;
  d.pixels_per_lens = 6;
  d.pitch = 0.25;
  d.gap = 0.7;
  return d;
}

std::string parse_error_headline(const std::string& text, const NffLimits& limits) {
  try {
    parse_nff(text, "big.nff", limits);
  } catch (const ParseError& e) {
    return e.headline();
  }
  return "no error";
}

}  // namespace

// Eight nested glass spheres that both mirror and transmit, inside a closed
// mirror box around the array, recorded pseudoscopic so that eye rays start
// at the array, inside the box (orthoscopic ones would start outside it and
// bounce off its outer faces): no ray ever escapes, so only the depth limit D
// ends the recursion. Every node of the ray tree has at most two children
// (mirror + transmitted), so an eye ray spawns at most 2 + 4 + ... + 2^(D-1)
// = 2^D - 2 secondary rays, and its tree has at most 2^D - 1 nodes, each
// casting at most one shadow ray per light. Every node below the limit has at
// least one child, so the chain reaches the limit: >= D - 1 secondaries.
TEST(PathologicalScenes, EndlessRefractionAndMirrorsStopAtTheDepthLimit) {
  SceneDesc s;
  Material glass;
  glass.kd = 0.1;
  glass.ks = 0.5;
  glass.transmittance = 0.5;
  glass.ior = 1.5;
  Material mirror;
  mirror.kd = 0.1;
  mirror.ks = 0.9;
  s.materials = {glass, mirror};
  for (int k = 1; k <= 8; ++k) s.objects.push_back(ObjectDesc{SphereDesc{{0, 0, 4}, 0.4 * k}, 0, {}});
  const double h = 20;
  const Vec3 c[8] = {{-h, -h, -h}, {h, -h, -h}, {h, h, -h}, {-h, h, -h}, {-h, -h, h}, {h, -h, h}, {h, h, h}, {-h, h, h}};
  const int faces[6][4] = {{0, 1, 2, 3}, {4, 5, 6, 7}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 3, 7, 4}, {1, 2, 6, 5}};
  for (const auto& f : faces) {
    PolygonDesc p;
    for (int v : f) p.vertices.push_back(c[v]);
    s.objects.push_back(ObjectDesc{p, 1, {}});
  }
  s.lights = {Light{{3, 3, 0}, {1, 1, 1}, {}}, Light{{-3, 2, 8}, {1, 1, 1}, {}}};

  RenderScene scene(s);
  EXPECT_EQ(scene.file_max_depth(), kMaxRayDepth);
  LensArrayDesc inside = small_array();
  inside.mode = RecordingMode::pseudoscopic;
  const LensArray cam(inside);
  for (const int depth : {1, 3, kMaxRayDepth, 8}) {
    SCOPED_TRACE(depth);
    RenderSettings settings = file_settings(scene);
    settings.max_depth = depth;
    RenderStats stats;
    const FrameBuffers fb = render_frame(RenderContext(scene, settings), cam, RenderOptions{}, stats);
    const RayCounts& r = stats.rays;
    ASSERT_EQ(r.eye, static_cast<uint64_t>(cam.pixel_count()));  // the box surrounds the array
    const uint64_t secondary = r.reflected + r.refracted, nodes = (uint64_t{1} << depth) - 1;
    EXPECT_LE(secondary, (nodes - 1) * r.eye);
    EXPECT_GE(secondary, static_cast<uint64_t>(depth - 1) * r.eye);
    EXPECT_LE(r.shadow, nodes * s.lights.size() * r.eye);
    for (float v : fb.colour.data) ASSERT_TRUE(std::isfinite(v));
  }
}

// A file with one object too many is refused at that object, before it is stored.
TEST(PathologicalScenes, ObjectsOverTheLimitAreRefusedAtTheFirstOneTooMany) {
  NffLimits limits;
  limits.max_objects = 1000;
  std::string text;
  for (int k = 0; k < 1000; ++k) text += fmt::format("s {} 0 0 0.1\n", k);
  EXPECT_NO_THROW(parse_nff(text, "big.nff", limits));
  text += "s 0 1 0 0.1\n";
  EXPECT_EQ(parse_error_headline(text, limits), "big.nff:1001:1: error: expected at most 1000 objects in one file, found more");
}

TEST(PathologicalScenes, LightsOverTheLimitAreRefusedAtTheFirstOneTooMany) {
  NffLimits limits;
  limits.max_lights = 3;
  const std::string text = "l 0 0 1\nl 0 0 2\nl 0 0 3\ns 0 0 0 1\nl 0 0 4\n";
  EXPECT_EQ(parse_error_headline(text, limits), "big.nff:5:1: error: expected at most 3 lights in one file, found more");
}

// A million degenerate polygons must not keep a million messages: the first
// max_warnings_kept are kept as text, every one is counted.
TEST(PathologicalScenes, WarningsAreCountedButOnlyTheFirstAreKept) {
  NffLimits limits;
  limits.max_warnings_kept = 5;
  std::string text;
  for (int k = 0; k < 40; ++k) text += "p 3\n0 0 0\n1 1 1\n2 2 2\n";
  const SceneDesc s = parse_nff(text, "flat.nff", limits);
  EXPECT_EQ(s.warning_count, 40u);
  ASSERT_EQ(s.warnings.size(), 5u);
  EXPECT_EQ(s.warnings.back().substr(0, 18), "flat.nff:17:1: war");
}

// 40 000 spheres read from NFF text and rendered: every hit lies on the
// surface of the sphere of the grid cell it falls in.
TEST(PathologicalScenes, FortyThousandSpheresRenderOnTheirSurfaces) {
  constexpr int kSide = 200;
  constexpr double kRadius = 0.02, kSpacing = 0.05, kZ = 3;
  std::string text = "l 0 0 -10\nf 1 1 1 1 0 0 0 0\n";
  text.reserve(text.size() + kSide * kSide * 32);
  for (int y = 0; y < kSide; ++y)
    for (int x = 0; x < kSide; ++x)
      text += fmt::format("s {} {} {} {}\n", (x - kSide / 2) * kSpacing, (y - kSide / 2) * kSpacing, kZ, kRadius);
  const SceneDesc desc = parse_nff(text, "grid.nff");
  ASSERT_EQ(desc.objects.size(), static_cast<size_t>(kSide * kSide));

  const RenderScene scene(desc);
  const LensArray cam(small_array());
  RenderOptions opt;
  opt.aovs.depth = true;
  RenderStats stats;
  const FrameBuffers fb = render_frame(scene, cam, opt, stats);
  int hits = 0;
  for (int j = 0; j < cam.height(); ++j)
    for (int i = 0; i < cam.width(); ++i) {
      const float t = *fb.depth.at(i, j);
      if (std::isnan(t)) continue;
      ++hits;
      const PixelLine l = cam.line(i, j);
      const Vec3 p = l.origin + l.dir * static_cast<double>(t);
      const Vec3 centre{std::round(p.x / kSpacing) * kSpacing, std::round(p.y / kSpacing) * kSpacing, kZ};
      ASSERT_NEAR(length(p - centre), kRadius, 1e-4) << i << "," << j;
    }
  EXPECT_GT(hits, cam.pixel_count() / 10);  // the grid fills much of every elemental image
}
