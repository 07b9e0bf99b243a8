// holoray/camera: the integral camera, implemented once, exactly as
// shared/docs/camera-model.md (the contract). Every renderer path and test
// calls this; nothing else knows the grid geometry.
//
// Frames: "local" is the array frame of the contract (origin at the array
// centre, z the array normal toward the viewer, panel at z = -gap); "world" is
// the scene's frame. Pixel (i, j): column i from the left, row j from the top.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "camera/camera.hpp"
#include "camera/pixel_lines.h"
#include "math/vec.hpp"

namespace holoray {

/// Lens layout (contract: "Square grid", "Hexagonal grid", "Lenticular sheet").
enum class Grid { square, hex, lenticular };

/// Which surface a pixel records along its line (contract: "Recording modes").
enum class RecordingMode {
  orthoscopic,  ///< the hit with the largest t over the whole line (display-ready)
  pseudoscopic  ///< the hit with the smallest t > 0 (direct pickup)
};

const char* to_string(Grid g);
const char* to_string(RecordingMode m);

/// Everything that fixes the camera, in scene units. Validated by LensArray.
struct LensArrayDesc {
  Grid grid = Grid::square;
  RecordingMode mode = RecordingMode::orthoscopic;
  int lenses_x = 64;         ///< Nx
  int lenses_y = 64;         ///< Ny (ignored by the lenticular sheet)
  int pixels_per_lens = 8;   ///< P, pixels across one lens
  int rows = 0;              ///< H for hex and lenticular; 0 = the contract's default
  double pitch = 1;          ///< lens pitch (scene units)
  double gap = 1;            ///< lens plane to pixel panel (scene units)
  double view_distance = INFINITY;  ///< lenticular vertical perspective distance V
  Frame frame;               ///< array placement in the world
  /// Equal descriptions give every pixel the same line, bit for bit.
  friend bool operator==(const LensArrayDesc&, const LensArrayDesc&) = default;
};

/// Up to kLaneCount pixel lines (world), one array per coordinate: what a
/// packet's eye rays are generated and clipped from (LensArray::lines).
struct PixelLineLanes {
  static constexpr int kLaneCount = 16;
  alignas(16) double ox[kLaneCount], oy[kLaneCount], oz[kLaneCount];
  alignas(16) double dx[kLaneCount], dy[kLaneCount], dz[kLaneCount];
};

/// Lens index: column lx from the left, row ly from the top.
struct LensIndex {
  int x = 0, y = 0;
  friend bool operator==(const LensIndex&, const LensIndex&) = default;
};


/// An integral camera. Immutable after construction; safe to share between threads.
/// The angle (radians) one pixel of an elemental image subtends through its
/// lens: pixel size / gap. What a mesh texture's MIP level is chosen by
/// (RenderSettings::footprint).
inline double pixel_angle(const LensArrayDesc& d) { return d.pitch / d.pixels_per_lens / d.gap; }

class LensArray {
 public:
  /// Validates and precomputes. Throws std::invalid_argument naming the bad
  /// value: pitch or gap <= 0 or not finite, zero or negative lens or pixel
  /// counts, rows < 1, view distance <= 0, image dimensions over 2^30.
  explicit LensArray(const LensArrayDesc& desc);

  const LensArrayDesc& desc() const { return desc_; }
  int width() const { return width_; }    ///< W, pixels
  int height() const { return height_; }  ///< H, pixels
  int64_t pixel_count() const { return static_cast<int64_t>(width_) * height_; }
  double pixel_pitch() const { return s_; }  ///< s = pitch / P (scene units)
  /// Full field of view of one lens, 2*atan(pitch / (2g)), in degrees.
  double lens_fov_deg() const;
  int lens_count_x() const { return desc_.lenses_x; }
  int lens_count_y() const { return desc_.grid == Grid::lenticular ? 1 : desc_.lenses_y; }

  /// The lens a pixel belongs to (hex: nearest centre, ties to lower ly then lx):
  /// camera_lines::hr_lens_of_pixel. Square and lenticular grids are a
  /// division, inlined because the reprojection asks once per neighbour of
  /// every pixel; the hex case stays out of line (the shared function
  /// inlined whole made this too large to inline: 2 % of a reprojected
  /// shot's time went to the call).
  LensIndex lens_of_pixel(int i, int j) const {
    const int P = desc_.pixels_per_lens;
    if (desc_.grid == Grid::square) return {i / P, j / P};
    if (desc_.grid == Grid::lenticular) return {i / P, 0};
    return hex_lens_of_pixel(i, j);
  }
  /// lens_of_pixel(i, j) == lens, without its divisions on square and
  /// lenticular grids (the reverse reprojection asks for every reused hit).
  bool pixel_in_lens(int i, int j, LensIndex lens) const {
    const int P = desc_.pixels_per_lens;
    if (desc_.grid == Grid::square)
      return static_cast<unsigned>(i - lens.x * P) < static_cast<unsigned>(P) &&
             static_cast<unsigned>(j - lens.y * P) < static_cast<unsigned>(P);
    if (desc_.grid == Grid::lenticular) return static_cast<unsigned>(i - lens.x * P) < static_cast<unsigned>(P);
    return hex_lens_of_pixel(i, j) == lens;
  }
  /// Lens centre c in the array frame (z = 0). Lenticular: (c_x, 0, 0).
  /// Inline: every reprojection lookup asks for one or two.
  Vec3 lens_centre_local(LensIndex l) const { return camera_lines::hr_lens_centre(grid_, l.x, l.y); }
  /// Panel point p of pixel (i, j) at offset (u, v) in the pixel, array frame (z = -gap).
  Vec3 panel_point_local(int i, int j, double u = 0.5, double v = 0.5) const {
    return camera_lines::hr_panel_point(grid_, i, j, u, v);
  }

  /// The pixel's line in the array frame; (u, v) jitters p inside the pixel
  /// (contract: "Sampling") and keeps the lens centre fixed.
  PixelLine line_local(int i, int j, double u = 0.5, double v = 0.5) const;
  /// The pixel's line in the world frame.
  PixelLine line(int i, int j, double u = 0.5, double v = 0.5) const;
  /// line() for n <= PixelLineLanes::kLaneCount pixels (i[k], j[k]) at
  /// offsets (u[k], v[k]), one array per coordinate (world): lane k equals
  /// line(i[k], j[k], u[k], v[k]) bit for bit. A lens's centre is computed
  /// once for a run of pixels under the same lens (a packet of one elemental
  /// image, issue 4), and the directions two lanes per SSE2 instruction in
  /// line()'s operations and order (x86-64's baseline has no fused
  /// multiply-add to change a bit). Throws std::invalid_argument for more lanes.
  void lines(const int i[], const int j[], const double u[], const double v[], int n, PixelLineLanes& out) const;

  /// Forward projection (contract, property 2): every pixel whose line passes
  /// through the world point, one per lens whose elemental image contains it,
  /// appended to `out` (cleared first). Pseudoscopic keeps only t > 0. The
  /// exact inverse of line(): line(h.i, h.j, h.u, h.v) passes through the
  /// point at parameter h.t. Points on the lens plane (z = 0) project nowhere.
  void project(const Vec3& p_world, std::vector<PanelHit>& out) const;

  /// Forward projection through one lens (array-frame point): true and `out`
  /// when the point's line through that lens centre lands in the lens's own
  /// elemental image (pseudoscopic: with t > 0). `landing_lens` (optional)
  /// gets the lens whose elemental image the landing pixel belongs to
  /// (clamped to the image), so a caller can try that lens next.
  bool project_through(const Vec3& x_local, LensIndex lens, PanelHit& out, LensIndex* landing_lens = nullptr) const;
  /// The lens whose elemental image holds the panel pixel under an
  /// array-frame point (z ignored; clamped to the array).
  LensIndex lens_near(const Vec3& p_local) const;
  /// The pixel that records array-frame point `x_local` seen along direction
  /// `d_local` (array frame, any length, d.z != 0): project_through the lens
  /// near where the line through the point along d crosses the array, else
  /// through the lens its projection landed in. There the point lands at the
  /// same place in the elemental image as where a pixel looking along d saw
  /// it (the reprojections' lookup, once per hit). `lens` (optional) gets
  /// the lens it was recorded through. False where neither lens records it.
  bool project_along(const Vec3& x_local, const Vec3& d_local, PanelHit& out, LensIndex* lens = nullptr) const;
  /// Row-major lens number, lx + ly * lens_count_x().
  int lens_number(LensIndex l) const { return l.x + l.y * lens_count_x(); }

  /// The constants its lines are computed from (camera/line_constants.h),
  /// which the GPU's kernel reads too (gpu/shaders/layout.h, GpuFrame).
  const camera_lines::HrLensGrid& line_constants() const { return grid_; }

 private:
  LensIndex hex_lens_of_pixel(int i, int j) const;
  void project_local(const Vec3& x, std::vector<PanelHit>& out) const;

  LensArrayDesc desc_;
  int width_ = 0, height_ = 0;
  double s_ = 0;           // pixel pitch
  double inv_s_ = 0;       // 1 / s_: the reprojection's lookups divide by s_ once per hit
  double half_w_ = 0, half_h_ = 0;  // W*s/2, H*s/2
  double row_step_ = 0;    // hex: pitch*sqrt(3)/2
  double reach_x_ = 0, reach_y_ = 0;  // max |p - c| per axis over the panel (scene units)
  camera_lines::HrLensGrid grid_{};  // the grid as the shared line functions take it (camera/pixel_lines.h)
};
static_assert(PixelCamera<LensArray>);

}  // namespace holoray
