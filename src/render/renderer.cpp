#include "render/renderer.hpp"

#include <fmt/format.h>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <vector>

#include <emmintrin.h>

#include "render/path_tracer.hpp"
#include "render/shading.hpp"
#include "render/tiles.hpp"

namespace holoray {

const char* to_string(TraceStyle style) {
  switch (style) {
    case TraceStyle::packet: return "packet";
    case TraceStyle::subaperture: return "subaperture";
    case TraceStyle::horizontal: return "horizontal";
    case TraceStyle::vertical: return "vertical";
  }
  return "?";
}

TraceStyle preferred_style(const LensArrayDesc& desc) {
  const double width = desc.lenses_x * desc.pitch;
  return width > 4.0 * desc.gap * desc.pixels_per_lens ? TraceStyle::subaperture : TraceStyle::packet;
}

void sample_offset(int i, int j, int k, double& u, double& v) {
  if (k == 0) {
    u = v = 0.5;
    return;
  }
  // A hashed Cranley-Patterson rotation of the R2 sequence (the shared
  // sampler's hash): deterministic in (pixel, sample), so any schedule gives the same image.
  const uint32_t h = shading::hr_hash(static_cast<uint32_t>(i) * 73856093U ^ shading::hr_hash(static_cast<uint32_t>(j) * 19349663U));
  const double ru = (h & 0xffff) / 65536.0, rv = (h >> 16) / 65536.0;
  u = std::fmod(ru + k * 0.7548776662466927, 1.0);
  v = std::fmod(rv + k * 0.5698402909980532, 1.0);
}

namespace {

PrimaryHit make_primary(const PrimaryRay& pr, const Hit& hit) {
  PrimaryHit p;
  p.p_object[0] = static_cast<float>(hit.p_object.x);
  p.p_object[1] = static_cast<float>(hit.p_object.y);
  p.p_object[2] = static_cast<float>(hit.p_object.z);
  p.t = static_cast<float>(pr.t_offset + pr.t_sign * hit.t);
  p.prim = hit.prim;
  p.group = static_cast<uint16_t>(hit.group);
  p.kind = static_cast<uint8_t>(hit.kind);
  p.status = PrimaryHit::kHit;
  return p;
}

}  // namespace

uint64_t frame_bytes(int64_t pixels, const AovSet& aovs) {
  const uint64_t channels = 3 + (aovs.albedo ? 3 : 0) + (aovs.depth ? 1 : 0) + (aovs.normal ? 3 : 0) + (aovs.id ? 1 : 0);
  return static_cast<uint64_t>(pixels) * channels * sizeof(float);
}

FrameBuffers allocate_frame(int width, int height, const AovSet& aovs) {
  FrameBuffers fb;
  fb.colour = ImageBuffer(width, height, 3);
  if (aovs.albedo) fb.albedo = ImageBuffer(width, height, 3);
  if (aovs.depth) fb.depth = ImageBuffer(width, height, 1, NAN);
  if (aovs.normal) fb.normal = ImageBuffer(width, height, 3);
  if (aovs.id) fb.id = ImageBuffer(width, height, 1, -1.0f);
  return fb;
}

void store_pixel(FrameBuffers& fb, const AovSet& aovs, int i, int j, const Vec3& c, const SurfacePoint* sp, double t,
                 const Vec3& toward_viewer) {
  auto put = [](float* o, const Vec3& v) {
    o[0] = static_cast<float>(v.x), o[1] = static_cast<float>(v.y), o[2] = static_cast<float>(v.z);
  };
  put(fb.colour.at(i, j), c);
  if (!sp) return;
  if (aovs.albedo) put(fb.albedo.at(i, j), albedo_of(*sp));
  if (aovs.depth) *fb.depth.at(i, j) = static_cast<float>(t);
  if (aovs.normal) put(fb.normal.at(i, j), dot(sp->ns, toward_viewer) >= 0 ? sp->ns : -sp->ns);
  if (aovs.id) *fb.id.at(i, j) = static_cast<float>(sp->object);
}

namespace {

// The primary ray along the line o + t d, which crosses the scene box
// (grown by `margin`) over [t0, t1]; false when it cannot meet the scene.
inline bool primary_over(const Vec3& o, const Vec3& d, double t0, double t1, double margin, RecordingMode mode,
                         PrimaryRay& out) {
  if (mode == RecordingMode::orthoscopic) {
    const double start = t1 + margin;
    out = PrimaryRay{Ray{o + d * start, -d, 0, start - t0 + margin}, start, -1};
    return true;
  }
  if (t1 <= 0) return false;
  out = PrimaryRay{Ray{o, d, std::fmax(0.0, t0 - margin), t1 + margin}, 0, 1};
  return true;
}

// The primary ray along `line`, clipped to `box` (the scene bounds grown by
// `margin`); false when the line cannot meet the scene.
inline bool clip_primary(const PixelLine& line, const Bounds3& box, double margin, RecordingMode mode, PrimaryRay& out) {
  double t0, t1;
  return intersect_line_box(line.origin, line.dir, box, t0, t1) &&
         primary_over(line.origin, line.dir, t0, t1, margin, mode, out);
}

Bounds3 grown(const Bounds3& bounds, double margin) {
  Bounds3 b = bounds;
  b.lo -= Vec3{margin, margin, margin};
  b.hi += Vec3{margin, margin, margin};
  return b;
}

}  // namespace

std::optional<PrimaryRay> primary_ray(const LensArray& camera, const Bounds3& bounds, double margin, int i, int j,
                                      double u, double v) {
  if (bounds.empty()) return std::nullopt;
  PrimaryRay pr;
  if (!clip_primary(camera.line(i, j, u, v), grown(bounds, margin), margin, camera.desc().mode, pr)) return std::nullopt;
  return pr;
}

std::optional<PrimaryRay> primary_ray_along(const PixelLine& line, const Bounds3& bounds, double margin,
                                            RecordingMode mode) {
  if (bounds.empty()) return std::nullopt;
  PrimaryRay pr;
  if (!clip_primary(line, grown(bounds, margin), margin, mode, pr)) return std::nullopt;
  return pr;
}

namespace {

// intersect_line_box() for n lanes of `lines`, two per SSE2 instruction in
// its operations and order (its selects are minpd and maxpd with the same
// operands): hit[l], and the interval [t0[l], t1[l]] where hit. A pair
// with a zero direction coordinate (an axis-aligned line) takes the scalar
// test, whose special case keeps 0 * inf out.
void clip_lanes(const PixelLineLanes& lines, int n, const Bounds3& box, double t0[], double t1[], bool hit[]) {
  const double* org[3] = {lines.ox, lines.oy, lines.oz};
  const double* dir[3] = {lines.dx, lines.dy, lines.dz};
  auto scalar = [&](int l) {
    hit[l] = intersect_line_box(Vec3{lines.ox[l], lines.oy[l], lines.oz[l]}, Vec3{lines.dx[l], lines.dy[l], lines.dz[l]},
                                box, t0[l], t1[l]);
  };
  const __m128d one = _mm_set1_pd(1.0), zero = _mm_setzero_pd();
  int l = 0;
  for (; l + 1 < n; l += 2) {
    __m128d near_t = _mm_set1_pd(-INFINITY), far_t = _mm_set1_pd(INFINITY), axis_aligned = zero;
    for (int a = 0; a < 3; ++a) {
      const __m128d o = _mm_load_pd(org[a] + l), d = _mm_load_pd(dir[a] + l);
      axis_aligned = _mm_or_pd(axis_aligned, _mm_cmpeq_pd(d, zero));
      const __m128d inv = _mm_div_pd(one, d);
      const __m128d ta = _mm_mul_pd(_mm_sub_pd(_mm_set1_pd(box.lo[a]), o), inv);
      const __m128d tb = _mm_mul_pd(_mm_sub_pd(_mm_set1_pd(box.hi[a]), o), inv);
      near_t = _mm_max_pd(_mm_min_pd(ta, tb), near_t);
      far_t = _mm_min_pd(_mm_max_pd(tb, ta), far_t);
    }
    if (_mm_movemask_pd(axis_aligned)) {
      scalar(l), scalar(l + 1);
      continue;
    }
    _mm_storeu_pd(t0 + l, near_t);
    _mm_storeu_pd(t1 + l, far_t);
    const int inside = _mm_movemask_pd(_mm_cmple_pd(near_t, far_t));
    hit[l] = inside & 1, hit[l + 1] = (inside >> 1) & 1;
  }
  for (; l < n; ++l) scalar(l);
}

}  // namespace

void primary_rays(const LensArray& camera, const Bounds3& bounds, double margin, const PixelXY px[], int n, int k,
                  PrimaryRay out[], bool ok[]) {
  static_assert(PixelLineLanes::kLaneCount == kPacketSize);
  if (n > kPacketSize) throw std::invalid_argument(fmt::format("at most {} rays at once, got {}", kPacketSize, n));
  if (bounds.empty()) {
    std::fill(ok, ok + n, false);
    return;
  }
  int i[kPacketSize], j[kPacketSize];
  double u[kPacketSize], v[kPacketSize];
  for (int l = 0; l < n; ++l) {
    i[l] = px[l].i;
    j[l] = px[l].j;
    sample_offset(i[l], j[l], k, u[l], v[l]);
  }
  PixelLineLanes lines;
  camera.lines(i, j, u, v, n, lines);
  double t0[kPacketSize], t1[kPacketSize];
  bool hit[kPacketSize];
  clip_lanes(lines, n, grown(bounds, margin), t0, t1, hit);
  for (int l = 0; l < n; ++l)
    ok[l] = hit[l] && primary_over(Vec3{lines.ox[l], lines.oy[l], lines.oz[l]}, Vec3{lines.dx[l], lines.dy[l], lines.dz[l]},
                                   t0[l], t1[l], margin, camera.desc().mode, out[l]);
}

namespace {

// render_pixel under the path integrator (path_pixel_sum): a line that
// misses the scene sees the environment along the light's way back.
Vec3 path_pixel(const RenderContext& scene, const LensArray& camera, int i, int j, int spp, RayCounts& counts,
                PrimaryHit* primary, SurfacePoint* surface) {
  const bool ortho = camera.desc().mode == RecordingMode::orthoscopic;
  PathFirstHit first;
  const Vec3 sum = path_pixel_sum(scene, i, j, spp, counts, [&](double u, double v, PrimaryRay& pr, Vec3& escape) {
    if (const auto p = primary_ray(camera, scene.bounds(), scene.epsilon(), i, j, u, v)) {
      pr = *p;
      return true;
    }
    const Vec3 d = camera.line(i, j, u, v).dir;
    escape = ortho ? -d : d;
    return false;
  }, first);
  if (primary) *primary = first.found ? make_primary(first.primary, first.hit) : PrimaryHit{};
  if (surface && first.found) *surface = first.surface;
  return sum * (1.0 / spp);
}

}  // namespace

Vec3 render_pixel(const RenderContext& scene, const LensArray& camera, int i, int j, int spp, RayCounts& counts,
                  PrimaryHit* primary, SurfacePoint* surface) {
  if (scene.settings().integrator == Integrator::path) return path_pixel(scene, camera, i, j, spp, counts, primary, surface);
  Vec3 sum;
  if (primary) *primary = PrimaryHit{};
  for (int k = 0; k < spp; ++k) {
    double u, v;
    sample_offset(i, j, k, u, v);
    Vec3 c = scene.background();
    const auto pr = primary_ray(camera, scene.bounds(), scene.epsilon(), i, j, u, v);
    Hit hit;
    if (pr) {
      ++counts.eye;
      if (scene.accel().intersect(pr->ray, hit, RayCoherence::coherent)) {
        const SurfacePoint sp = scene.surface(pr->ray, hit);
        c = shade(scene, pr->ray, sp, 1, counts);
        if (k == 0) {
          if (surface) *surface = sp;
          if (primary) *primary = make_primary(*pr, hit);
        }
      }
    }
    sum += c;
  }
  return sum * (1.0 / spp);
}

void trace_eye_packet(const RenderContext& scene, const LensArray& camera, const PixelXY px[], int n, int k,
                      RayCounts& counts, EyePacket& out) {
  bool ok[kPacketSize];
  primary_rays(camera, scene.bounds(), scene.epsilon(), px, n, k, out.primary, ok);
  intersect_eye_packet(scene, ok, n, counts, out);
}

void intersect_eye_packet(const RenderContext& scene, const bool ok[], int n, RayCounts& counts, EyePacket& out) {
  // Only the flags need resetting: a lane's ray is read where it is active.
  std::fill(out.rays.active, out.rays.active + kPacketSize, false);
  std::fill(out.found, out.found + kPacketSize, false);
  for (int l = 0; l < n; ++l) {
    if (!ok[l]) continue;
    out.rays.active[l] = true;
    out.rays.rays[l] = out.primary[l].ray;
    ++counts.eye;
  }
  // Lenses that look past the scene leave whole packets empty: skip them.
  if (std::none_of(out.rays.active, out.rays.active + n, [](bool a) { return a; })) return;
  scene.accel().intersect(out.rays, out.hits, out.found, RayCoherence::coherent);
  for (int l = 0; l < n; ++l)
    if (out.found[l]) out.surface[l] = scene.surface(out.rays.rays[l], out.hits[l]);
}

void render_packet(const RenderContext& scene, const LensArray& camera, const PixelXY px[], int n, int spp,
                   PacketScratch& scratch, RayCounts& counts, Vec3 colours[], PrimaryHit primary[],
                   SurfacePoint surface[], ShadeParts parts[]) {
  if (parts && spp != 1) throw std::invalid_argument(fmt::format("shading records need spp = 1, got {}", spp));
  if (parts) std::fill(parts, parts + n, ShadeParts{});
  Vec3 sum[kPacketSize];
  EyePacket& eye = scratch.eye;
  for (int k = 0; k < spp; ++k) {
    trace_eye_packet(scene, camera, px, n, k, counts, eye);
    Vec3 c[kPacketSize];
    for (int l = 0; l < kPacketSize; ++l) c[l] = scene.background();
    // shade() sets the parts it is given; the scratch's, so that packets
    // without parts do not zero 256 bytes each.
    ShadeParts* lane_parts = scratch.lane_parts;
    if (std::any_of(eye.found, eye.found + n, [](bool f) { return f; }))
      shade(scene, eye.rays, eye.found, eye.surface, 1, counts, c, parts ? lane_parts : nullptr);
    if (parts)
      for (int l = 0; l < n; ++l)
        if (eye.found[l]) parts[l] = lane_parts[l];
    for (int l = 0; l < n; ++l) {
      sum[l] += c[l];
      if (k != 0) continue;
      if (primary) primary[l] = eye.found[l] ? make_primary(eye.primary[l], eye.hits[l]) : PrimaryHit{};
      if (surface && eye.found[l]) surface[l] = eye.surface[l];
    }
  }
  for (int l = 0; l < n; ++l) colours[l] = sum[l] * (1.0 / spp);
}

FrameBuffers render_frame(const RenderContext& scene, const LensArray& camera, const RenderOptions& opt,
                          RenderStats& stats, uint64_t memory_limit_bytes) {
  if (opt.spp < 1) throw std::invalid_argument(fmt::format("samples per pixel must be at least 1, got {}", opt.spp));
  if (opt.threads < 0) throw std::invalid_argument(fmt::format("threads must be 0 (all) or more, got {}", opt.threads));
  const int W = camera.width();
  const int y0 = opt.rows ? (*opt.rows)[0] : 0, y1 = opt.rows ? (*opt.rows)[1] : camera.height();
  if (y0 < 0 || y1 > camera.height() || y0 >= y1)
    throw std::invalid_argument(fmt::format("rows {} to {} are not a band of the {} rows of the EIA", y0, y1, camera.height()));
  const int H = y1 - y0;
  const int64_t pixels = static_cast<int64_t>(W) * H;
  const uint64_t need = frame_bytes(pixels, opt.aovs) + (opt.primary_hits ? pixels * sizeof(PrimaryHit) : 0);
  if (memory_limit_bytes && need > memory_limit_bytes)
    throw std::length_error(fmt::format("a {}x{} image needs {:.1f} MiB of buffers, over the limit of {:.1f} MiB",
                                        W, H, need / 1048576.0, memory_limit_bytes / 1048576.0));

  FrameBuffers fb = allocate_frame(W, H, opt.aovs);
  if (opt.primary_hits) fb.primary.resize(static_cast<size_t>(pixels));
  const bool want_surface = opt.aovs.albedo || opt.aovs.depth || opt.aovs.normal || opt.aovs.id;

  const auto start = std::chrono::steady_clock::now();
  // The path integrator traces single rays (its bounces scatter packets at
  // once), elemental image by elemental image.
  const TraceStyle style = scene.settings().integrator == Integrator::path ? TraceStyle::horizontal : opt.style;
  // Sub-aperture packets take one pixel of each of 4x4 lenses: tiles of at
  // least 4x4 lenses keep them full.
  const bool subaperture = style == TraceStyle::subaperture;
  const ElementalTiles tiles(camera, opt.tile_order, y0, y1, subaperture ? kSubapertureLenses : 1);
  std::vector<RayCounts> tile_counts(static_cast<size_t>(tiles.count()));
  std::atomic<int> tiles_done{0};
  const int P = camera.desc().pixels_per_lens;
  for_each_tile(tiles, opt.threads, [&](int tile) {
    RayCounts counts;
    auto store = [&](int i, int j, const Vec3& c, const PrimaryHit& ph, const SurfacePoint& sp) {
      if (opt.primary_hits) fb.primary[static_cast<size_t>(j - y0) * W + i] = ph;
      // Normals face the viewer: along +d orthoscopic (it looks back down
      // the line), along -d pseudoscopic (it sits at the lens).
      Vec3 toward;
      if (opt.aovs.normal && ph.status == PrimaryHit::kHit) {
        const Vec3 d = camera.line(i, j).dir;
        toward = camera.desc().mode == RecordingMode::orthoscopic ? d : -d;
      }
      store_pixel(fb, opt.aovs, i, j - y0, c, ph.status == PrimaryHit::kHit ? &sp : nullptr, ph.t, toward);
    };
    const TileRect r = tiles.rect(tile);
    // Packets of either kind come from the whole tile (for_each_packet_of);
    // the single-ray styles go elemental image by elemental image: tiles are
    // P-aligned, so each P x P block is one elemental image (square grid), a
    // piece of one lenticule's strip, or close to one hex lens.
    const bool packets = style == TraceStyle::packet || subaperture;
    if (packets)
      render_block(scene, camera, r, style, opt.spp, want_surface, counts, store);
    else
      for (int by = r.y0; by < r.y1; by += P)
        for (int bx = r.x0; bx < r.x1; bx += P) {
          const TileRect b{bx, by, std::min(bx + P, r.x1), std::min(by + P, r.y1)};
          render_block(scene, camera, b, style, opt.spp, want_surface, counts, store);
        }
    tile_counts[static_cast<size_t>(tile)] = counts;
    const int done = ++tiles_done;
    if (opt.progress) opt.progress(static_cast<double>(done) / tiles.count());
  });
  stats.trace_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  stats.rays = {};
  for (const RayCounts& c : tile_counts) stats.rays += c;
  return fb;
}

}  // namespace holoray
