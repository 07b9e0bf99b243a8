// Kernel benchmarks (issues 2 and 4): on the SPD scenes at 128x128 lenses x
// 16 px (2048x2048), primary-ray throughput of the integral camera in each
// pixel-tracing style against plain Embree on the very same rays, in the same
// packet order (rtcIntersect1 and rtcIntersect16: the yardsticks), full
// Whitted shading per frame in each style, and the paper's Table 3: the time
// to trace the first lens in each style. All use the same oneTBB schedule.
#include <benchmark/benchmark.h>
#include <oneapi/tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <tuple>

#include "accel/embree_api.hpp"
#include "camera/placement.hpp"
#include "render/renderer.hpp"
#include "render/tiles.hpp"
#include "scene/nff_reader.hpp"

using namespace holoray;

namespace {

constexpr int kLenses = 128, kPixelsPerLens = 16;

// Embree reads a packet's valid mask with aligned loads.
struct alignas(64) ValidMask {
  int lane[16];
};

struct Fixture {
  std::unique_ptr<RenderScene> scene;
  std::unique_ptr<LensArray> camera;
  // The camera's primary rays, lens by lens in packet order (packet_order),
  // for the yardsticks: one RTCRayHit per ray, and the same rays as packets
  // of 16 with their valid masks (partial packets where a lens has fewer).
  std::vector<RTCRayHit> rays;
  std::vector<RTCRayHit16> packets;
  std::vector<ValidMask> valid;
};

// The rays that follow the eye rays, built from the eye rays' hits as the
// shading builds them (render/shading.cpp): for every packet of one lens and
// every light, the shadow rays of its hits that face the light, as one packet;
// for every hit on a mirror (ks > 0), its mirror ray.
struct KindRays {
  std::vector<RayPacket> shadow;
  std::vector<int> shadow_light;  // the light each shadow packet goes to
  std::vector<RayPacket> shadow_sorted;  // the same rays regrouped: sorted_shadow_packets()
  std::vector<Ray> mirror;
  int64_t shadow_rays = 0;
};

RTCRay to_rtc(const Ray& r) {
  RTCRay o{};
  o.org_x = static_cast<float>(r.org.x);
  o.org_y = static_cast<float>(r.org.y);
  o.org_z = static_cast<float>(r.org.z);
  o.dir_x = static_cast<float>(r.dir.x);
  o.dir_y = static_cast<float>(r.dir.y);
  o.dir_z = static_cast<float>(r.dir.z);
  o.tnear = static_cast<float>(r.tnear);
  o.tfar = static_cast<float>(r.tfar);
  o.mask = ~0u;
  return o;
}

// Calls fn(block) for every lens block (P x P) of the EIA, lens rows in parallel.
template <class Fn>
void for_each_lens(const LensArray& cam, Fn&& fn) {
  const int P = cam.desc().pixels_per_lens;
  const int rows = (cam.height() + P - 1) / P, cols = (cam.width() + P - 1) / P;
  tbb::parallel_for(tbb::blocked_range<int>(0, rows, 1), [&](const tbb::blocked_range<int>& r) {
    for (int ly = r.begin(); ly != r.end(); ++ly)
      for (int lx = 0; lx < cols; ++lx)
        fn(TileRect{lx * P, ly * P, std::min(cam.width(), lx * P + P), std::min(cam.height(), ly * P + P)});
  });
}

// Fixtures per (scene, lens count). The benchmarks run scene by scene, and
// only the current scene's rays are kept: the shadow rays of tree_s11's
// 2048x2048 EIA alone take about 2 GB.
template <class T>
using Cache = std::map<std::pair<std::string, int>, T>;
Cache<Fixture>& fixtures() {
  static Cache<Fixture> c;
  return c;
}
Cache<KindRays>& kinds() {
  static Cache<KindRays> c;
  return c;
}
void keep_only(const std::string& name) {
  std::erase_if(fixtures(), [&](const auto& e) { return e.first.first != name; });
  std::erase_if(kinds(), [&](const auto& e) { return e.first.first != name; });
}

Fixture& fixture(const std::string& name, int lenses = kLenses) {
  keep_only(name);
  auto it = fixtures().find({name, lenses});
  if (it != fixtures().end()) return it->second;
  Fixture& f = fixtures()[{name, lenses}];
  const SceneDesc desc = read_nff_file(std::string(HOLORAY_SHARED_DIR) + "/scenes/nff/" + name + ".nff");
  f.scene = std::make_unique<RenderScene>(desc);
  ArraySettings s;
  s.lenses_x = s.lenses_y = lenses;
  s.pixels_per_lens = kPixelsPerLens;
  f.camera = std::make_unique<LensArray>(place_array(s, desc.viewpoint));
  const LensArray& cam = *f.camera;
  const int P = cam.desc().pixels_per_lens;
  std::vector<PixelXY> px(static_cast<size_t>(P) * P);
  for (int by = 0; by < cam.height(); by += P)
    for (int bx = 0; bx < cam.width(); bx += P) {
      const PixelXY* lanes = px.data();
      const int n = packet_order(TileRect{bx, by, std::min(cam.width(), bx + P), std::min(cam.height(), by + P)}, px.data());
      for (int start = 0; start < n; start += 16) {
        RTCRayHit16 packet{};
        ValidMask valid{};
        for (int l = 0; l < 16 && start + l < n; ++l) {
          const auto pr = primary_ray(cam, f.scene->bounds(), f.scene->epsilon(), lanes[start + l].i, lanes[start + l].j);
          if (!pr) continue;
          RTCRayHit rh{};
          rh.ray = to_rtc(pr->ray);
          f.rays.push_back(rh);
          valid.lane[l] = -1;
          packet.ray.org_x[l] = rh.ray.org_x;
          packet.ray.org_y[l] = rh.ray.org_y;
          packet.ray.org_z[l] = rh.ray.org_z;
          packet.ray.dir_x[l] = rh.ray.dir_x;
          packet.ray.dir_y[l] = rh.ray.dir_y;
          packet.ray.dir_z[l] = rh.ray.dir_z;
          packet.ray.tnear[l] = rh.ray.tnear;
          packet.ray.tfar[l] = rh.ray.tfar;
          packet.ray.mask[l] = ~0u;
        }
        f.packets.push_back(packet);
        f.valid.push_back(valid);
      }
    }
  return f;
}

Vec3 mirror(const Vec3& d, const Vec3& n) { return d - n * (2 * dot(d, n)); }

KindRays& kind_rays(const std::string& name, int lenses) {
  const Fixture& f = fixture(name, lenses);
  auto it = kinds().find({name, lenses});
  if (it != kinds().end()) return it->second;
  KindRays& k = kinds()[{name, lenses}];
  const RenderScene& scene = *f.scene;
  const double eps = scene.epsilon();
  for (size_t pk = 0; pk < f.packets.size(); ++pk) {
    // The eye rays again, in double, with their hits and surface points.
    RayPacket eye;
    const RTCRay16& r = f.packets[pk].ray;
    for (int l = 0; l < kPacketSize; ++l) {
      eye.active[l] = f.valid[pk].lane[l] != 0;
      eye.rays[l] = Ray{Vec3{r.org_x[l], r.org_y[l], r.org_z[l]}, normalize(Vec3{r.dir_x[l], r.dir_y[l], r.dir_z[l]}),
                        r.tnear[l], r.tfar[l]};
    }
    Hit hits[kPacketSize];
    bool found[kPacketSize] = {};
    scene.accel().intersect(eye, hits, found, RayCoherence::coherent);
    SurfacePoint sp[kPacketSize];
    Vec3 ng[kPacketSize], ns[kPacketSize];
    for (int l = 0; l < kPacketSize; ++l) {
      if (!found[l]) continue;
      sp[l] = scene.surface(eye.rays[l], hits[l], {});
      const bool front = dot(sp[l].ng, -eye.rays[l].dir) >= 0;
      ng[l] = front ? sp[l].ng : -sp[l].ng;
      ns[l] = front ? sp[l].ns : -sp[l].ns;
      if (sp[l].material->ks > 0) {
        Vec3 m = mirror(eye.rays[l].dir, ns[l]);
        if (dot(m, ng[l]) <= 0) m = mirror(eye.rays[l].dir, ng[l]);
        k.mirror.push_back(Ray{sp[l].position + ng[l] * eps, normalize(m), 0, INFINITY});
      }
    }
    for (const PointLight& light : scene.lights()) {
      RayPacket shadow;
      int cast = 0;
      for (int l = 0; l < kPacketSize; ++l) {
        if (!found[l]) continue;
        Vec3 to = light.position - sp[l].position;
        const double dist = length(to);
        if (!(dist > eps)) continue;
        to = to / dist;
        if (dot(ns[l], to) <= 0) continue;
        shadow.rays[l] = Ray{sp[l].position + ng[l] * eps, to, 0, dist - eps};
        shadow.active[l] = true;
        ++cast;
      }
      if (cast == 0) continue;
      k.shadow.push_back(shadow);
      k.shadow_light.push_back(static_cast<int>(&light - scene.lights().data()));
      k.shadow_rays += cast;
    }
  }
  return k;
}

bool have_scenes() { return std::filesystem::is_directory(std::string(HOLORAY_SHARED_DIR) + "/scenes/nff"); }

// Integral camera, primary visibility only: generate each pixel's line, clip
// it to the scene, trace, refine the hit in double. Single rays lens by lens
// (row by row inside each), or 16-ray packets per lens (TraceStyle::packet).
void BM_IntegralPrimary(benchmark::State& state, const std::string& name, TraceStyle style, int lenses) {
  if (!have_scenes()) return state.SkipWithError("no ../shared/scenes");
  Fixture& f = fixture(name, lenses);
  const LensArray& cam = *f.camera;
  const RenderScene& scene = *f.scene;
  int64_t rays = 0;
  for (auto _ : state) {
    std::atomic<int64_t> count{0};
    for_each_lens(cam, [&](const TileRect& b) {
      int64_t local = 0;
      if (style == TraceStyle::packet) {
        PixelXY px[kPixelsPerLens * kPixelsPerLens];
        const int n = packet_order(b, px);
        for (int start = 0; start < n; start += kPacketSize) {
          RayPacket packet;
          PrimaryRay pr[kPacketSize];
          bool ok[kPacketSize];
          const int m = std::min(kPacketSize, n - start);
          primary_rays(cam, scene.bounds(), scene.epsilon(), px + start, m, 0, pr, ok);
          for (int l = 0; l < m; ++l) {
            if (!ok[l]) continue;
            packet.rays[l] = pr[l].ray;
            packet.active[l] = true;
            ++local;
          }
          Hit hits[kPacketSize];
          bool found[kPacketSize];
          scene.accel().intersect(packet, hits, found, RayCoherence::coherent);
          benchmark::DoNotOptimize(found);
        }
      } else {
        for (int j = b.y0; j < b.y1; ++j)
          for (int i = b.x0; i < b.x1; ++i) {
            const auto pr = primary_ray(cam, scene.bounds(), scene.epsilon(), i, j);
            if (!pr) continue;
            Hit hit;
            benchmark::DoNotOptimize(scene.accel().intersect(pr->ray, hit, RayCoherence::coherent));
            ++local;
          }
      }
      count += local;
    });
    rays += count;
  }
  state.counters["rays"] = benchmark::Counter(static_cast<double>(rays), benchmark::Counter::kIsRate);
}

// Yardstick: plain rtcIntersect16 over the same rays in the same packets, no
// ray generation, no refinement, no shading.
void BM_EmbreePacket(benchmark::State& state, const std::string& name) {
  if (!have_scenes()) return state.SkipWithError("no ../shared/scenes");
  Fixture& f = fixture(name);
  auto* scene = static_cast<RTCScene>(f.scene->accel().rtc_scene());
  std::vector<RTCRayHit16> work = f.packets;
  const int64_t n = static_cast<int64_t>(work.size());
  for (auto _ : state) {
    state.PauseTiming();
    work = f.packets;
    for (auto& p : work)
      for (auto& id : p.hit.geomID) id = RTC_INVALID_GEOMETRY_ID;
    state.ResumeTiming();
    tbb::parallel_for(tbb::blocked_range<int64_t>(0, n, 256), [&](const tbb::blocked_range<int64_t>& r) {
      for (int64_t k = r.begin(); k != r.end(); ++k)
        embree::intersect16(f.valid[static_cast<size_t>(k)].lane, scene, work[static_cast<size_t>(k)], true);
    });
  }
  state.counters["rays"] = benchmark::Counter(static_cast<double>(f.rays.size() * state.iterations()), benchmark::Counter::kIsRate);
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
      for (int64_t k = r.begin(); k != r.end(); ++k) embree::intersect1(scene, work[static_cast<size_t>(k)], true);
    });
  }
  state.counters["rays"] = benchmark::Counter(static_cast<double>(n * state.iterations()), benchmark::Counter::kIsRate);
}

// Shadow rays alone, as the renderer traces them: 16-ray packets toward one
// light (AccelScene::occluded, rtcOccluded16).
void BM_ShadowRays(benchmark::State& state, const std::string& name, int lenses) {
  if (!have_scenes()) return state.SkipWithError("no ../shared/scenes");
  const KindRays& k = kind_rays(name, lenses);
  const AccelScene& accel = fixture(name, lenses).scene->accel();
  const int64_t n = static_cast<int64_t>(k.shadow.size());
  for (auto _ : state) {
    tbb::parallel_for(tbb::blocked_range<int64_t>(0, n, 256), [&](const tbb::blocked_range<int64_t>& r) {
      bool blocked[kPacketSize];
      for (int64_t p = r.begin(); p != r.end(); ++p) {
        accel.occluded(k.shadow[static_cast<size_t>(p)], blocked);
        benchmark::DoNotOptimize(blocked);
      }
    });
  }
  state.counters["rays"] = benchmark::Counter(static_cast<double>(k.shadow_rays * state.iterations()), benchmark::Counter::kIsRate);
}

// The frame's shadow rays regrouped into packets of one light whose origins
// are neighbours: sorted by light, then by the Morton code of the origin
// (10 bits per axis over the scene bounds). The ceiling of what a renderer
// that queues a whole frame's shadow rays before tracing them could gain
// (the renderer traces each eye packet's shadow rays right away).
const std::vector<RayPacket>& sorted_shadow_packets(const std::string& name, int lenses) {
  KindRays& k = kind_rays(name, lenses);
  if (!k.shadow_sorted.empty()) return k.shadow_sorted;
  const Bounds3 b = fixture(name, lenses).scene->bounds();
  auto morton = [&](const Vec3& p) {
    auto cell = [](double v, double lo, double hi) {
      return static_cast<uint64_t>(std::clamp((v - lo) / (hi - lo), 0.0, 1.0) * 1023);
    };
    const uint64_t x = cell(p.x, b.lo.x, b.hi.x), y = cell(p.y, b.lo.y, b.hi.y), z = cell(p.z, b.lo.z, b.hi.z);
    uint64_t m = 0;
    for (int i = 0; i < 10; ++i) m |= (x >> i & 1) << (3 * i) | (y >> i & 1) << (3 * i + 1) | (z >> i & 1) << (3 * i + 2);
    return m;
  };
  struct Keyed {
    uint64_t key;
    Ray ray;
  };
  std::vector<Keyed> all;
  all.reserve(static_cast<size_t>(k.shadow_rays));
  for (size_t p = 0; p < k.shadow.size(); ++p)
    for (int l = 0; l < kPacketSize; ++l)
      if (k.shadow[p].active[l])
        all.push_back({static_cast<uint64_t>(k.shadow_light[p]) << 32 | morton(k.shadow[p].rays[l].org), k.shadow[p].rays[l]});
  std::sort(all.begin(), all.end(), [](const Keyed& a, const Keyed& c) { return a.key < c.key; });
  RayPacket cur;
  int n = 0;
  for (size_t i = 0; i < all.size(); ++i) {
    if (n == kPacketSize || (n > 0 && all[i].key >> 32 != all[i - 1].key >> 32)) {
      k.shadow_sorted.push_back(cur);
      cur = RayPacket{};
      n = 0;
    }
    cur.rays[n] = all[i].ray;
    cur.active[n++] = true;
  }
  if (n > 0) k.shadow_sorted.push_back(cur);
  return k.shadow_sorted;
}

// The same shadow rays as BM_ShadowRays, in sorted_shadow_packets' packets
// (the sort itself not timed).
void BM_ShadowRaysSorted(benchmark::State& state, const std::string& name, int lenses) {
  if (!have_scenes()) return state.SkipWithError("no ../shared/scenes");
  const std::vector<RayPacket>& packets = sorted_shadow_packets(name, lenses);
  const int64_t rays = kind_rays(name, lenses).shadow_rays;
  const AccelScene& accel = fixture(name, lenses).scene->accel();
  const int64_t n = static_cast<int64_t>(packets.size());
  for (auto _ : state) {
    tbb::parallel_for(tbb::blocked_range<int64_t>(0, n, 256), [&](const tbb::blocked_range<int64_t>& r) {
      bool blocked[kPacketSize];
      for (int64_t p = r.begin(); p != r.end(); ++p) {
        accel.occluded(packets[static_cast<size_t>(p)], blocked);
        benchmark::DoNotOptimize(blocked);
      }
    });
  }
  state.counters["rays"] = benchmark::Counter(static_cast<double>(rays * state.iterations()), benchmark::Counter::kIsRate);
}

// The Morton code of `p` on a 1024^3 grid over `b` (30 bits).
uint32_t morton30(const Vec3& p, const Bounds3& b) {
  auto cell = [](double v, double lo, double hi) {
    return static_cast<uint32_t>(std::clamp((v - lo) / (hi - lo), 0.0, 1.0) * 1023);
  };
  auto spread = [](uint32_t v) {  // 10 bits to every third bit
    v = (v | v << 16) & 0x030000FFu;
    v = (v | v << 8) & 0x0300F00Fu;
    v = (v | v << 4) & 0x030C30C3u;
    return (v | v << 2) & 0x09249249u;
  };
  return spread(cell(p.x, b.lo.x, b.hi.x)) | spread(cell(p.y, b.lo.y, b.hi.y)) << 1 | spread(cell(p.z, b.lo.z, b.hi.z)) << 2;
}

// A wavefront's shadow stage, timed whole: the frame's shadow rays taken in
// windows of about `window` rays in the renderer's order (lens by lens), each
// window keyed by light and the Morton code of the origin, sorted, gathered
// into packets of one light and traced (rtcOccluded16). Windows go to the
// threads as tiles do. What window a wave needs for the sorted order to pay
// for its own sort: against BM_ShadowRays, the same rays in today's packets.
void BM_ShadowRaysWindowed(benchmark::State& state, const std::string& name, int lenses, int64_t window) {
  if (!have_scenes()) return state.SkipWithError("no ../shared/scenes");
  const KindRays& k = kind_rays(name, lenses);
  const AccelScene& accel = fixture(name, lenses).scene->accel();
  const Bounds3 b = fixture(name, lenses).scene->bounds();
  // Window boundaries in packets.
  std::vector<size_t> starts{0};
  int64_t in_window = 0;
  for (size_t p = 0; p < k.shadow.size(); ++p) {
    in_window += std::count(k.shadow[p].active, k.shadow[p].active + kPacketSize, true);
    if (in_window >= window) {
      starts.push_back(p + 1);
      in_window = 0;
    }
  }
  if (starts.back() != k.shadow.size()) starts.push_back(k.shadow.size());
  const int64_t windows = static_cast<int64_t>(starts.size()) - 1;
  for (auto _ : state) {
    tbb::parallel_for(tbb::blocked_range<int64_t>(0, windows, 1), [&](const tbb::blocked_range<int64_t>& r) {
      thread_local std::vector<std::pair<uint64_t, const Ray*>> keyed;
      for (int64_t w = r.begin(); w != r.end(); ++w) {
        keyed.clear();
        for (size_t p = starts[static_cast<size_t>(w)]; p < starts[static_cast<size_t>(w) + 1]; ++p)
          for (int l = 0; l < kPacketSize; ++l)
            if (k.shadow[p].active[l])
              keyed.emplace_back(static_cast<uint64_t>(k.shadow_light[p]) << 32 | morton30(k.shadow[p].rays[l].org, b),
                                 &k.shadow[p].rays[l]);
        std::sort(keyed.begin(), keyed.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
        RayPacket packet;
        bool blocked[kPacketSize];
        int n = 0;
        for (size_t i = 0; i <= keyed.size(); ++i) {
          if (n == kPacketSize || (n > 0 && (i == keyed.size() || keyed[i].first >> 32 != keyed[i - 1].first >> 32))) {
            std::fill(packet.active + n, packet.active + kPacketSize, false);
            accel.occluded(packet, blocked);
            benchmark::DoNotOptimize(blocked);
            n = 0;
          }
          if (i == keyed.size()) break;
          packet.rays[n] = *keyed[i].second;
          packet.active[n++] = true;
        }
      }
    });
  }
  state.counters["rays"] = benchmark::Counter(static_cast<double>(k.shadow_rays * state.iterations()), benchmark::Counter::kIsRate);
  state.counters["windows"] = static_cast<double>(windows);
}

// The frame's shadow rays as a wave would hold them: one array per
// coordinate in float (origins as Embree takes them), in the renderer's
// order, each with its 32-bit sort key (light in the top 3 bits, then the
// Morton code of the origin on a 512^3 grid). Built once, untimed, as
// today's packets are for BM_ShadowRays.
struct ShadowSoA {
  std::vector<float> ox, oy, oz, dx, dy, dz, tfar;
  std::vector<uint32_t> key;
  std::vector<int64_t> window_starts;
};

const ShadowSoA& shadow_soa(const std::string& name, int lenses, int64_t window) {
  static std::map<std::tuple<std::string, int, int64_t>, ShadowSoA> cache;
  std::erase_if(cache, [&](const auto& e) { return std::get<0>(e.first) != name; });
  auto it = cache.find({name, lenses, window});
  if (it != cache.end()) return it->second;
  ShadowSoA& a = cache[{name, lenses, window}];
  const KindRays& k = kind_rays(name, lenses);
  const Bounds3 b = fixture(name, lenses).scene->bounds();
  for (size_t p = 0; p < k.shadow.size(); ++p)
    for (int l = 0; l < kPacketSize; ++l) {
      if (!k.shadow[p].active[l]) continue;
      const Ray& r = k.shadow[p].rays[l];
      a.ox.push_back(static_cast<float>(r.org.x)), a.oy.push_back(static_cast<float>(r.org.y));
      a.oz.push_back(static_cast<float>(r.org.z)), a.dx.push_back(static_cast<float>(r.dir.x));
      a.dy.push_back(static_cast<float>(r.dir.y)), a.dz.push_back(static_cast<float>(r.dir.z));
      a.tfar.push_back(static_cast<float>(r.tfar));
      a.key.push_back(static_cast<uint32_t>(k.shadow_light[p]) << 27 | morton30(r.org, b) >> 3);
    }
  const int64_t n = static_cast<int64_t>(a.key.size());
  for (int64_t s = 0; s < n; s += window) a.window_starts.push_back(s);
  a.window_starts.push_back(n);
  return a;
}

// The shadow stage of a wave with a cheaper sort: per window, the rays'
// indices sorted by their 32-bit keys with an LSD radix sort (3 passes of 10
// bits), then gathered straight into Embree's 16-wide layout (ShadowPacket)
// and traced. Timed: the sort, the gather, the trace.
void BM_ShadowRaysRadix(benchmark::State& state, const std::string& name, int lenses, int64_t window) {
  if (!have_scenes()) return state.SkipWithError("no ../shared/scenes");
  const ShadowSoA& a = shadow_soa(name, lenses, window);
  const AccelScene& accel = fixture(name, lenses).scene->accel();
  const int64_t windows = static_cast<int64_t>(a.window_starts.size()) - 1;
  for (auto _ : state) {
    tbb::parallel_for(tbb::blocked_range<int64_t>(0, windows, 1), [&](const tbb::blocked_range<int64_t>& r) {
      thread_local std::vector<uint32_t> idx, tmp;
      for (int64_t w = r.begin(); w != r.end(); ++w) {
        const int64_t s0 = a.window_starts[static_cast<size_t>(w)], n = a.window_starts[static_cast<size_t>(w) + 1] - s0;
        idx.resize(static_cast<size_t>(n));
        tmp.resize(static_cast<size_t>(n));
        for (int64_t i = 0; i < n; ++i) idx[static_cast<size_t>(i)] = static_cast<uint32_t>(i);
        const uint32_t* key = a.key.data() + s0;
        for (int shift = 0; shift < 30; shift += 10) {
          uint32_t count[1025] = {};
          for (int64_t i = 0; i < n; ++i) ++count[(key[idx[static_cast<size_t>(i)]] >> shift & 1023) + 1];
          for (int c = 0; c < 1024; ++c) count[c + 1] += count[c];
          for (int64_t i = 0; i < n; ++i) {
            const uint32_t v = idx[static_cast<size_t>(i)];
            tmp[count[key[v] >> shift & 1023]++] = v;
          }
          idx.swap(tmp);
        }
        ShadowPacket packet;
        bool blocked[kPacketSize];
        int m = 0;
        for (int64_t i = 0; i <= n; ++i) {
          const bool end = i == n;
          if (m == kPacketSize || (m > 0 && (end || key[idx[static_cast<size_t>(i)]] >> 27 != key[idx[static_cast<size_t>(i - 1)]] >> 27))) {
            for (int l = m; l < kPacketSize; ++l) packet.valid[l] = 0;
            accel.occluded(packet, blocked);
            benchmark::DoNotOptimize(blocked);
            m = 0;
          }
          if (end) break;
          const size_t v = static_cast<size_t>(s0) + idx[static_cast<size_t>(i)];
          const float org[3] = {a.ox[v], a.oy[v], a.oz[v]};
          packet.set(m++, org, Vec3{a.dx[v], a.dy[v], a.dz[v]}, a.tfar[v], true);
        }
      }
    });
  }
  state.counters["rays"] = benchmark::Counter(static_cast<double>(a.key.size() * state.iterations()), benchmark::Counter::kIsRate);
}

// The same SoA rays in the renderer's order, unsorted, gathered into
// ShadowPacket 16 at a time and traced: BM_ShadowRaysRadix's baseline with
// the same layout, so that only the order differs.
void BM_ShadowRaysSoA(benchmark::State& state, const std::string& name, int lenses) {
  if (!have_scenes()) return state.SkipWithError("no ../shared/scenes");
  const ShadowSoA& a = shadow_soa(name, lenses, 65536);
  const AccelScene& accel = fixture(name, lenses).scene->accel();
  const int64_t n = static_cast<int64_t>(a.key.size());
  for (auto _ : state) {
    tbb::parallel_for(tbb::blocked_range<int64_t>(0, (n + 15) / 16, 256), [&](const tbb::blocked_range<int64_t>& r) {
      ShadowPacket packet;
      bool blocked[kPacketSize];
      for (int64_t p = r.begin(); p != r.end(); ++p) {
        int m = 0;
        for (int64_t i = p * 16; i < std::min(n, p * 16 + 16); ++i) {
          const size_t v = static_cast<size_t>(i);
          const float org[3] = {a.ox[v], a.oy[v], a.oz[v]};
          packet.set(m++, org, Vec3{a.dx[v], a.dy[v], a.dz[v]}, a.tfar[v], true);
        }
        for (int l = m; l < kPacketSize; ++l) packet.valid[l] = 0;
        accel.occluded(packet, blocked);
        benchmark::DoNotOptimize(blocked);
      }
    });
  }
  state.counters["rays"] = benchmark::Counter(static_cast<double>(n * state.iterations()), benchmark::Counter::kIsRate);
}

// Mirror rays alone, as the renderer traces them: one by one, incoherent,
// each hit refined in double (AccelScene::intersect).
void BM_MirrorRays(benchmark::State& state, const std::string& name, int lenses) {
  if (!have_scenes()) return state.SkipWithError("no ../shared/scenes");
  const KindRays& k = kind_rays(name, lenses);
  const AccelScene& accel = fixture(name, lenses).scene->accel();
  const int64_t n = static_cast<int64_t>(k.mirror.size());
  if (n == 0) return state.SkipWithError("no mirror in this scene");
  for (auto _ : state) {
    tbb::parallel_for(tbb::blocked_range<int64_t>(0, n, 1024), [&](const tbb::blocked_range<int64_t>& r) {
      Hit hit;
      for (int64_t p = r.begin(); p != r.end(); ++p)
        benchmark::DoNotOptimize(accel.intersect(k.mirror[static_cast<size_t>(p)], hit, RayCoherence::incoherent));
    });
  }
  state.counters["rays"] = benchmark::Counter(static_cast<double>(n * state.iterations()), benchmark::Counter::kIsRate);
}

// Full Whitted shading: one whole EIA per iteration, in one style.
void BM_FullShading(benchmark::State& state, const std::string& name, TraceStyle style) {
  if (!have_scenes()) return state.SkipWithError("no ../shared/scenes");
  Fixture& f = fixture(name);
  RenderOptions opt;
  opt.style = style;
  uint64_t rays = 0;
  for (auto _ : state) {
    RenderStats stats;
    benchmark::DoNotOptimize(render_frame(*f.scene, *f.camera, opt, stats));
    rays += stats.rays.total();
  }
  state.counters["rays"] = benchmark::Counter(static_cast<double>(rays), benchmark::Counter::kIsRate);
}

// The paper's Table 3: the time to render (trace and shade) the first lens,
// one thread, in one style. The paper's lens is a cylindrical one; here the
// top-left elemental image of the square array, 16 x 16 pixels.
void BM_FirstLens(benchmark::State& state, const std::string& name, TraceStyle style) {
  if (!have_scenes()) return state.SkipWithError("no ../shared/scenes");
  Fixture& f = fixture(name);
  const LensArray& cam = *f.camera;
  const TileRect b{0, 0, kPixelsPerLens, kPixelsPerLens};
  for (auto _ : state) {
    RayCounts counts;
    Vec3 sum;
    render_block(*f.scene, cam, b, style, 1, false, counts,
                 [&](int, int, const Vec3& c, const PrimaryHit&, const SurfacePoint&) { sum += c; });
    benchmark::DoNotOptimize(sum);
  }
}

const char* style_name(TraceStyle s) {
  return s == TraceStyle::packet ? "packet" : s == TraceStyle::horizontal ? "horizontal" : "vertical";
}

const int registered = [] {
  for (const char* name : {"balls_s4", "gears_s4", "teapot_s6", "tree_s11"}) {
    const std::string scene = name;
    auto reg = [&](const std::string& what, auto fn, auto... args) {
      return benchmark::RegisterBenchmark((what + "/" + scene).c_str(), fn, scene, args...)
          ->Unit(benchmark::kMillisecond)->UseRealTime();
    };
    for (const TraceStyle style : {TraceStyle::packet, TraceStyle::horizontal})
      reg(std::string("IntegralPrimary_") + style_name(style), BM_IntegralPrimary, style, kLenses)->Iterations(3)->Repetitions(3);
    // Mrays/s by ray kind (eye rays in the packet style, shadow rays, mirror
    // rays) at 512x512, 1024x1024 and 2048x2048: Kind<EIA width>_<kind>.
    for (const int lenses : {32, 64, 128}) {
      const std::string kind = "Kind" + std::to_string(lenses * kPixelsPerLens) + "_";
      reg(kind + "eye", BM_IntegralPrimary, TraceStyle::packet, lenses)->Iterations(3)->Repetitions(3);
      reg(kind + "shadow", BM_ShadowRays, lenses)->Iterations(3)->Repetitions(3);
      reg(kind + "shadow_sorted", BM_ShadowRaysSorted, lenses)->Iterations(3)->Repetitions(3);
      if (lenses == 128)  // the wave's window, by measurement (issue 43)
        for (const int64_t window : {4096, 16384, 65536, 262144, 1048576})
          reg(kind + "shadow_window" + std::to_string(window), BM_ShadowRaysWindowed, lenses, window)
              ->Iterations(3)->Repetitions(3);
      if (lenses == 128) {
        reg(kind + "shadow_soa", BM_ShadowRaysSoA, lenses)->Iterations(3)->Repetitions(3);
        for (const int64_t window : {4096, 16384, 65536, 262144, 1048576})
          reg(kind + "shadow_radix" + std::to_string(window), BM_ShadowRaysRadix, lenses, window)
              ->Iterations(3)->Repetitions(3);
      }
      reg(kind + "mirror", BM_MirrorRays, lenses)->Iterations(3)->Repetitions(3);
    }
    reg("EmbreeRaw", BM_EmbreeRaw)->Iterations(3)->Repetitions(3);
    reg("EmbreePacket", BM_EmbreePacket)->Iterations(3)->Repetitions(3);
    for (const TraceStyle style : {TraceStyle::packet, TraceStyle::horizontal, TraceStyle::vertical}) {
      reg(std::string("FullShading_") + style_name(style), BM_FullShading, style)->Iterations(1)->Repetitions(3);
      reg(std::string("FirstLens_") + style_name(style), BM_FirstLens, style)->Unit(benchmark::kMicrosecond)->Repetitions(5);
    }
  }
  return 0;
}();

}  // namespace

BENCHMARK_MAIN();
