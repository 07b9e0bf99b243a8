// The path integrator (render/path_tracer.hpp) and what it reads
// (render/environment.hpp): analytic scenes whose radiance is known, the
// environment's sampling against its own density and Blender's mapping,
// the image's independence of the thread count, the noise's fall with the
// sample count, and the options the API refuses.
#include <gtest/gtest.h>
#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "holoray/animate.hpp"
#include "holoray/render.hpp"
#include "holoray/scene.hpp"
#include "image/metrics.hpp"
#include "render/emitters.hpp"
#include "render/environment.hpp"
#include "render/gltf_brdf.hpp"
#include "render/path_tracer.hpp"
#include "render/view_renderer.hpp"
#include "scene/lights_file.hpp"
#include "scene/nff_reader.hpp"
#include "shading/environment.h"
#include "gltf_squares.hpp"
#include "test_util.hpp"

namespace holoray {
namespace {

RenderSettings path_settings(const RenderScene& scene, const EnvironmentMap* env, int max_depth) {
  RenderSettings s = file_settings(scene);
  s.integrator = Integrator::path;
  s.environment = env;
  s.max_depth = max_depth;
  return s;
}

// The mean red radiance along `ray` over samples 0 to n - 1 of the stream
// `seed` (each stream's first pair stands for the pixel position).
double mean_radiance(const RenderContext& ctx, const Ray& ray, uint32_t seed, int n) {
  double sum = 0;
  for (int k = 0; k < n; ++k) {
    shading::HrSampler sampler = shading::hr_sampler(seed, static_cast<uint32_t>(k));
    shading::hr_next2(sampler);
    RayCounts counts;
    sum += path_radiance(ctx, ray, sampler, counts).x;
  }
  return sum / n;
}

// A size x size pinhole view of `desc` (through its viewpoint) under the
// path integrator, lit by `env`.
FrameBuffers path_view(const SceneDesc& desc, const EnvironmentMap* env, int size, int spp, int max_depth = 5,
                       int threads = 0) {
  const RenderScene scene(desc);
  const RenderContext ctx(scene, path_settings(scene, env, max_depth));
  const Viewpoint& vp = *desc.viewpoint;
  const PinholeCamera cam(PinholeDesc{vp.from, vp.at, vp.up, vp.angle_deg, size, size});
  RenderOptions ro;
  ro.spp = spp;
  ro.threads = threads;
  RenderStats stats;
  return render_view(ctx, cam, ro, stats);
}

// A unit sphere at the origin seen from 4 units away, no light: `material`
// is an NFF `f` line.
SceneDesc sphere_scene(const std::string& material) {
  return parse_nff("v\nfrom 0 -4 0\nat 0 0 0\nup 0 0 1\nangle 40\nhither 0\nresolution 32 32\n" + material + "\ns 0 0 0 1\n",
                   "sphere.nff");
}

// The pixels whose whole footprint lies on the sphere (their centre ray
// meets it well inside the silhouette): the mean over them of channel 0,
// and the largest distance of one from `expected`.
void sphere_pixels(const FrameBuffers& fb, int size, double expected, double& mean, double& worst) {
  const Viewpoint vp{{0, -4, 0}, {0, 0, 0}, {0, 0, 1}, 40};
  const PinholeCamera cam(PinholeDesc{vp.from, vp.at, vp.up, vp.angle_deg, size, size});
  double sum = 0;
  int n = 0;
  worst = 0;
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) {
      const PixelLine l = cam.line(i, j);
      const double b = dot(l.origin, l.dir), disc = b * b - (dot(l.origin, l.origin) - 1);
      if (disc < 0.15) continue;  // off the sphere or near its silhouette
      const double v = fb.colour.at(i, j)[0];
      sum += v, ++n;
      worst = std::max(worst, std::fabs(v - expected));
    }
  ASSERT_GT(n, 100);
  mean = sum / n;
}

// The white furnace: a convex Lambertian surface of albedo 0.5 under a sky
// of radiance 1 everywhere reflects exactly 0.5 (it sees nothing but the
// sky), whatever the bounce count; the sky seen past it is 1.
TEST(PathIntegrator, AConvexLambertianSphereUnderAUniformSkyShowsItsAlbedo) {
  const EnvironmentMap sky(Vec3{1, 1, 1});
  const FrameBuffers fb = path_view(sphere_scene("f 0.5 0.5 0.5 1 0 0 0 1"), &sky, 48, 64);
  double mean, worst;
  sphere_pixels(fb, 48, 0.5, mean, worst);
  EXPECT_NEAR(mean, 0.5, 0.005);
  EXPECT_LT(worst, 0.05);
  EXPECT_FLOAT_EQ(fb.colour.at(0, 0)[0], 1.0f) << "a corner sees the sky";
}

// glTF's metal of colour 1 under a sky of radiance 1 reflects, toward each
// pixel, the directional albedo E(mu) of its BRDF at that pixel's view
// cosine mu: what its single-scattering GGX lobe keeps. E is integrated
// here by quadrature of the Whitted path's own copy of the BRDF
// (gltf_brdf.hpp, in double), an independent evaluation; a smooth metal is
// a mirror of the sky, 1.
TEST(PathIntegrator, AGltfMetalUnderAUniformSkyShowsItsDirectionalAlbedo) {
  const EnvironmentMap sky(Vec3{1, 1, 1});
  const int size = 40;
  for (const double roughness : {0.0, 0.5}) {
    SceneDesc desc = sphere_scene("f 1 1 1 1 0 0 0 1");
    desc.materials[0].model = ShadingModel::gltf;
    desc.materials[0].colour = {1, 1, 1};
    desc.materials[0].metallic = 1;
    desc.materials[0].roughness = roughness;
    const FrameBuffers fb = path_view(desc, &sky, size, 256);
    const GltfSurface surface{{1, 1, 1}, 1, roughness, 0.04, 0};
    // E(mu) = (1/pi) * integral of pi f cos over the hemisphere (gltf_direct returns pi f cos).
    auto albedo = [&](double mu) {
      const Vec3 n{0, 0, 1}, v{std::sqrt(1 - mu * mu), 0, mu};
      const int nt = 256, np = 256;
      double e = 0;
      for (int a = 0; a < nt; ++a) {
        const double t = (a + 0.5) / nt * M_PI / 2;
        for (int b = 0; b < np; ++b) {
          const double p = (b + 0.5) / np * 2 * M_PI;
          const Vec3 l{std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)};
          e += gltf_direct(surface, n, v, l).x * std::sin(t);
        }
      }
      return e * (M_PI / 2 / nt) * (2 * M_PI / np) / M_PI;
    };
    const PinholeCamera cam(PinholeDesc{{0, -4, 0}, {0, 0, 0}, {0, 0, 1}, 40, size, size});
    double rendered = 0, expected = 0;
    int n = 0;
    for (int j = 0; j < size; j += 3)
      for (int i = 0; i < size; i += 3) {
        const PixelLine l = cam.line(i, j);
        const double b = dot(l.origin, l.dir), disc = b * b - (dot(l.origin, l.origin) - 1);
        if (disc < 0.15) continue;
        const Vec3 hit = l.origin + l.dir * (-b - std::sqrt(disc));
        rendered += fb.colour.at(i, j)[0];
        expected += roughness == 0 ? 1.0 : albedo(std::clamp(-dot(hit, l.dir), 1e-3, 1.0));
        ++n;
      }
    ASSERT_GT(n, 40);
    EXPECT_NEAR(rendered / n, expected / n, 0.01) << "roughness " << roughness;
    if (roughness > 0) EXPECT_LT(expected / n, 0.97) << "the lobe loses light: the test can tell";
  }
}

// One point light over a Lambertian floor: path tracing's next-event
// estimate is Lambert's law exactly, C I cos(theta) (NFF's lights have no
// falloff; docs/lights.md), and the floor's own bounces leave for a black sky.
TEST(PathIntegrator, APointLightOnALambertianFloorFollowsLambertsLaw) {
  const SceneDesc desc = parse_nff("l 0 0 3\nf 0.6 0.4 0.2 1 0 0 0 1\np 4\n-5 -5 0\n5 -5 0\n5 5 0\n-5 5 0\n", "floor.nff");
  const RenderScene scene(desc);
  const EnvironmentMap black(Vec3{0, 0, 0});
  const RenderContext ctx(scene, path_settings(scene, &black, 5));
  ASSERT_EQ(scene.lights().size(), 1u);
  const Vec3 I = scene.lights()[0].intensity;
  for (const Vec3 p : {Vec3{0, 0, 0}, Vec3{1, 0.5, 0}, Vec3{-2, 3, 0}}) {
    shading::HrSampler sampler = shading::hr_sampler(7, 0);
    shading::hr_next2(sampler);
    RayCounts counts;
    const Vec3 c = path_radiance(ctx, Ray{p + Vec3{0.3, -0.2, 1}, normalize(Vec3{-0.3, 0.2, -1}), 0, INFINITY}, sampler, counts);
    const Vec3 to_light = Vec3{0, 0, 3} - p;
    const double cos_t = to_light.z / length(to_light);
    EXPECT_NEAR(c.x, 0.6 * I.x * cos_t, 1e-5) << p.x << "," << p.y;
    EXPECT_NEAR(c.y, 0.4 * I.y * cos_t, 1e-5);
    EXPECT_NEAR(c.z, 0.2 * I.z * cos_t, 1e-5);
  }
}

// An image environment: sample() draws directions with the density pdf()
// gives them, and sample()'s estimate of the mean radiance over the sphere
// agrees with the texels' own solid-angle-weighted mean.
TEST(EnvironmentMap, ItsSamplesFollowItsDensityAndEstimateItsMeanRadiance) {
  const int w = 32, h = 16;
  ImageBuffer img(w, h, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) img.at(x, y)[c] = (x == 5 && y == 4) ? 400.0f : 0.1f + 0.05f * c + 0.02f * ((x * 7 + y * 3) % 11);
  const EnvironmentMap env(img, 1.0, 0.3, EnvironmentUp::y);
  double exact = 0;
  for (int y = 0; y < h; ++y) {
    const double omega = 2 * M_PI / w * (std::sin((0.5 - double(y) / h) * M_PI) - std::sin((0.5 - double(y + 1) / h) * M_PI));
    for (int x = 0; x < w; ++x) exact += img.at(x, y)[1] * omega;
  }
  exact /= 4 * M_PI;
  double estimate = 0;
  const int n = 200000;
  int elsewhere = 0;  // drawn on a texel's edge, which float rounding gives the neighbour
  for (int k = 0; k < n; ++k) {
    shading::HrSampler s = shading::hr_sampler(11, static_cast<uint32_t>(k));
    const shading::vec2 a = shading::hr_next2(s), b = shading::hr_next2(s);
    Vec3 dir;
    double pdf;
    env.sample(a.x, b.x, b.y, dir, pdf);
    ASSERT_NEAR(length(dir), 1.0, 1e-6);
    elsewhere += std::fabs(pdf - env.pdf(dir)) > 1e-3 * pdf;
    estimate += env.radiance(dir).y / pdf;
  }
  estimate /= n * 4 * M_PI;
  EXPECT_LT(elsewhere, n / 10000);
  // Bilinear lookups against nearest-texel sampling: within the blur of one texel.
  EXPECT_NEAR(estimate, exact, 0.03 * exact);
}

// The mapping measured against Blender 3.4's Cycles (a probe image whose
// texels hold their own column and row, seen through a 1-degree camera):
// Blender's +X reads the centre column, +Y the first quarter, -Y the third,
// and 30 degrees up the row 0.5 + 30/180 of the way from the bottom.
// glTF's frame (y up) is Blender's turned by the exporter: Blender (x, y, z)
// = glTF (x, -z, y).
TEST(EnvironmentMap, MapsDirectionsAsBlendersEnvironmentTexture) {
  using shading::vec3;
  EXPECT_NEAR(shading::hr_equirect_uv(vec3(1, 0, 0)).x, 0.5f, 1e-6f);
  EXPECT_NEAR(shading::hr_equirect_uv(vec3(0, 1, 0)).x, 0.25f, 1e-6f);
  EXPECT_NEAR(shading::hr_equirect_uv(vec3(0, -1, 0)).x, 0.75f, 1e-6f);
  const float s = std::sin(float(M_PI / 6)), c = std::cos(float(M_PI / 6));
  EXPECT_NEAR(shading::hr_equirect_uv(vec3(-c, 0, s)).y, 0.5f + 30.0f / 180.0f, 1e-6f);
  // An image whose left half is red and right half green: glTF's +x looks
  // at the centre, where they meet; glTF's -z (Blender's +y) at the red quarter.
  ImageBuffer img(4, 2, 3);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 4; ++x) img.at(x, y)[x < 2 ? 0 : 1] = 1;
  const EnvironmentMap env(img, 1.0, 0.0, EnvironmentUp::y);
  EXPECT_NEAR(env.radiance({0, 0, -1}).x, 1.0, 1e-6);
  EXPECT_NEAR(env.radiance({0, 0, 1}).y, 1.0, 1e-6);
  // A Mapping node's Z rotation of 90 degrees reads Rz(90) d: +x then reads what +y did.
  const EnvironmentMap turned(img, 1.0, M_PI / 2, EnvironmentUp::y);
  EXPECT_NEAR(turned.radiance({1, 0, 0}).x, 1.0, 1e-6);
  for (const Vec3 d : {normalize(Vec3{0.3, 0.4, -0.866}), Vec3{-0.8, 0.6, 0}}) {
    const shading::vec2 uv = shading::hr_equirect_uv(vec3(float(d.x), float(d.y), float(d.z)));
    const vec3 back = shading::hr_equirect_direction(uv);
    EXPECT_NEAR(back.x, d.x, 1e-5);
    EXPECT_NEAR(back.y, d.y, 1e-5);
    EXPECT_NEAR(back.z, d.z, 1e-5);
  }
}

// Each pixel's samples are a function of the pixel, its index and the
// image's salt alone: one thread or two render the same bits.
TEST(PathIntegrator, TheImageIsTheSameForAnyThreadCount) {
  const SceneDesc desc = read_nff_file(test::source_dir() + "/examples/primitives.nff");
  const FrameBuffers one = path_view(desc, nullptr, 40, 4, 5, 1);
  const FrameBuffers two = path_view(desc, nullptr, 40, 4, 5, 2);
  EXPECT_EQ(one.colour.data, two.colour.data);
}

// Monte Carlo noise falls as 1 / sqrt(spp): 4x the samples, +6 dB against
// a converged image. Owen-scrambled Sobol points do no worse, and better
// where the integrand is smooth (up to N^-3/2: Owen 1997), so only the
// floor is a property; a biased or correlated sampler falls short of it.
TEST(PathIntegrator, NoiseFallsByAboutSixDecibelsPerFourTimesTheSamples) {
  SceneDesc desc = sphere_scene("f 0.7 0.6 0.5 1 0 0 0 1");
  desc.objects.push_back(ObjectDesc{PolygonDesc{{{-4, -4, -1}, {4, -4, -1}, {4, 4, -1}, {-4, 4, -1}}, {}}, 0, {}});
  ImageBuffer img(16, 8, 3);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 16; ++x)
      for (int c = 0; c < 3; ++c) img.at(x, y)[c] = y < 3 ? 2.0f + x % 3 : 0.2f;
  const EnvironmentMap env(img, 1.0, 0.0, EnvironmentUp::z);
  const FrameBuffers ref = path_view(desc, &env, 24, 4096);
  double last = 0;
  for (const int spp : {4, 16, 64}) {
    const double psnr = compare_images(path_view(desc, &env, 24, spp).colour, ref.colour).psnr_all();
    if (last > 0) EXPECT_GT(psnr - last, 4.5) << spp << " spp";
    last = psnr;
  }
}

// Two seeds draw unrelated samples: the squared difference of their images
// is the sum of each one's error against a converged image (the cross term,
// their noises' correlation, near zero), as for two independent renders.
// One seed renders the same image twice; Whitted's integrator, which draws
// no random samples, refuses a seed.
TEST(PathIntegrator, RendersWithDifferentSeedsHaveIndependentNoise) {
  const test::TempDir tmp;
  const std::string file = tmp.path.string() + "/s.nff";
  std::ofstream(file) << "v\nfrom 0 -4 1\nat 0 0 0\nup 0 0 1\nangle 40\nhither 0\nresolution 8 8\n"
                         "f 0.7 0.6 0.5 1 0 0 0 1\ns 0 0 0 1\np 4\n-4 -4 -1\n4 -4 -1\n4 4 -1\n-4 4 -1\n";
  const api::Scene scene = api::Scene::load(file);
  api::Pinhole view;
  view.width = view.height = 40;
  auto render = [&](uint32_t seed, int spp) {
    api::RenderOptions o;
    o.integrator = api::Integrator::path;
    o.environment.colour = std::array<double, 3>{1, 0.9, 0.8};
    o.spp = spp;
    o.seed = seed;
    return api::Renderer(scene, api::Camera{view}, o).render().colour;
  };
  auto mse = [](const api::Image& a, const api::Image& b) {
    double sum = 0;
    for (size_t k = 0; k < a.size(); ++k) sum += (double(a.data()[k]) - b.data()[k]) * (double(a.data()[k]) - b.data()[k]);
    return sum / double(a.size());
  };
  const api::Image ref = render(1000, 2048), a = render(0, 4), again = render(0, 4), b = render(1, 4);
  EXPECT_EQ(mse(a, again), 0.0);
  const double apart = mse(a, b), sum = mse(a, ref) + mse(b, ref);
  EXPECT_GT(apart, 0.0);
  EXPECT_NEAR(apart, sum, 0.15 * sum) << "seeds 0 and 1 apart " << apart << ", their errors' sum " << sum;
  api::RenderOptions whitted;
  whitted.seed = 3;
  EXPECT_EQ(test::error_of([&] { api::Renderer(scene, api::Camera{view}, whitted); }),
            "seed: Whitted's integrator draws no random samples: go with the path integrator");
}

// What the path integrator does not do yet is refused, saying why.
TEST(PathIntegrator, TheApiRefusesWhatItCannotRenderSayingWhy) {
  const test::TempDir tmp;
  const std::string dir = tmp.path.string();
  std::ofstream(dir + "/s.nff") << "v\nfrom 0 -4 0\nat 0 0 0\nup 0 0 1\nangle 40\nhither 0\nresolution 8 8\ns 0 0 0 1\n";
  const api::Scene scene = api::Scene::load(dir + "/s.nff");
  api::RenderOptions o;
  o.integrator = api::Integrator::path;
  o.cache.enabled = true;
  EXPECT_EQ(test::error_of([&] { api::Renderer(scene, api::Camera{api::LensArray{}}, o); }),
            "`integrator` path: the shadow cache reuses Whitted's point-light visibility, not paths; leave `cache` off");
  o = {};
  o.environment.colour = std::array<double, 3>{1, 1, 1};
  EXPECT_EQ(test::error_of([&] { api::Renderer(scene, api::Camera{api::LensArray{}}, o); }),
            "`environment`: lights the path integrator only (`integrator` path); Whitted's sees the background colour");
  o.integrator = api::Integrator::path;
  o.environment = {};
  o.environment.file = dir + "/missing.exr";
  EXPECT_NE(test::error_of([&] { api::Renderer(scene, api::Camera{api::LensArray{}}, o); }).find("missing.exr"), std::string::npos);
}

// glTF's thin-walled transmission over a glowing square of radiance 1, the
// sky black. Smooth, the glass passes the glow on unbent, c (1 - F) with F
// Schlick's at the view angle (0.04 along the axis), and nothing beside it
// (a pixel that sees past the glow's edge through the glass is black).
// Rough, it spreads the glow: the pixel beside it is lit, the centre is
// dimmer than the smooth glass's and never brighter.
TEST(PathIntegrator, RoughTransmissionSpreadsTheLightBehindTheGlassAndSmoothPassesItUnbent) {
  const test::TempDir dir;
  auto render = [&](double roughness) {
    test::GltfSquares s;
    s.materials = fmt::format(R"({{"name": "glass", "extensions": {{"KHR_materials_transmission": {{"transmissionFactor": 1}}}},
 "pbrMetallicRoughness": {{"baseColorFactor": [1, 1, 1, 1], "metallicFactor": 0, "roughnessFactor": {}}}}},
 {{"name": "glow", "emissiveFactor": [1, 1, 1], "pbrMetallicRoughness": {{"baseColorFactor": [0, 0, 0, 1], "metallicFactor": 1}}}})",
                              roughness);
    s.squares = {{1.5, 0}, {0.3, -1}};
    s.lights = "";
    s.light_node = "{}";
    test::write_text(dir.file("s.gltf"), test::gltf(s));
    api::RenderOptions o;
    o.integrator = api::Integrator::path;
    o.spp = 256;
    api::Pinhole view;
    view.width = view.height = 21;
    return api::render(api::Scene::load(dir.file("s.gltf")), api::Camera{view}, o);
  };
  // The glow spans about 0.3 / 5 of the 0.6 radian field: 4 of 21 pixels
  // across; pixel (10, 10) looks at its centre, (10, 16) well beside it.
  auto at = [](const api::Result& r, int i, int j) { return r.colour.data()[(size_t(j) * r.colour.width() + i) * 3]; };
  const api::Result smooth = render(0), rough = render(0.5);
  EXPECT_NEAR(at(smooth, 10, 10), 0.96, 0.01);
  EXPECT_EQ(at(smooth, 10, 16), 0.0f);
  EXPECT_GT(at(rough, 10, 16), 0.01);
  EXPECT_LT(at(rough, 10, 10), at(smooth, 10, 10) - 0.05);
  EXPECT_GT(at(rough, 10, 10), 0.05);
}

}  // namespace
}  // namespace holoray

namespace holoray {
namespace {

// An emissive square of radiance L, side a, at height c over a Lambertian
// floor of albedo rho: under its centre the floor's radiance is rho / pi
// times the square's irradiance there, 2 L [A / sqrt(1 + A^2) atan(B /
// sqrt(1 + A^2)) + B / sqrt(1 + B^2) atan(A / sqrt(1 + B^2))], A = B =
// a / (2c) (the rectangle's form factor, four corner pieces). Next-event
// estimation of the emitter and the BSDF's rays, MIS-weighted, average to
// it; with the emitter's own sampling off, the BSDF's rays alone do too.
TEST(PathIntegrator, AnEmissiveSquareLightsAFloorAsItsFormFactorSays) {
  SceneDesc desc = parse_nff("f 0.5 0.5 0.5 1 0 0 0 1\np 4\n-5 -5 0\n5 -5 0\n5 5 0\n-5 5 0\n", "floor.nff");
  Material emitter;
  emitter.colour = {0, 0, 0};
  emitter.kd = 0;
  emitter.emission = {4, 4, 4};
  desc.materials.push_back(emitter);
  const double a = 0.8, c = 1.0;
  TriangleMeshDesc quad;
  quad.vertices = {{-a / 2, -a / 2, c}, {a / 2, -a / 2, c}, {a / 2, a / 2, c}, {-a / 2, a / 2, c}};
  quad.triangles = {{0, 2, 1}, {0, 3, 2}};  // facing down
  desc.objects.push_back(ObjectDesc{quad, static_cast<int>(desc.materials.size() - 1), {}});
  const RenderScene scene(desc);
  const EmissiveTriangles emitters(scene);
  ASSERT_EQ(emitters.size(), 2u);
  const EnvironmentMap black(Vec3{0, 0, 0});
  const double A = a / (2 * c), s = std::sqrt(1 + A * A);
  const double irradiance = 2 * 4 * 2 * (A / s * std::atan(A / s));
  const double expected = 0.5 / M_PI * irradiance;
  for (const bool light_sampling : {true, false}) {
    RenderSettings settings = path_settings(scene, &black, 2);
    if (light_sampling) settings.emitters = &emitters;
    const RenderContext ctx(scene, settings);
    const double mean = mean_radiance(ctx, Ray{{0.05, -0.3, 0.5}, normalize(Vec3{-0.05, 0.3, -0.5}), 0, INFINITY}, 5, 20000);
    EXPECT_NEAR(mean, expected, 0.01 * expected) << (light_sampling ? "with" : "without") << " light sampling";
  }
}

}  // namespace
}  // namespace holoray

namespace holoray {
namespace {

// A lights file's area light of power P over a floor: its radiance is
// P / (pi A) (Cycles 4's, measured against Blender 4.3), and under
// its centre the floor shows rho / pi times the square's form-factor
// irradiance; above it (its unlit side) nothing. Drawn by the light's own
// sampling and met by the BSDF's rays, MIS-weighted.
TEST(PathIntegrator, AnAreaLightFromALightsFileLightsOneSideAsItsFormFactorSays) {
  SceneDesc desc = parse_nff("f 0.5 0.5 0.5 1 0 0 0 1\np 4\n-5 -5 0\n5 -5 0\n5 5 0\n-5 5 0\n", "floor.nff");
  const LightsFile lights = parse_lights_file(
      "[[light]]\ntype = \"area\"\nposition = [0, 0, 1]\ndirection = [0, 0, -1]\nright = [1, 0, 0]\n"
      "shape = \"rectangle\"\nsize = [0.8, 0.8]\npower = 12.8\n",
      "lights.toml");
  ASSERT_EQ(lights.area_lights.size(), 1u);
  EXPECT_NEAR(lights.area_lights[0].radiance.x, 12.8 / (M_PI * 0.64), 1e-12);
  desc.area_lights = lights.area_lights;
  const RenderScene scene(desc);
  const EnvironmentMap black(Vec3{0, 0, 0});
  const RenderContext ctx(scene, path_settings(scene, &black, 3));
  const double L = 12.8 / (M_PI * 0.64), A = 0.4, s = std::sqrt(1 + A * A);
  const double expected = 0.5 / M_PI * 2 * L * 2 * (A / s * std::atan(A / s));
  // The same light turned over, facing away from the floor: its back is dark.
  desc.area_lights[0].normal = -desc.area_lights[0].normal;
  const RenderScene turned(desc);
  const RenderContext turned_ctx(turned, path_settings(turned, &black, 3));
  const Ray to_floor{{0.05, -0.3, 0.5}, normalize(Vec3{-0.05, 0.3, -0.5}), 0, INFINITY};
  EXPECT_NEAR(mean_radiance(ctx, to_floor, 9, 20000), expected, 0.01 * expected);
  EXPECT_EQ(mean_radiance(turned_ctx, to_floor, 9, 20000), 0.0);
}

// A point light with a radius: Cycles' disk facing the lit point, the
// irradiance on its axis P / (4 pi (d^2 + r^2)) (measured against Blender
// 3.4: 7.48893 for P = 100, d = 1, r = 0.25); a sun with an angle keeps its
// irradiance S.
TEST(PathIntegrator, SoftLightsFromALightsFileKeepCyclesIrradiance) {
  const LightsFile lights = parse_lights_file(
      "[[light]]\ntype = \"point\"\nposition = [0, 0, 1]\npower = 100\nradius = 0.25\n"
      "[[light]]\ntype = \"sun\"\ndirection = [0, 0, -1]\nstrength = 3\nangle = 6\n",
      "lights.toml");
  ASSERT_EQ(lights.lights.size(), 2u);
  for (int which = 0; which < 2; ++which) {
    SceneDesc desc = parse_nff("f 1 1 1 1 0 0 0 1\np 4\n-5 -5 0\n5 -5 0\n5 5 0\n-5 5 0\n", "floor.nff");
    desc.lights = {lights.lights[static_cast<size_t>(which)]};
    const RenderScene scene(desc);
    const EnvironmentMap black(Vec3{0, 0, 0});
    const RenderContext ctx(scene, path_settings(scene, &black, 1));
    // A white Lambertian floor shows E / pi.
    const double irradiance = mean_radiance(ctx, Ray{{0.1, 0.1, 0.5}, normalize(Vec3{-0.1, -0.1, -0.5}), 0, INFINITY}, 3, 4000) * M_PI;
    if (which == 0) EXPECT_NEAR(irradiance, 100 / (4 * M_PI * (1 + 0.0625)), 0.005 * 7.49);
    else EXPECT_NEAR(irradiance, 3 * (1 + std::cos(3 * M_PI / 180)) / 2, 1e-3);
  }
}

// What a lights file may not say is refused at its line and column.
TEST(LightsFile, RefusesMalformedLightsAtTheirLineAndColumn) {
  auto first_line = [](const std::function<void()>& f) {
    const std::string e = test::error_of(f);
    return e.substr(0, e.find('\n'));
  };
  EXPECT_EQ(first_line([] { parse_lights_file("[[light]]\ntype = \"area\"\nposition = [0, 0, 1]\n", "l.toml"); }),
            "l.toml:1:1: error: an area light needs `direction` = [x, y, z]");
  EXPECT_EQ(test::error_of([] { parse_lights_file("[[light]]\ntype = \"point\"\npositon = [0, 0, 1]\n", "l.toml"); })
                .substr(0, 20),
            "l.toml:3:1: error: u");
  EXPECT_EQ(first_line([] {
              parse_lights_file("[[light]]\ntype = \"area\"\nposition = [0,0,1]\ndirection = [0,0,-1]\nright = [0,0,1]\n", "l.toml");
            }),
            "l.toml:5:9: error: right: expected a direction across `direction`, not along it");
  EXPECT_EQ(first_line([] {
              parse_lights_file("[[light]]\ntype = \"area\"\nposition = [0,0,1]\ndirection = [0,0,-1]\nright = [1,0,0]\n"
                                "shape = \"disk\"\nsize = [1, 2]\n", "l.toml");
            }),
            "l.toml:7:8: error: size: expected one number for a disk");
}

}  // namespace
}  // namespace holoray

namespace holoray {
namespace {

// `animate --integrator path` traces every frame in full, each as `render`
// path traces the still (the same samples: the noise stays put from frame
// to frame, as Cycles' by default); reuse, which reprojects Whitted's
// shading, is refused saying why.
TEST(PathIntegrator, AnimatedFramesArePathTracedAsTheStill) {
  test::TempDir dir;
  const std::string scene = test::source_dir() + "/tests/data/pinhole/spheres.nff";
  // A shot's samples per pixel are its file's `spp`.
  test::write_text(dir.file("shot.toml"), "frames = 2\nspp = 4\n[[object]]\nscene = \"" + scene + "\"\n");
  const std::string light = " --integrator path --environment-colour 0.3,0.4,0.5";
  const auto anim = test::run_cli("animate " + dir.file("shot.toml") + " --camera pinhole --resolution 40x30" + light +
                                  " --format exr -o " + dir.file("frames") + " -q");
  ASSERT_EQ(anim.status, 0) << anim.output;
  const auto still = test::run_cli("render " + scene + " --camera pinhole --resolution 40x30 --spp 4" + light + " -o " +
                                   dir.file("still.exr") + " -q");
  ASSERT_EQ(still.status, 0) << still.output;
  const ImageBuffer a = read_image(dir.file("frames/frame_0001.exr")), b = read_image(dir.file("still.exr"));
  ASSERT_EQ(a.width, 40);
  EXPECT_EQ(as_rgb(a).data, as_rgb(b).data);
  const auto whitted = test::run_cli("render " + scene + " --camera pinhole --resolution 40x30 -o " + dir.file("w.exr") + " -q");
  ASSERT_EQ(whitted.status, 0) << whitted.output;
  EXPECT_NE(as_rgb(read_image(dir.file("w.exr"))).data, as_rgb(b).data) << "the path integrator ran";
  const auto reuse = test::run_cli("animate " + dir.file("shot.toml") + light + " --method reverse -o " + dir.file("r") + " -q");
  EXPECT_EQ(reuse.status, 1);
  EXPECT_NE(reuse.output.find("--integrator path: goes with --method full (reuse reprojects Whitted's shading; path "
                              "tracing traces every frame in full)"),
            std::string::npos)
      << reuse.output;
}

// `animate --seed S` draws every frame's samples as `render --seed S`;
// with --animated-seed, frame f's as `render --seed S+f` (Cycles' Animated
// Seed), so a shot where nothing moves changes noise from frame to frame.
// Under Whitted's integrator both are refused, by the CLI and the API.
TEST(PathIntegrator, AnimatedSeedsDrawEachFramesSamplesAsTheStillOfItsSeed) {
  test::TempDir dir;
  const std::string scene = test::source_dir() + "/tests/data/pinhole/spheres.nff";
  test::write_text(dir.file("shot.toml"), "frames = 3\nspp = 2\n[[object]]\nscene = \"" + scene + "\"\n");
  const std::string view = " --camera pinhole --resolution 40x30 --integrator path --environment-colour 0.3,0.4,0.5";
  const auto frames_of = [&](const std::string& seeds, const std::string& out) {
    const auto run = test::run_cli("animate " + dir.file("shot.toml") + view + seeds + " --format exr -o " + dir.file(out) + " -q");
    EXPECT_EQ(run.status, 0) << run.output;
    std::vector<FloatSamples> f;
    for (int k = 0; k < 3; ++k) f.push_back(as_rgb(read_image(dir.file(fmt::format("{}/frame_{:04d}.exr", out, k)))).data);
    return f;
  };
  const auto still = [&](int seed) {
    const std::string out = dir.file(fmt::format("still_{}.exr", seed));
    const auto run = test::run_cli("render " + scene + view + " --spp 2 --seed " + std::to_string(seed) + " -o " + out + " -q");
    EXPECT_EQ(run.status, 0) << run.output;
    return as_rgb(read_image(out)).data;
  };
  const auto fixed = frames_of(" --seed 7", "fixed");
  const auto animated = frames_of(" --seed 7 --animated-seed", "animated");
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(fixed[static_cast<size_t>(k)], still(7)) << "frame " << k;
    EXPECT_EQ(animated[static_cast<size_t>(k)], still(7 + k)) << "frame " << k;
  }
  EXPECT_NE(animated[1], animated[0]) << "a new seed, new noise";
  const auto whitted = test::run_cli("animate " + dir.file("shot.toml") + " --camera pinhole --seed 3 -o " + dir.file("w") + " -q");
  EXPECT_EQ(whitted.status, 1);
  EXPECT_NE(whitted.output.find("--seed: Whitted's integrator draws no random samples: go with --integrator path"),
            std::string::npos)
      << whitted.output;
  api::AnimateOptions o;
  o.animated_seed = true;
  try {
    api::Animation a(dir.file("shot.toml"), o);
    ADD_FAILURE() << "an animated seed under Whitted's integrator was taken";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "`animated_seed`: Whitted's integrator draws no random samples: go with the path integrator");
  }
}

}  // namespace
}  // namespace holoray

namespace holoray {
namespace {

// A lights file's lights are the scene's own: a mesh file's stand-in
// headlight goes (found by a Blender scene with a black world: the add-on
// sends its lights as a file, and the headlight lit the scene besides).
TEST(PathIntegrator, ALightsFileReplacesTheReadersHeadlight) {
  test::TempDir dir;
  test::write_text(dir.file("s.obj"), "v -2 0 -2\nv 2 0 -2\nv 2 0 2\nv -2 0 2\nf 1 4 3 2\n");
  test::write_text(dir.file("l.toml"), "[[light]]\ntype = \"point\"\nposition = [0, 2, 0]\npower = 100\n");
  api::Scene with_file = api::Scene::load(dir.file("s.obj"));
  EXPECT_EQ(with_file.light_count(), 1) << "the headlight";
  with_file.add_lights(dir.file("l.toml"));
  EXPECT_EQ(with_file.light_count(), 1) << "the file's light alone";
  api::RenderOptions o;
  o.integrator = api::Integrator::path;
  o.spp = 4;
  api::Pinhole view;
  view.width = 24, view.height = 18;
  const api::Result file_only = api::render(with_file, view, o);
  o.environment.colour = std::array<double, 3>{0, 0, 0};  // light of the render's own: no headlight either way
  const api::Result black = api::render(with_file, view, o);
  EXPECT_TRUE(std::isinf(api::psnr(file_only.colour, black.colour)));
}

// A mesh file without lights gets the readers' headlight; its emissive
// surfaces are light of its own, so the path integrator leaves the
// headlight out, as it does for an environment given on the command line:
// the two renders are the same image.
TEST(PathIntegrator, EmissiveSurfacesReplaceTheReadersHeadlight) {
  test::TempDir dir;
  test::write_text(dir.file("s.mtl"), "newmtl floor\nKd 0.8 0.8 0.8\nnewmtl lamp\nKd 0 0 0\nKe 4 4 4\n");
  test::write_text(dir.file("s.obj"),
                   "mtllib s.mtl\nv -2 0 -2\nv 2 0 -2\nv 2 0 2\nv -2 0 2\nv -0.3 1 -0.3\nv 0.3 1 -0.3\nv 0.3 1 0.3\nv -0.3 1 0.3\n"
                   "usemtl floor\nf 1 4 3 2\nusemtl lamp\nf 5 6 7 8\n");
  const std::string common = "render " + dir.file("s.obj") + " --camera pinhole --resolution 32x24 --integrator path --spp 4 -q";
  const auto own = test::run_cli(common + " -o " + dir.file("own.exr"));
  const auto black = test::run_cli(common + " --environment-colour 0,0,0 -o " + dir.file("black.exr"));
  ASSERT_EQ(own.status, 0) << own.output;
  ASSERT_EQ(black.status, 0) << black.output;
  const ImageBuffer a = read_image(dir.file("own.exr")), b = read_image(dir.file("black.exr"));
  EXPECT_EQ(as_rgb(a).data, as_rgb(b).data);
  float brightest = 0;
  for (float v : as_rgb(a).data) brightest = std::max(brightest, v);
  EXPECT_GT(brightest, 1.0f) << "the lamp is seen";
}

}  // namespace
}  // namespace holoray
