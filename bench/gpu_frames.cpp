// bench/gpu_frames: one scene's EIA rendered again and again by one built
// Renderer on one device, for bench/run_gpu_bench.sh (issue 55). Through
// the public API alone. Prints one line of key=value pairs: the device, the
// median and range of the dispatch time per frame (ray generation,
// traversal and shading; the scene's upload and the image's readback
// apart), rays per second, BVH nodes visited and primitives tested per ray
// (counted in one more frame by a Renderer built to count them: counting
// slows the kernel, RenderOptions::count_work), and under the path
// integrator's wavefront (HOLORAY_GPU_WAVEFRONT=1) its traversals' lanes'
// use (nodes visited over their lanes' steps: 1 when no lane waits),
// and with --cpu the PSNR of the last frame against the CPU path's image,
// with the depth and id AOVs' agreement where both hit. With --integrator
// path, the path integrator at --spp samples per pixel, lit by the scene's
// lights, a lights file (--lights) and an environment image (--environment).
//
// Usage: holoray_gpu_frames SCENE [--device gpu] [--lenses 240x135] [--ppl 16] [--frames 20] [--warmup 3] [--cpu]
//          [--integrator whitted|path] [--spp N] [--max-depth D] [--lights FILE] [--environment FILE]
#include <holoray/holoray.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

using namespace holoray::api;

namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr,
                 "usage: %s SCENE [--device gpu] [--lenses NXxNY] [--ppl P] [--frames N] [--warmup K] [--cpu] "
                 "[--integrator whitted|path] [--spp N] [--max-depth D] [--lights FILE] [--environment FILE]\n",
                 argv[0]);
    return 2;
  }
  std::string scene_path = argv[1], device = "gpu", integrator = "whitted", lights, environment;
  int lx = 240, ly = 135, ppl = 16, frames = 20, warmup = 3, spp = 1, max_depth = 0;
  bool cpu = false;
  for (int k = 2; k < argc; ++k) {
    const std::string a = argv[k];
    auto next = [&] { return k + 1 < argc ? std::string(argv[++k]) : std::string(); };
    if (a == "--device") device = next();
    else if (a == "--lenses") std::sscanf(next().c_str(), "%dx%d", &lx, &ly);
    else if (a == "--ppl") ppl = std::atoi(next().c_str());
    else if (a == "--frames") frames = std::atoi(next().c_str());
    else if (a == "--warmup") warmup = std::atoi(next().c_str());
    else if (a == "--cpu") cpu = true;
    else if (a == "--integrator") integrator = next();
    else if (a == "--spp") spp = std::atoi(next().c_str());
    else if (a == "--max-depth") max_depth = std::atoi(next().c_str());
    else if (a == "--lights") lights = next();
    else if (a == "--environment") environment = next();
    else {
      std::fprintf(stderr, "unknown argument %s\n", a.c_str());
      return 2;
    }
  }
  try {
    Scene scene = Scene::load(scene_path);
    if (!lights.empty()) scene.add_lights(lights);
    LensArray array;
    array.lenses_x = lx, array.lenses_y = ly, array.pixels_per_lens = ppl;
    RenderOptions options;
    options.device = device;
    options.aovs.depth = options.aovs.id = cpu;
    options.integrator = integrator == "path" ? Integrator::path : Integrator::whitted;
    options.spp = spp;
    options.max_depth = max_depth;
    options.environment.file = environment;
    const auto t0 = std::chrono::steady_clock::now();
    const Renderer renderer(scene, array, options);
    const double setup = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::vector<double> trace, readback;
    Result last;
    for (int f = 0; f < warmup + frames; ++f) {
      last = renderer.render();
      if (f < warmup) continue;
      trace.push_back(last.stats.trace_seconds);
      readback.push_back(last.stats.readback_seconds);
    }
    RenderOptions counting = options;
    counting.count_work = true;
    const RenderStats st = Renderer(scene, array, counting).render().stats;
    const double rays = double(st.rays.total()), ms = median(trace) * 1e3;
    std::printf("scene=%s device=\"%s\" size=%dx%d spp=%d frames=%d setup_s=%.3f ms_median=%.3f ms_min=%.3f ms_max=%.3f "
                "fps=%.1f readback_ms=%.3f rays=%.0f mrays_s=%.1f nodes_per_ray=%.2f prims_per_ray=%.2f lanes_use=%s",
                scene_path.c_str(), renderer.device_name().empty() ? "cpu" : renderer.device_name().c_str(),
                renderer.width(), renderer.height(), spp, frames, setup, ms, *std::min_element(trace.begin(), trace.end()) * 1e3,
                *std::max_element(trace.begin(), trace.end()) * 1e3, 1e3 / ms, median(readback) * 1e3, rays,
                rays / (ms * 1e-3) / 1e6, double(st.nodes_visited) / rays, double(st.primitives_tested) / rays,
                st.lane_steps ? std::to_string(double(st.nodes_visited) / double(st.lane_steps)).substr(0, 5).c_str() : "-");
    if (cpu) {
      RenderOptions on_cpu = options;
      on_cpu.device = "cpu";
      const auto tc = std::chrono::steady_clock::now();
      const Result ref = render(scene, array, on_cpu);
      const double cpu_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - tc).count();
      // Depth within 1e-4 relative where both hit (relative to 1 % of the
      // image's largest |t| at least: t is signed, 0 on the lens plane);
      // ids equal.
      size_t both = 0, depth_off = 0, id_same = 0, n = size_t(ref.id.width()) * ref.id.height();
      float t_max = 0;
      for (size_t k = 0; k < n; ++k)
        if (!std::isnan(ref.depth.data()[k])) t_max = std::fmax(t_max, std::fabs(ref.depth.data()[k]));
      for (size_t k = 0; k < n; ++k) {
        const float a = ref.depth.data()[k], b = last.depth.data()[k];
        if (!std::isnan(a) && !std::isnan(b)) {
          ++both;
          if (std::fabs(a - b) > 1e-4 * std::fmax(std::fabs(a), 0.01f * t_max)) ++depth_off;
        }
        id_same += ref.id.data()[k] == last.id.data()[k];
      }
      std::printf(" cpu_trace_s=%.3f cpu_total_s=%.3f psnr_db=%.2f depth_off_pct=%.4f id_equal_pct=%.4f", ref.stats.trace_seconds,
                  cpu_s, psnr(ref.colour, last.colour), 100.0 * depth_off / std::max<size_t>(both, 1),
                  100.0 * id_same / std::max<size_t>(n, 1));
    }
    std::printf("\n");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "holoray_gpu_frames: %s\n", e.what());
    return 1;
  }
  return 0;
}
