// Polygon tessellation: concave faces must not be fanned (nff-notes §8), and
// `pp` shading normals are turned into the winding hemisphere (§9).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "scene/nff_reader.hpp"
#include "scene/tessellate.hpp"
#include "test_util.hpp"

using namespace holoray;

namespace {

// Signed area of a planar polygon about `n` (shoelace in 3D).
double polygon_area(const std::vector<Vec3>& v, const Vec3& n) {
  Vec3 sum;
  for (size_t i = 0; i < v.size(); ++i) sum += cross(v[i], v[(i + 1) % v.size()]);
  return 0.5 * dot(sum, n);
}

double triangle_area(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& n) { return 0.5 * dot(cross(b - a, c - a), n); }

// A gear-like star: concave, like the SPD gear faces.
std::vector<Vec3> star(int teeth, double r_in, double r_out, const Vec3& offset) {
  std::vector<Vec3> v;
  for (int k = 0; k < 2 * teeth; ++k) {
    const double a = k * std::numbers::pi / teeth, r = (k % 2) ? r_in : r_out;
    v.push_back(offset + Vec3{r * std::cos(a), 0.3 * r * std::sin(a), r * std::sin(a)});
  }
  return v;
}

// Every triangle wound like the polygon and their areas summing to the
// polygon's: a fan over a concave polygon fails this (overlaps count twice).
void expect_exact_cover(const std::vector<Vec3>& v) {
  const Tessellation t = tessellate_polygon(v);
  ASSERT_FALSE(t.triangles.empty());
  double sum = 0;
  for (const auto& tri : t.triangles) {
    const double a = triangle_area(v[tri[0]], v[tri[1]], v[tri[2]], t.normal);
    EXPECT_GT(a, 0);
    sum += a;
  }
  const double area = polygon_area(v, t.normal);
  EXPECT_GT(area, 0);
  EXPECT_NEAR(sum, area, 1e-9 * area);
}

}  // namespace

TEST(Tessellate, ConcaveStarIsCoveredExactly) { expect_exact_cover(star(12, 0.6, 1.0, {1, 2, 3})); }

TEST(Tessellate, FanOfTheSameStarWouldNotBe) {
  // Guards the test above: it can fail. A fan from vertex 0 has triangles of both windings.
  const auto v = star(12, 0.6, 1.0, {0, 0, 0});
  const Vec3 n = polygon_normal(v);
  int backwards = 0;
  for (size_t k = 1; k + 1 < v.size(); ++k) backwards += triangle_area(v[0], v[k], v[k + 1], n) < 0;
  EXPECT_GT(backwards, 0);
}

TEST(Tessellate, WindingNormalFollowsCounterClockwiseSide) {
  const std::vector<Vec3> ccw{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  EXPECT_EQ(polygon_normal(ccw), (Vec3{0, 0, 1}));
  const std::vector<Vec3> cw(ccw.rbegin(), ccw.rend());
  EXPECT_EQ(polygon_normal(cw), (Vec3{0, 0, -1}));
}

TEST(Tessellate, DegenerateFirstCornerStillGivesTheRightNormal) {
  // Repeated first vertex (as in teapot_s1): the first three vertices define no plane.
  const std::vector<Vec3> v{{0, 0, 0}, {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  EXPECT_EQ(polygon_normal(v), (Vec3{0, 0, 1}));
  expect_exact_cover(v);
}

TEST(Tessellate, ZeroAreaPolygonGivesNoTriangles) {
  const std::vector<Vec3> v{{0, 0, 0}, {1, 1, 1}, {2, 2, 2}};
  EXPECT_TRUE(tessellate_polygon(v).triangles.empty());
}

TEST(Tessellate, CollinearVerticesAreHarmless) {
  expect_exact_cover({{0, 0, 0}, {0.5, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0.5, 1, 0}, {0, 1, 0}});
}

TEST(Tessellate, PatchNormalFlippedIntoWindingHemisphere) {
  const Vec3 winding{0, 0, 1};
  EXPECT_EQ(shading_normal_in_hemisphere({0, 0.6, -0.8}, winding), (Vec3{0, -0.6, 0.8}));
  EXPECT_EQ(shading_normal_in_hemisphere({0, 0.6, 0.8}, winding), (Vec3{0, 0.6, 0.8}));
  EXPECT_EQ(shading_normal_in_hemisphere({0, 0, 0}, winding), winding);
}

namespace {

// The concave 144-vertex gear faces of the SPD's gears_s1.
std::vector<std::vector<Vec3>> gear_faces() {
  const SceneDesc s = read_nff_file(test::shared_dir() + "/scenes/nff/gears_s1.nff");
  std::vector<std::vector<Vec3>> faces;
  for (const auto& o : s.objects)
    if (const auto* p = std::get_if<PolygonDesc>(&o.shape); p && p->vertices.size() >= 100) faces.push_back(p->vertices);
  return faces;
}

}  // namespace

TEST(Tessellate, EveryGearFaceIsCoveredExactly) {
  if (!test::have_shared_scenes()) GTEST_SKIP() << "no ../shared/scenes";
  const auto faces = gear_faces();
  EXPECT_FALSE(faces.empty());
  for (const auto& f : faces) expect_exact_cover(f);
}

namespace {

// The summed surface areas of the triangles' world bounding boxes, over
// twice the face's area: what a BVH's rays pay for the face (its SAH cost;
// 1 for a face tiled by axis-aligned boxes). Slivers fanned across the face
// make it large.
double box_cost(const std::vector<Vec3>& v) {
  const Tessellation t = tessellate_polygon(v);
  double boxes = 0;
  for (const auto& tri : t.triangles) {
    Vec3 lo = v[tri[0]], hi = v[tri[0]];
    for (int k : tri) lo = min(lo, v[k]), hi = max(hi, v[k]);
    const Vec3 e = hi - lo;
    boxes += 2 * (e.x * e.y + e.y * e.z + e.z * e.x);
  }
  return boxes / (2 * std::fabs(polygon_area(v, t.normal)));
}

}  // namespace

// The ear with the smallest bounding box goes first: the SPD gear faces
// become fat triangles, not slivers across the face (2.5 here; clipping the
// first ear found gave 20.1), and a star the same.
TEST(Tessellate, GearFacesBecomeFatTrianglesNotSlivers) {
  if (!test::have_shared_scenes()) GTEST_SKIP() << "no ../shared/scenes";
  const auto faces = gear_faces();
  EXPECT_FALSE(faces.empty());
  for (size_t k = 0; k < faces.size(); ++k) EXPECT_LT(box_cost(faces[k]), 5.0) << "face " << k;
  EXPECT_LT(box_cost(star(40, 1.0, 1.2, {0, 0, 0})), 5.0);
}
