// holoray/reuse: the shadow cache (issue 12). Whether a point light is
// visible from a surface point does not depend on the view: every lens that
// sees the point (tens in an EIA) and every frame in which nothing moves asks
// the same question. The cache answers it per surface cell (surface_cells.hpp)
// and per light, after Fernandez, Bala and Greenberg's local illumination
// environments (EGWR 2002) and Ward's last-occluder cache (Radiance):
//
//   lit       every sample point of the cell sees the light;
//   shadowed  one sphere or triangle blocks the light from every sample
//             point: it is convex, so it blocks every point of the cell's
//             convex hull (the segments to the light from the hull's points
//             are convex combinations of the corners' segments);
//   partial   anything else (a shadow edge, several occluders, an open cone,
//             the light grazing the cell): the pixel traces its shadow ray,
//             testing the first occluder the samples found before the BVH.
//
// What the shading keeps per pixel: N.L, highlights, mirror and refracted
// rays, and whether a shadow ray is cast at all (nff-notes §10.10) are computed
// per pixel as without the cache; only the visibility is reused, and only
// where the pixel's side of the surface faces the light (else the ray starts
// on the side away from it and is traced as before).
//
// Where it can differ from tracing: "lit" rests on the samples (corners and
// centre); an occluder whose shadow falls wholly between them is missed. The
// cells are about a lens pitch across (the finest detail the display shows at
// the array), so such a shadow is smaller than a lens. On curved patches
// (spheres, cones) the cell bulges past its corners' hull by the sagitta.
//
// Validity rules:
// - Deterministic: a cell's value comes only from its fixed sample points, so
//   the image is the same for any thread count and tile order; two threads
//   that classify one cell at once write the same value.
// - Across frames: kept while no object transform changes (lights never move
//   in holoray's scenes); RenderScene::set_transforms calls sync(), which
//   clears every cell when any transform changed. Never a stale shadow.
// - Memory: at most ShadowCacheOptions::memory_limit_bytes; primitives that
//   do not fit get no cells and trace their shadow rays (never coarser
//   cells, which would miss smaller shadows).
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

#include "render/ray_counts.hpp"
#include "reuse/surface_cells.hpp"

namespace holoray {

class RenderScene;
struct SurfacePoint;

struct ShadowCacheOptions {
  /// Cell size, object units; > 0. The CLI passes the lens pitch.
  double cell_size = 1;
  /// Bound on the cache's storage (4 bytes per cell per light).
  uint64_t memory_limit_bytes = uint64_t{512} << 20;
};

/// What the cache knows of one light from one cell.
enum class LightVisibility : uint8_t { unknown = 0, lit = 1, shadowed = 2, partial = 3 };

/// A partial cell's hint: the first occluder its samples met.
struct OccluderHint {
  bool valid = false;
  uint32_t group = 0;
  PrimKind kind = PrimKind::triangle;
  uint32_t prim = 0;
};

class ShadowCache {
 public:
  /// Cells over every primitive of `scene` (at its current transforms) for
  /// each of its lights. Throws std::invalid_argument for a bad cell size.
  ShadowCache(const RenderScene& scene, const ShadowCacheOptions& options);

  /// The cell of a surface point (once per hit, for all lights).
  CellRef locate(const SurfacePoint& sp) const;
  /// The visibility of `light` (index into RenderScene::lights()) over the
  /// cell of `sp`, classifying the cell on first use (its sample rays are
  /// counted in counts.cache_samples). `unknown` when the cell has no
  /// storage. For partial cells `hint` gets the first occluder found.
  LightVisibility visibility(const SurfacePoint& sp, const CellRef& cell, int light, RayCounts& counts,
                             OccluderHint& hint) const;

  /// Clears every cell when any object transform differs from the ones the
  /// cells were classified under; returns whether it did. Not thread-safe
  /// against rendering (called between frames).
  bool sync();

  /// Bytes held (cells x lights x 4 + the cell table).
  uint64_t bytes() const;
  const SurfaceCells& cells() const { return cells_; }
  /// Times sync() cleared the cells.
  uint64_t clears() const { return clears_; }

 private:
  uint32_t classify(const SurfacePoint& sp, const CellRef& cell, int light, RayCounts& counts) const;
  uint32_t encode(uint32_t group, PrimKind kind, uint32_t prim) const;
  OccluderHint decode(uint32_t id) const;

  const RenderScene& scene_;
  SurfaceCells cells_;
  size_t lights_;
  std::unique_ptr<std::atomic<uint32_t>[]> words_;  // [slot * lights + light]: state << 30 | occluder id + 1
  std::vector<std::array<uint32_t, 3>> prim_base_;   // per group: first global id of each kind
  std::vector<uint64_t> snapshot_;                    // transforms the cells hold, as bits
  uint64_t clears_ = 0;
};

}  // namespace holoray
