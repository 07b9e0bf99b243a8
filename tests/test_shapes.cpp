// Exact sphere and open-cone intersection (nff-notes §6, §7).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "accel/shapes.hpp"

using namespace holoray;

TEST(Sphere, HitsNearRootThenFarRootFromInside) {
  const Sphere s{{0, 0, 5}, 2};
  double t;
  Vec3 n;
  ASSERT_TRUE(intersect_sphere(s, {0, 0, 0}, {0, 0, 1}, 0, INFINITY, t, n));
  EXPECT_DOUBLE_EQ(t, 3);
  EXPECT_EQ(n, (Vec3{0, 0, -1}));
  ASSERT_TRUE(intersect_sphere(s, {0, 0, 5}, {0, 0, 1}, 0, INFINITY, t, n));  // from the centre
  EXPECT_DOUBLE_EQ(t, 2);
  EXPECT_FALSE(intersect_sphere(s, {0, 2.0001, 0}, {0, 0, 1}, 0, INFINITY, t, n));
}

TEST(Sphere, NegativeRadiusShowsOnlyTheInside) {
  const Sphere s{{0, 0, 5}, -2};
  double t;
  Vec3 n;
  ASSERT_TRUE(intersect_sphere(s, {0, 0, 0}, {0, 0, 1}, 0, INFINITY, t, n));
  EXPECT_DOUBLE_EQ(t, 7);  // the far wall, seen from inside
}

TEST(Sphere, PreciseFromFarAway) {
  const Sphere s{{0, 0, 0}, 1e-3};
  double t;
  Vec3 n;
  ASSERT_TRUE(intersect_sphere(s, {0, 0, -1e6}, {0, 0, 1}, 0, INFINITY, t, n));
  EXPECT_NEAR(t, 1e6 - 1e-3, 1e-9);
}

TEST(Cone, CylinderSideAtTheRadiusWithinItsLength) {
  const Cone c{{0, 0, 0}, {0, 0, 4}, 1, 1};
  double t;
  Vec3 n;
  ASSERT_TRUE(intersect_cone(c, {-5, 0, 2}, {1, 0, 0}, 0, INFINITY, t, n));
  EXPECT_NEAR(t, 4, 1e-12);
  EXPECT_LT(length(n - Vec3{-1, 0, 0}), 1e-12);
  EXPECT_FALSE(intersect_cone(c, {-5, 0, 4.01}, {1, 0, 0}, 0, INFINITY, t, n));  // beyond the apex end
}

TEST(Cone, OpenEndsLetAxialRaysThrough) {
  const Cone c{{0, 0, 0}, {0, 0, 4}, 1, 1};
  double t;
  Vec3 n;
  EXPECT_FALSE(intersect_cone(c, {0, 0, -3}, {0, 0, 1}, 0, INFINITY, t, n));  // no caps
}

TEST(Cone, TruncatedConeRadiusVariesLinearly) {
  const Cone c{{0, 0, 0}, {0, 0, 2}, 2, 0.5};  // radius 1.25 at z = 1
  double t;
  Vec3 n;
  ASSERT_TRUE(intersect_cone(c, {-5, 0, 1}, {1, 0, 0}, 0, INFINITY, t, n));
  EXPECT_NEAR(t, 5 - 1.25, 1e-12);
  // Outward normal tilts up (toward the apex) by atan(slope) = atan(1.5 / 2).
  EXPECT_NEAR(n.z / -n.x, 0.75, 1e-12);
}

TEST(Cone, DoesNotHitTheMirroredNappeBeyondATip) {
  const Cone c{{0, 0, 0}, {0, 0, 2}, 1, 0};  // true tip at z = 2
  double t;
  Vec3 n;
  EXPECT_FALSE(intersect_cone(c, {-5, 0, 2.5}, {1, 0, 0}, 0, INFINITY, t, n));
}

TEST(Cone, BoundsContainTheSurface) {
  const Cone c{{1, 2, 3}, {2, 4, 3.5}, 0.7, 0.2};
  const Bounds3 b = bounds_of(c);
  for (int k = 0; k < 64; ++k) {
    const double a = k * 2 * M_PI / 64;
    const Vec3 axis = normalize(c.apex - c.base);
    const Vec3 u = normalize(cross(axis, {0, 0, 1})), w = cross(axis, u);
    for (double h : {0.0, 1.0}) {
      const double r = 0.7 + (0.2 - 0.7) * h;
      const Vec3 p = c.base + (c.apex - c.base) * h + (u * std::cos(a) + w * std::sin(a)) * r;
      for (int e = 0; e < 3; ++e) {
        EXPECT_GE(p[e], b.lo[e] - 1e-12);
        EXPECT_LE(p[e], b.hi[e] + 1e-12);
      }
    }
  }
}

// Shadow rays ask only whether a shape is met (meets_sphere, meets_cone):
// over random segments through and past spheres and cones of both kinds of
// radius (inside-only among them), the answer is the full intersection's.
TEST(Shapes, MeetsAgreesWithTheFullIntersectionOnRandomSegments) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-2, 2);
  auto vec = [&] { return Vec3{u(rng), u(rng), u(rng)}; };
  const Sphere spheres[] = {{{0.1, -0.2, 0.3}, 0.8}, {{0, 0, 0}, -1.1}};
  const PreparedCone cones[] = {prepare_cone({{0, 0, -1}, {0.2, 0.1, 1}, 0.9, 0.3}),
                                prepare_cone({{0, 0, -1}, {0, 0, 1}, 1, 0}),
                                prepare_cone({{-0.5, 0, 0}, {0.5, 0.2, 0}, -0.6, -0.6})};
  int met = 0, missed = 0;
  for (int k = 0; k < 20000; ++k) {
    // From around the shapes toward a point near them, stopping short or not.
    const Vec3 o = vec() * 1.5, d = vec() * 0.4 - o;
    const double tnear = k % 3 == 0 ? 0.0 : std::fabs(u(rng)) * 0.2, tfar = k % 5 == 0 ? INFINITY : std::fabs(u(rng));
    double t;
    Vec3 n;
    for (const Sphere& s : spheres) {
      const bool full = intersect_sphere(s, o, d, tnear, tfar, t, n);
      ASSERT_EQ(meets_sphere(s, o, d, tnear, tfar), full) << "sphere " << s.radius << " ray " << k;
      (full ? met : missed)++;
    }
    for (const PreparedCone& c : cones) {
      const bool full = intersect_cone(c, o, d, tnear, tfar, t, n);
      ASSERT_EQ(meets_cone(c, o, d, tnear, tfar), full) << "cone " << c.cone.base_radius << " ray " << k;
      (full ? met : missed)++;
    }
  }
  // Both answers were asked often enough to mean something.
  EXPECT_GT(met, 25000);
  EXPECT_GT(missed, 25000);
}

// The sphere test rejects most misses before its division (sphere_hit's
// margin): on lines that graze a sphere, from near and from up to 1e6
// radii away, its answer is the one that the projection of the centre onto
// the line gives (the test before that rejection, here in long double),
// except within a few ulps of tangency where rounding decides either way.
TEST(Sphere, QuickRejectionAgreesWithTheProjectionOnGrazingLines) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  int hits = 0, misses = 0;
  for (int k = 0; k < 200000; ++k) {
    const Sphere s{{u(rng), u(rng), u(rng)}, 0.01 + std::fabs(u(rng))};
    // A unit direction, a point at distance r (1 + e) from the centre off
    // the line, and an origin up to 1e6 radii back along it.
    Vec3 d = normalize(Vec3{u(rng), u(rng), u(rng)});
    Vec3 side = normalize(cross(d, Vec3{u(rng), u(rng), u(rng)}));
    const double e = std::ldexp(u(rng), -static_cast<int>(rng() % 50));
    const double back = std::ldexp(std::fabs(u(rng)), static_cast<int>(rng() % 21)) * s.radius;
    const Vec3 o = s.centre + side * (s.radius * (1 + e)) - d * back;
    d = d * (0.5 + std::fabs(u(rng)));  // any length
    // The projection, in long double: h2 = r^2 - |oc + d tc|^2.
    long double ocd = 0, dd = 0, q2 = 0;
    const long double oc[3] = {static_cast<long double>(o.x) - s.centre.x, static_cast<long double>(o.y) - s.centre.y,
                               static_cast<long double>(o.z) - s.centre.z};
    const long double dl[3] = {d.x, d.y, d.z};
    for (int c = 0; c < 3; ++c) ocd += oc[c] * dl[c], dd += dl[c] * dl[c];
    for (int c = 0; c < 3; ++c) q2 += (oc[c] - dl[c] * ocd / dd) * (oc[c] - dl[c] * ocd / dd);
    const long double h2 = static_cast<long double>(s.radius) * s.radius - q2;
    // Rounding in double decides within ~1e-12 of tangency (relative to the
    // scale of the sum), the same either way the test is written.
    const long double scale = static_cast<long double>(s.radius) * s.radius + q2 + ocd * ocd / dd;
    if (std::fabs(static_cast<double>(h2 / scale)) < 1e-12) continue;
    double t;
    Vec3 n;
    const bool met = h2 > 0;
    ASSERT_EQ(meets_sphere(s, o, d, 0, INFINITY), met) << "line " << k << " e " << e << " back " << back;
    ASSERT_EQ(intersect_sphere(s, o, d, 0, INFINITY, t, n), met) << "line " << k;
    (met ? hits : misses)++;
  }
  EXPECT_GT(hits, 40000);
  EXPECT_GT(misses, 40000);
}
