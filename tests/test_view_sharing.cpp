// A quilt's views sharing their path samples (render/view_sharing.hpp,
// path_tracer.hpp's FirstVertexRecord): a sample's first vertex seen from
// its own eye gives back its radiance; seen from another eye it estimates
// what that eye's own paths estimate; a shared quilt converges to the
// unshared one with less noise, the same for any thread count; and the API
// refuses sharing where there is nothing to share, saying why.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "holoray/render.hpp"
#include "holoray/scene.hpp"
#include "image/metrics.hpp"
#include "render/environment.hpp"
#include "render/path_tracer.hpp"
#include "render/view_renderer.hpp"
#include "scene/nff_reader.hpp"
#include "test_util.hpp"

namespace holoray {
namespace {

// A sphere of `material` on a Lambertian floor under a sky with a bright
// band, and one point light: light from every side, a shadow, a bounce.
SceneDesc sphere_on_floor(const Material* material) {
  SceneDesc desc = parse_nff(
      "v\nfrom 0 -5 1.5\nat 0 0 0\nup 0 0 1\nangle 36\nhither 0\nresolution 32 32\n"
      "l 3 -3 5\nf 0.8 0.5 0.3 1 0 0 0 1\ns 0 0 0 1\nf 0.6 0.6 0.6 1 0 0 0 1\np 4 -6 -6 -1 6 -6 -1 6 6 -1 -6 6 -1\n",
      "floor.nff");
  if (material) desc.materials[0] = *material;
  return desc;
}

Material rough_metal(double roughness) {
  Material m;
  m.model = ShadingModel::gltf;
  m.colour = {0.9, 0.7, 0.4};
  m.metallic = 1;
  m.roughness = roughness;
  return m;
}

Material glossy_plastic() {
  Material m;
  m.model = ShadingModel::gltf;
  m.colour = {0.2, 0.4, 0.8};
  m.metallic = 0;
  m.roughness = 0.35;
  return m;
}

EnvironmentMap banded_sky() {
  ImageBuffer img(16, 8, 3);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 16; ++x)
      for (int c = 0; c < 3; ++c) img.at(x, y)[c] = y < 3 ? 1.5f + x % 3 : 0.2f;
  return EnvironmentMap(img, 1.0, 0.0, EnvironmentUp::z);
}

RenderSettings path_settings(const RenderScene& scene, const EnvironmentMap* env) {
  RenderSettings s = file_settings(scene);
  s.integrator = Integrator::path;
  s.environment = env;
  s.max_depth = 5;
  return s;
}

// The path sample k of stream `seed` along the ray from `eye` to `x`.
Vec3 sample_toward(const RenderContext& ctx, const Vec3& eye, const Vec3& x, uint32_t seed, int k, FirstVertexRecord* rec) {
  shading::HrSampler sampler = shading::hr_sampler(seed, static_cast<uint32_t>(k));
  shading::hr_next2(sampler);
  RayCounts counts;
  return path_radiance(ctx, Ray{eye, normalize(x - eye), 0, INFINITY}, sampler, counts, nullptr, nullptr, nullptr, rec);
}

// The record's terms, evaluated for the eye they were gathered for, sum to
// the sample's radiance: nothing is lost or counted twice in the split
// (next-event terms, the bounce's rest, the emission), on a rough metal, a
// glossy dielectric (Blender's Principled diffuse too) and Lambert's.
TEST(ViewSharing, ASampleSeenFromItsOwnEyeIsItsRadiance) {
  const EnvironmentMap sky = banded_sky();
  const Material metal = rough_metal(0.4), plastic = glossy_plastic();
  for (const Material* material : {&metal, &plastic, static_cast<const Material*>(nullptr)})
    for (const bool principled : {false, true}) {
      const RenderScene scene(sphere_on_floor(material));
      RenderSettings settings = path_settings(scene, &sky);
      settings.principled = principled;
      const RenderContext ctx(scene, settings);
      int shared = 0;
      for (int k = 0; k < 256; ++k) {
        const Vec3 eye{0, -5, 1.5}, x{0.3 * std::sin(k * 0.7), -0.2, 0.3 * std::cos(k * 0.3)};
        FirstVertexRecord rec;
        const Vec3 c = sample_toward(ctx, eye, x, 7, k, &rec);
        if (!rec.shareable) continue;
        ++shared;
        Vec3 again;
        ASSERT_TRUE(path_radiance_toward(ctx, rec, rec.eye_dir, again));
        for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(again[ch], c[ch], 1e-4 * (1 + c[ch])) << "sample " << k;
      }
      EXPECT_EQ(shared, 256) << "a sphere of these materials shares every sample";
    }
}

// A point x on a glossy sphere seen from two eyes 3 degrees apart: the
// samples gathered through eye A, evaluated for eye B, estimate the
// radiance toward B as B's own paths do (their means within 4 standard
// errors), and both differ from A's own where the lobe makes them differ.
TEST(ViewSharing, SamplesSharedWithAnotherEyeEstimateItsRadiance) {
  const EnvironmentMap sky = banded_sky();
  const Material plastic = glossy_plastic();
  const RenderScene scene(sphere_on_floor(&plastic));
  const RenderContext ctx(scene, path_settings(scene, &sky));
  const Vec3 x = normalize(Vec3{0.4, -1, 0.5});  // on the unit sphere, facing both eyes
  const Vec3 a{0, -5, 1.5};
  const double turn = 3 * M_PI / 180;
  const Vec3 b{a.x * std::cos(turn) - a.y * std::sin(turn), a.x * std::sin(turn) + a.y * std::cos(turn), a.z};
  const int n = 16384;
  double shared_sum = 0, shared_sq = 0, own_sum = 0, own_sq = 0;
  for (int k = 0; k < n; ++k) {
    FirstVertexRecord rec;
    sample_toward(ctx, a, x, 11, k, &rec);
    ASSERT_TRUE(rec.shareable);
    ASSERT_LT(length(rec.surface.position - x), 1e-6);
    Vec3 seen;
    ASSERT_TRUE(path_radiance_toward(ctx, rec, normalize(x - b), seen));
    shared_sum += seen.x, shared_sq += seen.x * seen.x;
    const double own = sample_toward(ctx, b, x, 13, k, nullptr).x;
    own_sum += own, own_sq += own * own;
  }
  const double ms = shared_sum / n, mo = own_sum / n;
  const double se = std::sqrt((shared_sq / n - ms * ms) / n + (own_sq / n - mo * mo) / n);
  EXPECT_NEAR(ms, mo, 4 * se) << "shared " << ms << ", B's own " << mo;
  EXPECT_LT(se, 0.01 * mo) << "the test can tell a bias of a few percent";
}

// A 4x2 quilt of 24x32 views (30 degree cone) of the glossy sphere on the
// floor, against the unshared quilt at 1024 samples: sharing with 3 views
// on each side, 8 samples a pixel come at least 3 dB nearer it than 8
// unshared ones (measured 4.0 to 4.6 dB at 4 and 16 samples: up to 7
// views see a point), and at 256 samples no further than 256 unshared
// ones: a bias (a sample pooled where the pixel's other samples see
// another surface: silhouettes, edges) would show there as a floor (it
// measured 33 dB against 38).
TEST(ViewSharing, ASharedQuiltConvergesToTheUnsharedOneWithLessNoise) {
  const EnvironmentMap sky = banded_sky();
  const Material plastic = glossy_plastic();
  const SceneDesc desc = sphere_on_floor(&plastic);
  const RenderScene scene(desc);
  const RenderContext ctx(scene, path_settings(scene, &sky));
  const Viewpoint& vp = *desc.viewpoint;
  const QuiltCamera quilt(QuiltDesc{4, 2, 24, 32, 30}, PinholeDesc{vp.from, vp.at, vp.up, vp.angle_deg, 24, 32});
  auto render = [&](int spp, int share) {
    RenderOptions ro;
    ro.spp = spp;
    ro.share_views = share;
    RenderStats stats;
    return render_quilt(ctx, quilt, ro, stats).colour;
  };
  const ImageBuffer ref = render(1024, 0);
  const double plain8 = compare_images(render(8, 0), ref).psnr_all(), shared8 = compare_images(render(8, 3), ref).psnr_all();
  EXPECT_GT(shared8, plain8 + 3) << "8 spp: unshared " << plain8 << " dB, shared " << shared8 << " dB";
  const double plain256 = compare_images(render(256, 0), ref).psnr_all(), shared256 = compare_images(render(256, 3), ref).psnr_all();
  EXPECT_GT(shared256, plain256 - 0.2) << "256 spp: unshared " << plain256 << " dB, shared " << shared256 << " dB";
}

// One task traces one row of every view and keeps what it shares: which
// thread takes which row changes no bit.
TEST(ViewSharing, TheSharedQuiltIsTheSameForAnyThreadCount) {
  const EnvironmentMap sky = banded_sky();
  const Material metal = rough_metal(0.5);
  for (const Material* material : {&metal, static_cast<const Material*>(nullptr)}) {  // the BSDF evaluated again; Lambert's
    const SceneDesc desc = sphere_on_floor(material);
    const RenderScene scene(desc);
    const RenderContext ctx(scene, path_settings(scene, &sky));
    const Viewpoint& vp = *desc.viewpoint;
    const QuiltCamera quilt(QuiltDesc{3, 2, 32, 32, 30}, PinholeDesc{vp.from, vp.at, vp.up, vp.angle_deg, 32, 32});
    auto render = [&](int threads) {
      RenderOptions ro;
      ro.spp = 4;
      ro.share_views = 2;
      ro.threads = threads;
      RenderStats stats;
      return render_quilt(ctx, quilt, ro, stats).colour.data;
    };
    EXPECT_EQ(render(1), render(2));
    EXPECT_EQ(render(1), render(3));
  }
}

// Sharing goes with a quilt, the path integrator and the CPU; each other
// case is refused before anything is rendered, saying what it needs.
TEST(ViewSharing, TheApiRefusesSharingWhereThereIsNothingToShare) {
  const test::TempDir tmp;
  const std::string file = tmp.path.string() + "/s.nff";
  std::ofstream(file) << "v\nfrom 0 -4 0\nat 0 0 0\nup 0 0 1\nangle 40\nhither 0\nresolution 8 8\ns 0 0 0 1\n";
  const api::Scene scene = api::Scene::load(file);
  api::Quilt q;
  q.columns = 2, q.rows = 1, q.view_width = 8, q.view_height = 8;
  api::RenderOptions o;
  o.share_views = 2;
  EXPECT_EQ(test::error_of([&] { api::Renderer(scene, api::Camera{q}, o); }),
            "share_views: views share path samples: go with the path integrator");
  o.integrator = api::Integrator::path;
  EXPECT_EQ(test::error_of([&] { api::Renderer(scene, api::Camera{api::Pinhole{}}, o); }),
            "share_views: goes with a quilt, whose views share their samples");
  o.share_views = api::kMaxShareViews + 1;
  EXPECT_EQ(test::error_of([&] { api::Renderer(scene, api::Camera{q}, o); }),
            "share_views: expected 0 to 16 views on each side, got 17");
  o.share_views = 1;
  o.device = "gpu";
  EXPECT_EQ(test::error_of([&] { api::Renderer(scene, api::Camera{q}, o); }),
            "share_views: views share their samples on the CPU only");
  o.device = "cpu";
  EXPECT_NO_THROW(api::Renderer(scene, api::Camera{q}, o).render());
}

}  // namespace
}  // namespace holoray
