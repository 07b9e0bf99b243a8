// holoray/render: renders one elemental image array (EIA) through the
// integral camera. oneTBB over tiles aligned to elemental images; every pixel
// is computed independently, so the output is identical for any thread count.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "camera/lens_array.hpp"
#include "image/image.hpp"
#include "render/ray_counts.hpp"
#include "render/render_context.hpp"
#include "render/shading.hpp"
#include "render/tiles.hpp"

namespace holoray {

/// Arbitrary output variables besides the colour.
struct AovSet {
  bool albedo = false;  ///< flat surface colour C, unlit (3 channels)
  bool depth = false;   ///< the contract's signed line parameter t; NaN for background (1 channel)
  bool normal = false;  ///< unit shading normal, world frame, facing the viewer; 0 for background (3)
  bool id = false;      ///< object index in file order; -1 for background (1)
};

/// How the pixels of one elemental image are traced (issue 4, paper §6).
/// What each pixel sees never depends on it, nor do the AOVs; the packet
/// styles shade NFF's and glTF's direct light in float (light_batch.hpp,
/// gltf_batch.hpp), the single-ray ones in double: colours within the image
/// budget, 60 dB (RenderStyles tests).
enum class TraceStyle {
  packet,       ///< 16-ray packets of 4x4 pixels of one lens (rtcIntersect16, coherent); shadow rays as packets
  subaperture,  ///< 16-ray packets of one pixel (u, v) of 4x4 neighbouring lenses: parallel rays (square grid) from a
                ///< patch of the lens plane, whose hits and shadow rays stay together (a sub-aperture view's pixels)
  horizontal,  ///< single rays, row by row inside each elemental image (paper §6.1)
  vertical,    ///< single rays, column by column inside each elemental image (paper §6.2)
};

/// "packet", "subaperture", "horizontal" or "vertical".
const char* to_string(TraceStyle style);

/// The faster packet style for an array. A packet of 4x4 pixels of one lens
/// spreads by 4 pixel angles (pitch / (gap P) each), one of 4x4 lenses by
/// 4 pitches: at a depth D the sub-aperture packet is the tighter when
/// D > gap P. Measured on the four SPD scenes (bench/results.md), it pays
/// once the array is wider than 4 gap P (about: scene content lies a
/// quarter of the array's width from it): sub-aperture then, else packet.
TraceStyle preferred_style(const LensArrayDesc& desc);

struct RenderOptions {
  int spp = 1;      ///< samples per pixel; sample 0 is the pixel centre (the reference)
  int threads = 0;  ///< 0: all cores
  AovSet aovs;
  bool primary_hits = false;  ///< fill FrameBuffers::primary (temporal reprojection keyframes)
  TileOrder tile_order = TileOrder::row_major;  ///< never changes the result (tests prove it)
  TraceStyle style = TraceStyle::packet;        ///< preferred_style(desc) is the faster of the packet styles
  /// Render only pixel rows [rows[0], rows[1]) of the image, a band (`mpirun
  /// holoray render` gives each rank bands of rows; every renderer takes
  /// it): the buffers hold just those rows, row 0 being image row rows[0].
  /// Pixels are computed as in the whole image, bit for bit. Empty: every row.
  std::optional<std::array<int, 2>> rows;
  /// A quilt's views under the path integrator: each takes the samples of
  /// this many views on each side (render/view_sharing.hpp); 0: none.
  int share_views = 0;
  /// Called from worker threads with the fraction done; must be thread-safe.
  std::function<void(double)> progress;
};

/// What a pixel's centre ray met: a point image record less its colour
/// (paper §4; temporal/ keeps these for keyframes). 24 bytes.
struct PrimaryHit {
  static constexpr int8_t kHit = 1, kBackground = 0;
  float p_object[3] = {0, 0, 0};  ///< hit point in its scene file's object space
  float t = 0;                    ///< the contract's line parameter of the hit
  uint32_t prim = 0;              ///< primitive within its group and kind
  uint16_t group = 0;             ///< scene file (RenderScene part)
  uint8_t kind = 0;               ///< PrimKind
  int8_t status = kBackground;
};

/// One rendered EIA: colour (linear RGB) and the requested AOVs (others
/// empty), plus the primary hits when asked for. AOVs come from the
/// pixel-centre sample.
struct FrameBuffers {
  ImageBuffer colour, albedo, depth, normal, id;
  std::vector<PrimaryHit> primary;  ///< row-major, W*H; empty unless RenderOptions::primary_hits
};

/// What a render did, from either executor (the CPU path's functions here,
/// gpu::GpuRenderer): the rays by kind and the seconds spent tracing; on the
/// GPU also the readback, and with its count_work the BVH nodes visited and
/// primitives tested over all rays (0 otherwise, and on the CPU).
struct RenderStats {
  RayCounts rays;
  double trace_seconds = 0;
  double readback_seconds = 0;
  uint64_t nodes_visited = 0, primitives_tested = 0;
  /// With count_work, the GPU path integrator's wavefront traversals, whose
  /// lanes fetch their rays: the node steps their lanes took, busy or
  /// waiting; nodes_visited over it is their lanes' use (1: none waits).
  uint64_t lane_steps = 0;
};

/// Renders one pixel: the colour averaged over `spp` samples (sample 0 at
/// the centre); `primary` (optional) gets sample 0's hit and `surface`
/// (optional) its surface point, valid when primary->status is kHit. `margin`
/// and `bounds` as for primary_ray (the scene's epsilon and bounds).
Vec3 render_pixel(const RenderContext& scene, const LensArray& camera, int i, int j, int spp, RayCounts& counts,
                  PrimaryHit* primary = nullptr, SurfacePoint* surface = nullptr);

/// render_pixel() for up to kPacketSize pixels px[k] (k < n), any pixels
/// (4x4 of one lens, or one of each of 4x4 lenses), traced as packets:
/// colours[k], and primary[k] /
/// surface[k] when given. The same primary hits and surfaces as
/// render_pixel() per pixel whenever Embree's packet and single-ray kernels
/// agree, and colours within the image budget (shade(RayPacket)). With `parts` (spp must be
/// 1), parts[k] gets what the rays of lane k's shading found (ShadeParts;
/// zero for background lanes): the keyframes of reverse reprojection.
/// `scratch` holds the packet's rays, hits and shading records: one per
/// thread's run of packets (a block, a task), made once (6 KB, every
/// member initialised), never shared between threads.
struct PacketScratch;
void render_packet(const RenderContext& scene, const LensArray& camera, const PixelXY px[], int n, int spp,
                   PacketScratch& scratch, RayCounts& counts, Vec3 colours[], PrimaryHit primary[] = nullptr,
                   SurfacePoint surface[] = nullptr, ShadeParts parts[] = nullptr);

/// Bytes the buffers of a frame of `pixels` take (colour plus requested
/// AOVs), computed without allocating; lets callers refuse absurd sizes up front.
uint64_t frame_bytes(int64_t pixels, const AovSet& aovs);
/// The colour buffer and the requested AOVs of a width x height frame, at
/// their background values (black, depth NaN, normal 0, id -1).
FrameBuffers allocate_frame(int width, int height, const AovSet& aovs);
/// Writes one pixel's colour and, where `surface` is given (the pixel's
/// first sample hit it), its AOVs: albedo, depth `t` (the camera's line
/// parameter), the shading normal turned toward `toward_viewer` (world
/// frame; needed only for the normal AOV) and the object id. Shared by every
/// camera's renderer so the AOVs mean the same for all.
void store_pixel(FrameBuffers& fb, const AovSet& aovs, int i, int j, const Vec3& colour, const SurfacePoint* surface,
                 double t, const Vec3& toward_viewer);
/// Pixel offset (u, v) of sample k: 0.5 (the centre) for k = 0, else a
/// per-pixel hashed rotation of a 2D Kronecker sequence (deterministic).
void sample_offset(int i, int j, int k, double& u, double& v);

/// Renders the EIA. Throws std::invalid_argument when spp < 1 or threads < 0,
/// std::length_error when the buffers would exceed `memory_limit_bytes`
/// (0: no limit), naming both numbers.
FrameBuffers render_frame(const RenderContext& scene, const LensArray& camera, const RenderOptions& options,
                          RenderStats& stats, uint64_t memory_limit_bytes = 0);

/// The primary ray of one pixel sample, and how to turn its hit distance back
/// into the contract's line parameter t. Orthoscopic rays start beyond the
/// scene on the +z side and travel along -d, so the first hit is the largest t;
/// pseudoscopic rays start at the lens and keep t > 0.
struct PrimaryRay {
  Ray ray;            ///< world; dir unit
  double t_offset;    ///< line t = t_offset + t_sign * ray t
  double t_sign;
};
/// nullopt when the pixel's line cannot meet the scene (records background).
std::optional<PrimaryRay> primary_ray(const LensArray& camera, const Bounds3& bounds, double margin, int i, int j,
                                      double u = 0.5, double v = 0.5);
/// The same for any line with its recording mode (the display camera's).
std::optional<PrimaryRay> primary_ray_along(const PixelLine& line, const Bounds3& bounds, double margin,
                                            RecordingMode mode);
/// primary_ray() for pixels px[0..n), n <= kPacketSize, at sample k
/// (sample_offset): ok[l] false where it would give nullopt, else out[l],
/// bit for bit the same. The packet path: consecutive pixels of one lens
/// share its centre (LensArray::lines). Throws std::invalid_argument for n > kPacketSize.
void primary_rays(const LensArray& camera, const Bounds3& bounds, double margin, const PixelXY px[], int n, int k,
                  PrimaryRay out[], bool ok[]);

/// The eye rays of up to kPacketSize pixels px[l] (l < n) at sample k, traced as one packet: the first half of render_packet, for
/// callers that schedule the shading themselves (reverse reprojection
/// gathers the lanes left to shade from several packets into full ones,
/// because a packet's shadow rays cost about as much with 3 lanes as with 16).
struct EyePacket {
  RayPacket rays;                       ///< world; active where the line meets the scene box
  PrimaryRay primary[kPacketSize];      ///< valid where rays.active
  Hit hits[kPacketSize];                ///< valid where found
  SurfacePoint surface[kPacketSize];    ///< valid where found
  bool found[kPacketSize] = {};
};
void trace_eye_packet(const RenderContext& scene, const LensArray& camera, const PixelXY px[], int n, int k,
                      RayCounts& counts, EyePacket& out);
/// The same for rays the caller made: out.primary[l] for the lanes l < n
/// with ok[l] (any camera); the others stay inactive.
void intersect_eye_packet(const RenderContext& scene, const bool ok[], int n, RayCounts& counts, EyePacket& out);

struct PacketScratch {
  EyePacket eye;
  ShadeParts lane_parts[kPacketSize];
};

/// Renders the pixels of `block` (single-ray styles: at most P x P, one
/// elemental image, or a P x P piece of a lenticule's strip or hex lens; the
/// packet styles: any P-aligned block, for sub-aperture packets ideally 4 or
/// more lenses across) in `style`, calling
/// store(i, j, colour, primary, surface) once per pixel; `surface` is filled
/// only when want_surface and primary.status is kHit. The one place where the
/// styles differ (paper §6), shared by render_frame and the benchmarks.
template <class Store>
void render_block(const RenderContext& scene, const LensArray& camera, const TileRect& block, TraceStyle style,
                  int spp, bool want_surface, RayCounts& counts, Store&& store) {
  auto single = [&](int i, int j) {
    PrimaryHit ph;
    SurfacePoint sp;
    const Vec3 c = render_pixel(scene, camera, i, j, spp, counts, &ph, want_surface ? &sp : nullptr);
    store(i, j, c, ph, sp);
  };
  switch (style) {
    case TraceStyle::horizontal:
      for (int j = block.y0; j < block.y1; ++j)
        for (int i = block.x0; i < block.x1; ++i) single(i, j);
      return;
    case TraceStyle::vertical:
      for (int i = block.x0; i < block.x1; ++i)
        for (int j = block.y0; j < block.y1; ++j) single(i, j);
      return;
    case TraceStyle::packet:
    case TraceStyle::subaperture: {
      // Once per block, not per packet: the arrays' members have initialisers.
      Vec3 c[kPacketSize];
      PrimaryHit ph[kPacketSize];
      SurfacePoint sp[kPacketSize];
      PacketScratch scratch;
      for_each_packet_of(block, camera.desc().pixels_per_lens, style == TraceStyle::subaperture,
                         [&](const PixelXY* px, int m) {
                           render_packet(scene, camera, px, m, spp, scratch, counts, c, ph, want_surface ? sp : nullptr);
                           for (int l = 0; l < m; ++l) store(px[l].i, px[l].j, c[l], ph[l], sp[l]);
                         });
      return;
    }
  }
}

}  // namespace holoray
