// Benchmarks for issue 2's table: on the SPD scenes at 128x128 lenses x 16 px
// (2048x2048), primary-ray throughput of the integral camera against plain
// Embree rtcIntersect1 on the very same rays (the yardstick), and full Whitted
// shading time per frame. Both primary kernels use the same oneTBB schedule.
#include <benchmark/benchmark.h>
#include <embree3/rtcore.h>
#include <oneapi/tbb/parallel_for.h>

#include <filesystem>
#include <map>
#include <memory>
#include <string>

#include "camera/placement.hpp"
#include "render/renderer.hpp"
#include "scene/nff_reader.hpp"

using namespace holoray;

namespace {

constexpr int kLenses = 128, kPixelsPerLens = 16;

struct Fixture {
  std::unique_ptr<RenderScene> scene;
  std::unique_ptr<LensArray> camera;
  std::vector<RTCRayHit> rays;  // the camera's primary rays, for the yardstick
};

Fixture& fixture(const std::string& name) {
  static std::map<std::string, Fixture> cache;
  auto it = cache.find(name);
  if (it != cache.end()) return it->second;
  Fixture& f = cache[name];
  const SceneDesc desc = read_nff_file(std::string(HOLORAY_SHARED_DIR) + "/scenes/nff/" + name + ".nff");
  f.scene = std::make_unique<RenderScene>(desc);
  ArraySettings s;
  s.lenses_x = s.lenses_y = kLenses;
  s.pixels_per_lens = kPixelsPerLens;
  f.camera = std::make_unique<LensArray>(place_array(s, desc.viewpoint));
  for (int j = 0; j < f.camera->height(); ++j)
    for (int i = 0; i < f.camera->width(); ++i) {
      const auto pr = primary_ray(*f.camera, f.scene->bounds(), f.scene->epsilon(), i, j);
      if (!pr) continue;
      RTCRayHit rh{};
      rh.ray.org_x = static_cast<float>(pr->ray.org.x);
      rh.ray.org_y = static_cast<float>(pr->ray.org.y);
      rh.ray.org_z = static_cast<float>(pr->ray.org.z);
      rh.ray.dir_x = static_cast<float>(pr->ray.dir.x);
      rh.ray.dir_y = static_cast<float>(pr->ray.dir.y);
      rh.ray.dir_z = static_cast<float>(pr->ray.dir.z);
      rh.ray.tnear = static_cast<float>(pr->ray.tnear);
      rh.ray.tfar = static_cast<float>(pr->ray.tfar);
      rh.ray.mask = ~0u;
      f.rays.push_back(rh);
    }
  return f;
}

bool have_scenes() { return std::filesystem::is_directory(std::string(HOLORAY_SHARED_DIR) + "/scenes/nff"); }

// Integral camera: generate each pixel's line, clip it to the scene, trace, refine t.
void BM_IntegralPrimary(benchmark::State& state, const std::string& name) {
  if (!have_scenes()) return state.SkipWithError("no ../shared/scenes");
  Fixture& f = fixture(name);
  const LensArray& cam = *f.camera;
  const int W = cam.width(), H = cam.height();
  int64_t rays = 0;
  for (auto _ : state) {
    std::atomic<int64_t> count{0};
    tbb::parallel_for(tbb::blocked_range<int>(0, H, kPixelsPerLens), [&](const tbb::blocked_range<int>& r) {
      int64_t local = 0;
      for (int j = r.begin(); j != r.end(); ++j)
        for (int i = 0; i < W; ++i) {
          const auto pr = primary_ray(cam, f.scene->bounds(), f.scene->epsilon(), i, j);
          if (!pr) continue;
          Hit hit;
          benchmark::DoNotOptimize(f.scene->accel().intersect(pr->ray, hit, RayCoherence::coherent));
          ++local;
        }
      count += local;
    });
    rays += count;
  }
  state.counters["rays"] = benchmark::Counter(static_cast<double>(rays), benchmark::Counter::kIsRate);
}

// Yardstick: plain rtcIntersect1 over the same rays, precomputed, no shading.
void BM_EmbreeRaw(benchmark::State& state, const std::string& name) {
  if (!have_scenes()) return state.SkipWithError("no ../shared/scenes");
  Fixture& f = fixture(name);
  auto* scene = static_cast<RTCScene>(f.scene->accel().rtc_scene());
  std::vector<RTCRayHit> work = f.rays;
  const int64_t n = static_cast<int64_t>(work.size());
  for (auto _ : state) {
    state.PauseTiming();
    work = f.rays;
    for (auto& rh : work) rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    state.ResumeTiming();
    tbb::parallel_for(tbb::blocked_range<int64_t>(0, n, 4096), [&](const tbb::blocked_range<int64_t>& r) {
      RTCIntersectContext ctx;
      rtcInitIntersectContext(&ctx);
      ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
      for (int64_t k = r.begin(); k != r.end(); ++k) rtcIntersect1(scene, &ctx, &work[static_cast<size_t>(k)]);
    });
  }
  state.counters["rays"] = benchmark::Counter(static_cast<double>(n * state.iterations()), benchmark::Counter::kIsRate);
}

// Full Whitted shading: one whole EIA per iteration.
void BM_FullShading(benchmark::State& state, const std::string& name) {
  if (!have_scenes()) return state.SkipWithError("no ../shared/scenes");
  Fixture& f = fixture(name);
  uint64_t rays = 0;
  for (auto _ : state) {
    RenderStats stats;
    benchmark::DoNotOptimize(render_frame(*f.scene, *f.camera, RenderOptions{}, stats));
    rays += stats.rays.total();
  }
  state.counters["rays"] = benchmark::Counter(static_cast<double>(rays), benchmark::Counter::kIsRate);
}

const int registered = [] {
  for (const char* name : {"balls_s4", "gears_s4", "teapot_s6", "tree_s11"}) {
    benchmark::RegisterBenchmark((std::string("IntegralPrimary/") + name).c_str(), BM_IntegralPrimary, name)
        ->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3)->Repetitions(3);
    benchmark::RegisterBenchmark((std::string("EmbreeRaw/") + name).c_str(), BM_EmbreeRaw, name)
        ->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3)->Repetitions(3);
    benchmark::RegisterBenchmark((std::string("FullShading/") + name).c_str(), BM_FullShading, name)
        ->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1)->Repetitions(3);
  }
  return 0;
}();

}  // namespace

BENCHMARK_MAIN();
