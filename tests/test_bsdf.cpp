// The path tracer's BSDF (shading/bsdf.h) against its own definition: what
// its sampling returns averages to the integral of what it evaluates (so
// the sampled directions follow the density it reports, lobe by lobe, rough
// transmission included), and glTF's rough thin-walled transmission
// narrows to the smooth one's straight-on delta as its roughness falls.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "shading/bsdf.h"

namespace holoray {
namespace {

namespace sh = shading;

// The integral of hr_bsdf_eval (f |cos|) over the sphere by the midpoint
// rule in (cos theta, phi), both hemispheres: the BSDF's albedo at `wo`
// through its non-delta lobes.
sh::vec3 albedo_by_quadrature(const sh::HrBsdf& b, sh::vec3 wo) {
  const int nc = 1200, np = 1200;
  double sum[3] = {0, 0, 0};
  for (int i = 0; i < 2 * nc; ++i)
    for (int j = 0; j < np; ++j) {
      const double c = -1 + (i + 0.5) / nc, s = std::sqrt(1 - c * c), phi = 2 * M_PI * (j + 0.5) / np;
      const sh::vec3 f = sh::hr_bsdf_eval(b, wo, sh::vec3(float(s * std::cos(phi)), float(s * std::sin(phi)), float(c)));
      sum[0] += f.x, sum[1] += f.y, sum[2] += f.z;
    }
  const double cell = (1.0 / nc) * (2 * M_PI / np);
  return sh::vec3(float(sum[0] * cell), float(sum[1] * cell), float(sum[2] * cell));
}

// The mean weight of the non-delta samples (the delta lobes' are left out:
// eval never sees them).
sh::vec3 albedo_by_sampling(const sh::HrBsdf& b, sh::vec3 wo, int n) {
  std::mt19937 rng(72);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  double sum[3] = {0, 0, 0};
  for (int k = 0; k < n; ++k) {
    sh::vec3 wi, w;
    float pdf;
    bool delta, passed;
    const float u_lobe = unit(rng);
    const sh::vec2 u(unit(rng), unit(rng));
    if (!sh::hr_bsdf_sample(b, wo, u_lobe, u, wi, w, pdf, delta, passed) || delta) continue;
    sum[0] += w.x, sum[1] += w.y, sum[2] += w.z;
  }
  return sh::vec3(float(sum[0] / n), float(sum[1] / n), float(sum[2] / n));
}

TEST(Bsdf, ItsSamplesAverageToTheIntegralOfItsEvaluationForEveryLobe) {
  const sh::vec3 colour(0.9f, 0.6f, 0.3f);
  struct Case {
    const char* name;
    sh::HrBsdf b;
  };
  const float cos_o = 0.7f;
  const Case cases[] = {
      {"glTF dielectric, rough", sh::hr_gltf_bsdf(colour, 0.0f, 0.6f, 0.04f, 0.0f, cos_o)},
      {"glTF metal, rough", sh::hr_gltf_bsdf(colour, 1.0f, 0.5f, 0.04f, 0.0f, cos_o)},
      {"glTF rough transmission", sh::hr_gltf_bsdf(colour, 0.0f, 0.5f, 0.04f, 1.0f, cos_o)},
      {"glTF half transmission, half metal", sh::hr_gltf_bsdf(colour, 0.5f, 0.7f, 0.04f, 0.6f, cos_o)},
      {"Blender's Principled, rough transmission", sh::hr_principled_bsdf(colour, 0.0f, 0.6f, 0.04f, 0.5f, cos_o)},
      {"Lambert and a mirror", sh::hr_plain_bsdf(colour, sh::vec3(0.3f), sh::vec3(0.0f), 1.0f)},
  };
  const sh::vec3 wo(std::sqrt(1 - cos_o * cos_o), 0.0f, cos_o);
  for (const Case& c : cases) {
    const sh::vec3 q = albedo_by_quadrature(c.b, wo);
    const sh::vec3 m = albedo_by_sampling(c.b, wo, 400000);
    // Monte Carlo's error at 400k samples is well under 1 %; 2 % of the
    // albedo, plus a floor for the dark channels.
    EXPECT_NEAR(m.x, q.x, 0.02 * q.x + 2e-3) << c.name;
    EXPECT_NEAR(m.y, q.y, 0.02 * q.y + 2e-3) << c.name;
    EXPECT_NEAR(m.z, q.z, 0.02 * q.z + 2e-3) << c.name;
    EXPECT_LE(q.x, 1.0f) << c.name << ": more light out than in";
  }
}

// Rough transmission passes light below the surface, spread about the
// straight-on direction; as the roughness falls its albedo tends to the
// smooth (delta) transmission's weight, c (1 - F(wo.z)), which the glossy
// lobe's single scattering keeps all of in the limit.
TEST(Bsdf, RoughTransmissionTendsToTheSmoothOnesWeightAsItsRoughnessFalls) {
  const sh::vec3 colour(1.0f, 0.5f, 0.25f);
  const float cos_o = 0.8f;
  const sh::vec3 wo(0.6f, 0.0f, cos_o);
  const sh::HrBsdf smooth = sh::hr_gltf_bsdf(colour, 0.0f, 0.0f, 0.04f, 1.0f, cos_o);
  EXPECT_EQ(smooth.transmit_alpha, 0.0f) << "roughness 0 keeps the delta lobe";
  double last_error = 1;
  for (const float roughness : {0.6f, 0.3f, 0.1f}) {
    const sh::HrBsdf rough = sh::hr_gltf_bsdf(colour, 0.0f, roughness, 0.04f, 1.0f, cos_o);
    ASSERT_GT(rough.transmit_alpha, 0.0f);
    // Only below the surface: the transmitted lobe alone.
    double through_share = 0;
    sh::vec3 below(0.0f);
    {
      std::mt19937 rng(73);
      std::uniform_real_distribution<float> unit(0.0f, 1.0f);
      double sum = 0, mean_x = 0;
      int n = 0;
      for (int k = 0; k < 200000; ++k) {
        sh::vec3 wi, w;
        float pdf;
        bool delta, passed;
        const float u_lobe = unit(rng);
        const sh::vec2 u(unit(rng), unit(rng));
        if (!sh::hr_bsdf_sample(rough, wo, u_lobe, u, wi, w, pdf, delta, passed) || !passed) continue;
        ASSERT_LT(wi.z, 0.0f);
        ASSERT_FALSE(delta);
        sum += w.x, mean_x += wi.x, ++n;
      }
      through_share = double(n) / 200000;
      below = sh::vec3(float(sum / 200000), 0.0f, 0.0f);
      // Centred near the straight-on direction -wo (its x is -0.6).
      EXPECT_NEAR(mean_x / n, -0.6, 0.1 + roughness * 0.3) << "roughness " << roughness;
    }
    EXPECT_GT(through_share, 0.5);
    const double error = std::fabs(below.x - smooth.transmit.x) / smooth.transmit.x;
    std::printf("roughness %.2f: transmitted albedo %.4f, smooth %.4f\n", roughness, below.x, smooth.transmit.x);
    EXPECT_LE(below.x, smooth.transmit.x * 1.01f);
    EXPECT_LT(error, last_error) << "roughness " << roughness;
    last_error = error;
  }
  EXPECT_LT(last_error, 0.03) << "at roughness 0.1";
}

}  // namespace
}  // namespace holoray
