// glTF's direct light as a float batch (render/gltf_batch.hpp) against the
// double path: which lanes cast a shadow ray and where it goes, the light's
// falloff for every kind of light (written out here as light_falloff()
// computes it), and the term against gltf_direct() in double.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "render/gltf_batch.hpp"

using namespace holoray;

namespace {

struct Lane {
  Vec3 p, n, view;
  GltfSurface s;
  double transmittance = 0;
  bool hit = true;
};

Vec3 random_unit(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  Vec3 v;
  do v = Vec3{u(rng), u(rng), u(rng)};
  while (dot(v, v) < 0.01 || dot(v, v) > 1);
  return normalize(v);
}

// Hits around the origin with normals and views anywhere, dielectrics and
// metals from nearly smooth (roughness 0.05) to rough, some transmission
// and some uncovered surface.
std::vector<Lane> random_lanes(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1), pos(0, 1);
  std::vector<Lane> lanes(kPacketSize);
  for (int k = 0; k < kPacketSize; ++k) {
    Lane& l = lanes[static_cast<size_t>(k)];
    l.p = Vec3{u(rng), u(rng), u(rng)} * 3;
    l.n = random_unit(rng);
    l.view = random_unit(rng);
    l.s.base = Vec3{pos(rng), pos(rng), pos(rng)};
    l.s.metallic = k % 3 == 0 ? 0.0 : k % 3 == 1 ? 1.0 : pos(rng);
    l.s.roughness = 0.05 + 0.95 * pos(rng);
    l.s.f0 = dielectric_f0(1.3 + 0.5 * pos(rng));
    l.s.transmission = k % 4 == 0 ? pos(rng) : 0.0;
    l.transmittance = k % 5 == 0 ? 0.5 * pos(rng) : 0.0;
    l.hit = k % 7 != 3;
  }
  return lanes;
}

GltfLanes batch_of(const std::vector<Lane>& lanes, double eps) {
  GltfLanes b;
  for (int k = 0; k < kPacketSize; ++k) {
    const Lane& l = lanes[static_cast<size_t>(k)];
    if (l.hit) b.set(k, l.p, l.n, l.p + l.n * eps, l.view, l.s, l.transmittance);
    else b.clear(k);
  }
  return b;
}

// The lights a glTF file gives (inverse-square points and spots, suns), one
// with a range window, and NFF's unit point.
std::vector<PointLight> lights() {
  auto light = [](LightKind kind, Vec3 pos, Vec3 dir) {
    PointLight l;
    l.kind = kind, l.position = pos, l.direction = normalize(dir), l.intensity = Vec3{0.9, 0.6, 0.3};
    if (kind != LightKind::directional) l.kc = 0, l.kq = 1;
    l.unit_falloff = false;
    return l;
  };
  std::vector<PointLight> out;
  out.push_back(light(LightKind::point, {2, 5, 4}, {0, 0, -1}));
  PointLight ranged = light(LightKind::point, {-1, 3, 2}, {0, 0, -1});
  ranged.range = 5;
  out.push_back(ranged);
  PointLight spot = light(LightKind::spot, {0, 6, 1}, {0, -1, -0.1});
  spot.smooth_cone = true, spot.fall_start = 0.4, spot.fall_end = 0.7;
  spot.cos_fall_start = std::cos(spot.fall_start), spot.cos_fall_end = std::cos(spot.fall_end);
  out.push_back(spot);
  out.push_back(light(LightKind::directional, {0, 0, 0}, {0.3, -1, -0.5}));
  PointLight unit;
  unit.position = Vec3{3, -2, 5}, unit.intensity = Vec3{1, 1, 1};
  out.push_back(unit);
  return out;
}

// The direction toward the light, its distance (infinite for a sun) and
// falloff, as shadow_ray() and light_falloff() compute them in double.
void toward(const PointLight& light, const Vec3& p, Vec3& to, double& dist, double& falloff) {
  falloff = 1;
  if (light.kind == LightKind::directional) {
    to = -light.direction, dist = INFINITY;
    return;
  }
  to = light.position - p;
  dist = length(to);
  to = to / dist;
  if (light.kc != 1 || light.kl != 0 || light.kq != 0) falloff = 1 / (light.kc + (light.kl + light.kq * dist) * dist);
  if (light.range > 0) {
    const double x2 = (dist / light.range) * (dist / light.range), w = std::clamp(1 - x2 * x2, 0.0, 1.0);
    falloff *= w * w;
  }
  if (light.kind == LightKind::spot) {
    const double t = std::clamp((-dot(light.direction, to) - light.cos_fall_end) /
                                    std::fmax(1e-3, light.cos_fall_start - light.cos_fall_end), 0.0, 1.0);
    falloff *= t * t;
  }
}

}  // namespace

// A lane casts a ray exactly when it is hit, N.L > 0 and the falloff leaves
// light (away from float rounding of those); the ray leaves the lifted
// origin toward the light, unbounded toward a sun, else stopping eps short.
TEST(GltfBatch, ShadowRaysAndFalloffAreTheDoublePathsForEveryKindOfLight) {
  std::mt19937 rng(5);
  const double eps = 1e-4;
  for (const PointLight& light : lights()) {
    SCOPED_TRACE(static_cast<int>(light.kind));
    ASSERT_TRUE(can_batch(light));
    int cast_total = 0, dark_total = 0;
    for (int round = 0; round < 40; ++round) {
      const std::vector<Lane> lanes = random_lanes(rng);
      const GltfLanes b = batch_of(lanes, eps);
      ShadowPacket s;
      GltfLightRays rays;
      const int cast = gltf_shadow_rays(b, light, eps, s, rays);
      int valid = 0;
      for (int k = 0; k < kPacketSize; ++k) valid += s.valid[k] != 0;
      EXPECT_EQ(cast, valid);
      for (int k = 0; k < kPacketSize; ++k) {
        const Lane& l = lanes[static_cast<size_t>(k)];
        Vec3 to;
        double dist, falloff;
        toward(light, l.p, to, dist, falloff);
        const double n_dot_l = dot(l.n, to);
        if (std::fabs(n_dot_l) < 1e-5 || (falloff > 0 && falloff < 1e-9)) continue;  // float rounding decides
        const bool expect = l.hit && n_dot_l > 0 && falloff > 0;
        ASSERT_EQ(s.valid[k] != 0, expect) << "lane " << k;
        dark_total += l.hit && n_dot_l > 0 && !(falloff > 0);
        if (!expect) continue;
        ++cast_total;
        const Vec3 dir{s.dir_x[k], s.dir_y[k], s.dir_z[k]};
        EXPECT_NEAR(dot(dir, to), 1.0, 1e-6);
        if (std::isinf(dist)) EXPECT_TRUE(std::isinf(s.tfar[k]));
        else EXPECT_NEAR(s.tfar[k], dist - eps, 1e-5 * dist);
        EXPECT_NEAR(rays.n_dot_l[k], n_dot_l, 1e-6);
        EXPECT_NEAR(rays.falloff[k], falloff, 1e-5 * falloff + 1e-7);
        EXPECT_FLOAT_EQ(s.org_y[k], static_cast<float>(l.p.y + l.n.y * eps));
        EXPECT_EQ(s.tnear[k], 0.0f);
        EXPECT_EQ(s.id[k], static_cast<unsigned>(k));
      }
    }
    EXPECT_GT(cast_total, 150);
    if (light.kind == LightKind::spot || light.range > 0) EXPECT_GT(dark_total, 5);  // outside the cone or range
  }
}

// The term added to a seen lane is intensity * falloff * (1 - transmittance)
// * gltf_direct() to float precision, bright highlights of nearly smooth
// metals included; unseen lanes are left as they were.
TEST(GltfBatch, TermIsGltfDirectToFloatPrecision) {
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> jitter(-0.05, 0.05);
  const double eps = 1e-4;
  int highlights = 0;
  for (const PointLight& light : lights())
    for (int round = 0; round < 40; ++round) {
      std::vector<Lane> lanes = random_lanes(rng);
      // Half the lanes look from near the light's mirror direction.
      for (int k = 0; k < kPacketSize; k += 2) {
        Lane& l = lanes[static_cast<size_t>(k)];
        Vec3 to;
        double dist, falloff;
        toward(light, l.p, to, dist, falloff);
        if (dot(l.n, to) < 0) l.n = -l.n;
        l.view = normalize(l.n * (2 * dot(l.n, to)) - to + Vec3{jitter(rng), jitter(rng), jitter(rng)});
      }
      const GltfLanes b = batch_of(lanes, eps);
      ShadowPacket s;
      GltfLightRays rays;
      gltf_shadow_rays(b, light, eps, s, rays);
      bool seen[kPacketSize];
      Vec3 colours[kPacketSize];
      for (int k = 0; k < kPacketSize; ++k) {
        seen[k] = s.valid[k] != 0 && k % 4 != 1;  // some lanes' rays were blocked
        colours[k] = Vec3{0.25, 0.5, 0.75};
      }
      add_gltf_light(b, rays, seen, light.intensity, colours);
      for (int k = 0; k < kPacketSize; ++k) {
        const Lane& l = lanes[static_cast<size_t>(k)];
        Vec3 expect{0.25, 0.5, 0.75};
        if (seen[k]) {
          Vec3 to;
          double dist, falloff;
          toward(light, l.p, to, dist, falloff);
          const Vec3 term = mul(light.intensity * (falloff * (1 - l.transmittance)), gltf_direct(l.s, l.n, l.view, to));
          highlights += term.x > 5 * light.intensity.x * falloff;
          expect += term;
        }
        for (int c = 0; c < 3; ++c) {
          const double got = c == 0 ? colours[k].x : c == 1 ? colours[k].y : colours[k].z;
          const double want = c == 0 ? expect.x : c == 1 ? expect.y : expect.z;
          EXPECT_NEAR(got, want, 2e-4 * std::fabs(want) + 1e-6) << "lane " << k << " channel " << c;
        }
      }
    }
  EXPECT_GT(highlights, 50);  // the GGX peak was really tested
}

// Tachyon's spot, linear in the angle, is left to the double path.
TEST(GltfBatch, TachyonsLinearSpotIsNotBatched) {
  PointLight spot;
  spot.kind = LightKind::spot;
  spot.smooth_cone = false;
  EXPECT_FALSE(can_batch(spot));
  spot.smooth_cone = true;
  EXPECT_TRUE(can_batch(spot));
}
