// NFF's direct light as a float batch (render/light_batch.hpp) against the
// formula written out here in double (nff-notes §10.10): which lanes cast a
// shadow ray, the rays Embree gets, and the light's term.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "render/light_batch.hpp"

using namespace holoray;

namespace {

struct Lane {
  Vec3 p, n, view, kd_colour;
  double ks = 0, shine = 1;
  bool hit = true;
};

// Random hits around the origin, a light at `light`: normals and view
// directions anywhere on the sphere, so every case (light behind the
// surface, highlight on and off) comes up across the lanes.
std::vector<Lane> random_lanes(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1), pos(0, 1);
  auto unit = [&] {
    Vec3 v;
    do v = Vec3{u(rng), u(rng), u(rng)};
    while (dot(v, v) < 0.01 || dot(v, v) > 1);
    return normalize(v);
  };
  std::vector<Lane> lanes(kPacketSize);
  for (int k = 0; k < kPacketSize; ++k) {
    Lane& l = lanes[static_cast<size_t>(k)];
    l.p = Vec3{u(rng), u(rng), u(rng)} * 3;
    l.n = unit();
    l.view = unit();
    l.kd_colour = Vec3{pos(rng), pos(rng), pos(rng)} * 0.8;
    l.ks = k % 3 == 0 ? 0 : pos(rng) * 0.5;
    l.shine = 1 + 60 * pos(rng);
    l.hit = k % 7 != 3;
  }
  return lanes;
}

NffLanes batch_of(const std::vector<Lane>& lanes, double eps) {
  NffLanes b;
  for (int k = 0; k < kPacketSize; ++k) {
    const Lane& l = lanes[static_cast<size_t>(k)];
    if (l.hit) b.set(k, l.p, l.n, l.p + l.n * eps, l.view, l.kd_colour, l.ks, l.shine);
    else b.clear(k);
  }
  return b;
}

}  // namespace

// A lane casts a ray exactly when it is hit and N.L > 0 (away from the
// float rounding of 0); the ray leaves the lifted origin, is unit, points at
// the light and stops eps short of it, in Embree's layout (tnear 0, mask ~0).
TEST(LightBatch, ShadowRaysAreTheFormulasSegmentsTowardTheLight) {
  std::mt19937 rng(7);
  const double eps = 1e-4;
  const Vec3 light{2, 5, 4};
  int cast_total = 0, skipped_total = 0;
  for (int round = 0; round < 50; ++round) {
    const std::vector<Lane> lanes = random_lanes(rng);
    const NffLanes b = batch_of(lanes, eps);
    ShadowPacket s;
    NffLightRays rays;
    const int cast = nff_shadow_rays(b, light, eps, s, rays);
    int counted = 0;
    for (int k = 0; k < kPacketSize; ++k) {
      const Lane& l = lanes[static_cast<size_t>(k)];
      const Vec3 to = light - l.p;
      const double dist = length(to), n_dot_l = dot(l.n, to / dist);
      if (std::fabs(n_dot_l) < 1e-5) continue;  // either answer is right at float rounding
      const bool expect = l.hit && n_dot_l > 0;
      ASSERT_EQ(s.valid[k] != 0, expect) << "lane " << k;
      counted += s.valid[k] != 0;
      if (!expect) continue;
      const Vec3 dir{s.dir_x[k], s.dir_y[k], s.dir_z[k]};
      EXPECT_NEAR(length(dir), 1.0, 1e-6);
      EXPECT_NEAR(dot(dir, to / dist), 1.0, 1e-6);
      EXPECT_NEAR(s.tfar[k], dist - eps, 1e-5 * dist);
      EXPECT_NEAR(rays.n_dot_l[k], n_dot_l, 1e-6);
      EXPECT_FLOAT_EQ(s.org_x[k], static_cast<float>(l.p.x + l.n.x * eps));
      EXPECT_EQ(s.tnear[k], 0.0f);
      EXPECT_EQ(s.mask[k], ~0u);
      EXPECT_EQ(s.id[k], static_cast<unsigned>(k));
    }
    EXPECT_GE(cast, counted);
    cast_total += cast;
    skipped_total += kPacketSize - cast;
  }
  // Both answers came up often enough for the test to mean something.
  EXPECT_GT(cast_total, 200);
  EXPECT_GT(skipped_total, 200);
}

// The term added to a seen lane is Il*(Kd*C*N.L + Ks*(R.V)^Shine) (the
// highlight where Ks > 0 and R.V > 0), R = L reflected about N, to float
// precision; unseen lanes are left as they were.
TEST(LightBatch, TermIsTheNffFormulaToFloatPrecision) {
  std::mt19937 rng(11);
  const double eps = 1e-4;
  const Vec3 light{-3, 4, 6}, intensity{0.9, 0.6, 0.3};
  int highlights = 0;
  std::uniform_real_distribution<double> jitter(-0.1, 0.1);
  for (int round = 0; round < 50; ++round) {
    std::vector<Lane> lanes = random_lanes(rng);
    // Half the lanes look from near the light's mirror direction: bright highlights.
    for (int k = 0; k < kPacketSize; k += 2) {
      Lane& l = lanes[static_cast<size_t>(k)];
      const Vec3 to = normalize(light - l.p);
      l.view = normalize(l.n * (2 * dot(l.n, to)) - to + Vec3{jitter(rng), jitter(rng), jitter(rng)});
    }
    const NffLanes b = batch_of(lanes, eps);
    ShadowPacket s;
    NffLightRays rays;
    nff_shadow_rays(b, light, eps, s, rays);
    bool seen[kPacketSize];
    Vec3 colours[kPacketSize];
    for (int k = 0; k < kPacketSize; ++k) {
      seen[k] = s.valid[k] != 0 && k % 4 != 1;  // some lanes' rays were blocked
      colours[k] = Vec3{0.25, 0.5, 0.75};
    }
    add_nff_light(b, rays, seen, intensity, colours);
    for (int k = 0; k < kPacketSize; ++k) {
      const Lane& l = lanes[static_cast<size_t>(k)];
      Vec3 expect{0.25, 0.5, 0.75};
      if (seen[k]) {
        const Vec3 to = normalize(light - l.p);
        const double n_dot_l = dot(l.n, to);
        const Vec3 r = l.n * (2 * n_dot_l) - to;
        Vec3 term = l.kd_colour * n_dot_l;
        const double r_dot_v = dot(r, l.view);
        if (l.ks > 0 && r_dot_v > 0) {
          term += Vec3{1, 1, 1} * (l.ks * std::pow(r_dot_v, l.shine));
          highlights += l.ks * std::pow(r_dot_v, l.shine) > 1e-3;
        }
        expect += mul(intensity, term);
      }
      EXPECT_NEAR(colours[k].x, expect.x, 1e-5) << "lane " << k;
      EXPECT_NEAR(colours[k].y, expect.y, 1e-5) << "lane " << k;
      EXPECT_NEAR(colours[k].z, expect.z, 1e-5) << "lane " << k;
    }
  }
  EXPECT_GT(highlights, 100);  // the highlight term was really tested
}
