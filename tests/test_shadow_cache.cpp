// The shadow cache (render/shadow_cache.hpp, issue 12): surface cells round
// trip, the cached image against tracing every shadow ray, determinism,
// validity across moving frames, and the memory bound.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include "camera/placement.hpp"
#include "image/image_io.hpp"
#include "image/metrics.hpp"
#include "render/renderer.hpp"
#include "render/shadow_cache.hpp"
#include "scene/nff_reader.hpp"

using namespace holoray;

namespace {

LensArrayDesc looking_at(const Vec3& from, int lenses = 32, int pixels = 8) {
  ArraySettings s;
  s.lenses_x = s.lenses_y = lenses;
  s.pixels_per_lens = pixels;
  return place_array(s, Viewpoint{from, {0, 0, 0}, {0, 0, 1}, 45});
}

struct Rendered {
  FrameBuffers fb;
  RenderStats stats;
};

// `scene` as its file asks, with `cache` (null: every shadow ray traced).
RenderContext with_cache(const RenderScene& scene, const ShadowCache* cache) {
  RenderSettings settings = file_settings(scene);
  settings.shadow_cache = cache;
  return {scene, settings};
}

Rendered render(const RenderContext& scene, const LensArrayDesc& cam, int threads = 0,
                TileOrder order = TileOrder::row_major) {
  RenderOptions opt;
  opt.threads = threads;
  opt.tile_order = order;
  Rendered r;
  r.fb = render_frame(scene, LensArray(cam), opt, r.stats);
  return r;
}

// Largest difference of one channel, in 8-bit steps.
double max_lsb(const ImageBuffer& a, const ImageBuffer& b) {
  double worst = 0;
  for (size_t k = 0; k < a.data.size(); ++k) worst = std::fmax(worst, std::fabs(a.data[k] - b.data[k]) * 255);
  return worst;
}

ShadowCacheOptions cells_of(double size) {
  ShadowCacheOptions o;
  o.cell_size = size;
  return o;
}

// A sphere, a cone and a mirror floor lit by two lights: the sphere and cone
// shadow the floor, with shadow edges, umbrae and reflections of both.
const char* kOccluders =
    "l 3 -2 6\nl -4 -3 5\n"
    "f 0.9 0.6 0.3 0.8 0.2 20 0 1\ns 0 0 0.6 0.6\n"
    "f 0.3 0.7 0.9 0.9 0 0 0 1\nc -1.2 0.8 0 0.25 -1.2 0.8 1.3 0.05\n"
    "f 0.8 0.8 0.8 0.7 0.3 30 0 1\np 4\n-4 -4 0\n4 -4 0\n4 4 0\n-4 4 0\n";

}  // namespace

TEST(SurfaceCells, EveryCellCentreLocatesBackToItsCell) {
  const SceneDesc desc = parse_nff(kOccluders, "cells.nff");
  const RenderScene scene(desc);
  const SurfaceCells cells(scene.accel(), 0.3, uint64_t{1} << 30);
  const GeometryGroup& geo = scene.accel().geometry(0);
  size_t checked = 0;
  auto check = [&](PrimKind kind, uint32_t prim, uint32_t slots) {
    for (uint32_t local = 0; local < slots; ++local) {
      CellSample s[SurfaceCells::kMaxSamples];
      const int n = cells.samples(0, kind, prim, local, s);
      const CellSample& centre = s[n - 1];
      // Triangles locate by barycentrics: recover them from the centre point.
      double u = 0, v = 0;
      if (kind == PrimKind::triangle) {
        const uint32_t* idx = &geo.triangles.indices[3 * size_t{prim}];
        auto vtx = [&](int k) {
          const float* p = &geo.triangles.positions[3 * size_t{idx[k]}];
          return Vec3{p[0], p[1], p[2]};
        };
        const Vec3 v0 = vtx(0), e1 = vtx(1) - v0, e2 = vtx(2) - v0, nrm = cross(e1, e2);
        const double area = dot(nrm, nrm);
        u = dot(cross(centre.p_object - v0, e2), nrm) / area;
        v = dot(cross(e1, centre.p_object - v0), nrm) / area;
        if (u + v > 1 + 1e-9) continue;  // the unused upper slot of the last row
      }
      const CellRef ref = cells.locate(0, kind, prim, u, v, centre.p_object);
      EXPECT_EQ(ref.local, local) << "kind " << static_cast<int>(kind) << " prim " << prim;
      ++checked;
    }
  };
  const CellRef first_sphere = cells.locate(0, PrimKind::sphere, 0, 0, 0, {0, 0, 1.2});
  const CellRef first_cone = cells.locate(0, PrimKind::cone, 0, 0, 0, {-1.2 + 0.25, 0.8, 0});
  ASSERT_NE(first_sphere.slot, CellRef::kNone);
  ASSERT_NE(first_cone.slot, CellRef::kNone);
  // Slots are dense in order triangle, sphere, cone: their counts follow.
  const uint32_t tri_slots = static_cast<uint32_t>((first_sphere.slot - first_sphere.local) / 2);
  check(PrimKind::triangle, 0, tri_slots);
  check(PrimKind::triangle, 1, tri_slots);
  check(PrimKind::sphere, 0, static_cast<uint32_t>(first_cone.slot - first_cone.local - (first_sphere.slot - first_sphere.local)));
  check(PrimKind::cone, 0, static_cast<uint32_t>(cells.slot_count() - (first_cone.slot - first_cone.local)));
  EXPECT_GT(checked, 100u);
}

TEST(ShadowCache, WithoutOccludersTheImageIsTracingsWithinOneLsb) {
  // Two spheres that cannot shadow each other (lights on the viewer's side,
  // spheres side by side across the view), each lit by two lights.
  const SceneDesc desc = parse_nff(
      "l 0 -10 4\nl 2 -10 -3\nf 0.9 0.5 0.2 0.8 0.3 30 0 1\ns -1.2 0 0 1\nf 0.2 0.6 0.9 1 0 0 0 1\ns 1.2 0 0 1\n",
      "free.nff");
  const LensArrayDesc cam = looking_at({0, -12, 0});
  RenderScene scene(desc);
  const Rendered traced = render(scene, cam);
  ShadowCache cache(scene, cells_of(0.1));
  const Rendered cached = render(with_cache(scene, &cache), cam);
  EXPECT_LE(max_lsb(traced.fb.colour, cached.fb.colour), 1.0);
  // The cache answered most questions (else this test would prove nothing).
  const RayCounts& r = cached.stats.rays;
  EXPECT_EQ(r.shadow_queries(), traced.stats.rays.shadow);
  EXPECT_GT(r.shadow_cached, r.shadow_queries() * 9 / 10);
}

TEST(ShadowCache, WithOccludersEveryPixelKeepsItsShadow) {
  const SceneDesc desc = parse_nff(kOccluders, "occluders.nff");
  const LensArrayDesc cam = looking_at({1, -6, 5}, 48, 8);
  RenderScene scene(desc);
  const Rendered traced = render(scene, cam);
  ShadowCache cache(scene, cells_of(cam.pitch));
  const Rendered cached = render(with_cache(scene, &cache), cam);
  const ImageDifference d = compare_images(quantize_8bit(traced.fb.colour, Encoding::linear),
                                           quantize_8bit(cached.fb.colour, Encoding::linear));
  EXPECT_GE(d.psnr_all(), 50.0) << "MSE " << d.mse_all;
  EXPECT_GT(cached.stats.rays.shadow_cached, cached.stats.rays.shadow_queries() / 2);
}

TEST(ShadowCache, ThreadCountAndTileOrderDoNotChangeTheImage) {
  const SceneDesc desc = parse_nff(kOccluders, "occluders.nff");
  const LensArrayDesc cam = looking_at({1, -6, 5}, 24, 8);
  RenderScene scene(desc);
  // A fresh cache per render: each classifies its cells in its own order.
  auto cached = [&](int threads, TileOrder order) {
    ShadowCache cache(scene, cells_of(cam.pitch));
    return render(with_cache(scene, &cache), cam, threads, order).fb.colour.data;
  };
  const auto ref = cached(1, TileOrder::row_major);
  EXPECT_EQ(ref, cached(2, TileOrder::row_major));
  EXPECT_EQ(ref, cached(3, TileOrder::reversed));
  EXPECT_EQ(ref, cached(2, TileOrder::strided));
}

TEST(ShadowCache, AnOccluderCrossingTheLightLeavesNoStaleShadow) {
  // A ball moves across the light's path over a floor; one cache serves
  // every frame, as in `animate`.
  const SceneDesc ball = parse_nff("f 0.9 0.2 0.2 1 0 0 0 1\ns 0 0 1 0.5\n", "ball.nff");
  const SceneDesc floor =
      parse_nff("l 0 0 6\nf 0.8 0.8 0.8 1 0 0 0 1\np 4\n-4 -4 0\n4 -4 0\n4 4 0\n-4 4 0\n", "floor.nff");
  RenderScene scene({{&ball, true}, {&floor, false}});
  auto at = [](int f) { return std::vector<Affine>{Affine::translate({-3 + f * 0.75, 0, 0}), Affine{}}; };
  const LensArrayDesc cam = looking_at({0, -6, 6});
  scene.set_transforms(at(0));
  ShadowCache cache(scene, cells_of(cam.pitch));  // built at frame 0
  for (int f = 0; f <= 8; ++f) {
    scene.set_transforms(at(f));
    cache.sync();  // as a shot does after each move
    const Rendered traced = render(scene, cam);
    const Rendered cached = render(with_cache(scene, &cache), cam);
    const ImageDifference d = compare_images(quantize_8bit(traced.fb.colour, Encoding::linear),
                                             quantize_8bit(cached.fb.colour, Encoding::linear));
    EXPECT_GE(d.psnr_all(), 45.0) << "frame " << f;
  }
  EXPECT_EQ(cache.clears(), 8u);  // every move cleared it; the first frame did not move
}

TEST(ShadowCache, OverItsMemoryBoundItTracesInsteadOfFailing) {
  const SceneDesc desc = parse_nff(kOccluders, "occluders.nff");
  const LensArrayDesc cam = looking_at({1, -6, 5}, 16, 8);
  RenderScene scene(desc);
  const Rendered traced = render(scene, cam);
  ShadowCacheOptions o = cells_of(0.01);
  // 176 for the cell table (24 bytes x 4 primitives, 80 for the cone's
  // frame), room for 3 cells or vertices x 2 lights.
  o.memory_limit_bytes = 200;
  ShadowCache cache(scene, o);
  EXPECT_GT(cache.cells().uncovered_primitives(), 0u);
  EXPECT_LE(cache.bytes(), o.memory_limit_bytes);
  const Rendered cached = render(with_cache(scene, &cache), cam);
  const ImageDifference d = compare_images(quantize_8bit(traced.fb.colour, Encoding::linear),
                                           quantize_8bit(cached.fb.colour, Encoding::linear));
  EXPECT_GE(d.psnr_all(), 50.0);
  EXPECT_GT(cached.stats.rays.shadow, 0u);
}

TEST(ShadowCache, RefusesANonPositiveCellSize) {
  const SceneDesc desc = parse_nff(kOccluders, "occluders.nff");
  const RenderScene scene(desc);
  EXPECT_THROW(ShadowCache(scene, cells_of(0)), std::invalid_argument);
  EXPECT_THROW(ShadowCache(scene, cells_of(-1)), std::invalid_argument);
  EXPECT_THROW(ShadowCache(scene, cells_of(NAN)), std::invalid_argument);
}
