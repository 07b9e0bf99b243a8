// holoray/render: the shadow cache (issue 12). Whether a point light is
// visible from a surface point does not depend on the view: every lens that
// sees the point (tens in an EIA) and every frame in which nothing moves asks
// the same question. The cache answers it per surface cell (surface_cells.hpp)
// and per light, after Fernandez, Bala and Greenberg's local illumination
// environments (EGWR 2002) and Ward's last-occluder cache (Radiance):
//
//   lit       every sample of the cell (corners and centre) sees the light;
//   shadowed  one sphere or triangle blocks the light from every sample: it
//             is convex, so it blocks every point of the corners' convex
//             hull (the segments to the light from the hull's points are
//             convex combinations of the corners' segments);
//   partial   anything else (a shadow edge, several occluders, an open cone,
//             the light grazing the cell): the pixel traces its shadow ray.
//
// A cell's corners are vertices of its primitive's cell grid, shared with
// its neighbours (surface_cells.hpp): each vertex's shadow ray is traced
// once per light, however many cells meet there, so classifying a cell
// costs about two rays (its centre, and a triangle's grid has half a vertex
// per cell, a patch grid one), not five.
//
// What the shading keeps per pixel: N.L, highlights, mirror and refracted
// rays, and whether a shadow ray is cast at all (nff-notes §10.10) are computed
// per pixel as without the cache; only the visibility is reused, and only
// where the pixel's side of the surface faces the light (else the ray starts
// on the side away from it and is traced as before).
//
// Where it can differ from tracing: "lit" rests on the samples; an occluder whose shadow falls wholly between them is missed. The
// cells are about a lens pitch across (the finest detail the display shows at
// the array), so such a shadow is smaller than a lens. On curved patches
// (spheres, cones) the cell bulges past its corners' hull by the sagitta.
//
// Validity rules:
// - Deterministic: a cell's value comes only from its fixed corners, so the
//   image is the same for any thread count and tile order; two threads that
//   classify one cell or one vertex at once write the same value.
// - Across frames: kept while no object transform changes (lights never move
//   in holoray's scenes); RenderScene::set_transforms calls sync(), which
//   clears every cell when any transform changed. Never a stale shadow.
// - Memory: at most ShadowCacheOptions::memory_limit_bytes of address
//   space, zero pages until a cell or vertex is first written (only what the
//   views reach costs memory); primitives that do not fit get no cells and
//   trace their shadow rays (never coarser cells, which would miss smaller
//   shadows).
#pragma once

#include <array>
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
  /// Bound on the cache's storage (4 bytes per cell, 4 per corner vertex
  /// and light).
  uint64_t memory_limit_bytes = uint64_t{512} << 20;
};

/// What the cache knows of one light from one cell.
enum class LightVisibility : uint8_t { unknown = 0, lit = 1, shadowed = 2, partial = 3 };

class ShadowCache {
 public:
  /// Lights past this many (in RenderScene::lights() order) are not cached:
  /// their shadow rays are traced.
  static constexpr int kMaxCachedLights = 16;

  /// Cells over every primitive of `scene` (at its current transforms) for
  /// each of its lights. Throws std::invalid_argument for a bad cell size.
  ShadowCache(const RenderScene& scene, const ShadowCacheOptions& options);

  /// The cell of a surface point (once per hit, for all lights).
  CellRef locate(const SurfacePoint& sp) const;
  /// The visibility of `light` (index into RenderScene::lights()) over the
  /// cell of `sp`, classifying the cell on first use (the shadow rays of its
  /// corners not yet known are counted in counts.cache_samples). `unknown`
  /// when the cell has no storage or the light is past kMaxCachedLights.
  LightVisibility visibility(const SurfacePoint& sp, const CellRef& cell, int light, RayCounts& counts) const;

  /// Clears every cell when any object transform differs from the ones the
  /// cells were classified under; returns whether it did. Not thread-safe
  /// against rendering (called between frames).
  bool sync();

  /// Bytes reserved ((cells + vertices) x lights x 4 + the cell table).
  uint64_t bytes() const;
  const SurfaceCells& cells() const { return cells_; }
  /// Times sync() cleared the cells.
  uint64_t clears() const { return clears_; }

 private:
  LightVisibility classify(const SurfacePoint& sp, const CellRef& cell, int light, RayCounts& counts) const;
  uint32_t vertex_state(const CellCorner& corner, uint32_t group, int light, RayCounts& counts) const;
  uint32_t sample_state(const CellSample& sample, uint32_t group, int light, RayCounts& counts) const;
  void allocate();
  uint32_t occluder_id(uint32_t group, PrimKind kind, uint32_t prim) const;

  const RenderScene& scene_;
  SurfaceCells cells_;
  size_t lights_;
  struct Free {
    void operator()(uint32_t* p) const;
  };
  // Read and written through std::atomic_ref; calloc'd so that untouched
  // pages stay the kernel's shared zero page.
  std::unique_ptr<uint32_t[], Free> states_;  // [slot]: LightVisibility of light l in bits 2l, 2l + 1
  std::unique_ptr<uint32_t[], Free> vwords_;  // [vertex * lights + light]: state << 30 | side << 29 | occluder id
  std::vector<std::array<uint32_t, 3>> prim_base_;   // per group: first global id of each kind
  std::vector<uint64_t> snapshot_;                    // transforms the cells hold, as bits
  uint64_t clears_ = 0;
};

}  // namespace holoray
