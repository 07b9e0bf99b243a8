// holoray/reuse: surface cells, the unit of view-independent reuse (issue 12).
//
// Every primitive's surface is cut into cells of about `cell_size` (object
// units) a side, keyed by the primitive and a parameter of the hit that costs
// no trigonometry:
//
// - triangle: its barycentrics (u, v) (Embree's, refined), n x n rows of
//   sub-triangles, n = ceil(sqrt(2 * area) / cell_size) (about cell_size^2 / 2 each);
// - sphere: the cube map of the direction from its centre (face = largest
//   axis, then the two other coordinates over it), n x n cells per face,
//   n = ceil(quarter circumference / cell_size);
// - cone: the same square map of the direction around its axis (four
//   faces, m cells each) times n steps along the axis.
//
// Each cell has fixed sample points, its corners and its centre (object
// space), with their geometric normals: whatever reuses a cell
// (render/shadow_cache.hpp) derives its value from these alone, so the value never
// depends on which pixel or thread asked first. Corners are the vertices of
// the primitive's cell grid and have slots of their own, shared by the cells
// that meet there (a triangle's inner vertex by six sub-triangles, a patch's
// by four), so what is learnt at a corner is learnt once. n and m are capped at
// kMaxCellsPerSide.
#pragma once

#include <cstdint>
#include <vector>

#include "accel/accel_scene.hpp"
#include "math/vec.hpp"

namespace holoray {

/// Where a hit falls: the cell's slot (index into per-cell storage, dense
/// over the whole scene) and its index within its primitive.
/// Trivial (no member initialisers) so that per-lane arrays of them cost
/// nothing on the shading path when no cache is in use; none() is "no cell".
struct CellRef {
  static constexpr uint64_t kNone = ~uint64_t{0};
  uint64_t slot;  ///< kNone: the primitive has no cells (over the memory bound)
  uint32_t local;
  static constexpr CellRef none() { return {kNone, 0}; }
};

/// One fixed sample point of a cell (object space of its group).
struct CellSample {
  Vec3 p_object;
  Vec3 n_object;  ///< unit geometric normal there; its sign carries no meaning
};

/// A corner of a cell: its vertex slot (dense over the scene, shared by the
/// cells that meet there) and its sample point.
struct CellCorner {
  uint64_t vertex;
  CellSample sample;
};

class SurfaceCells {
 public:
  static constexpr int kMaxCellsPerSide = 1024;
  static constexpr int kMaxSamples = 5;

  static constexpr int kMaxCorners = 4;

  /// Cuts every primitive of `accel` (object space, as its groups hold it)
  /// into cells of about `cell_size` (> 0). Primitives get cells in group,
  /// kind and index order while their cells and vertices together fit in
  /// `max_slots`; the rest get none (CellRef::kNone: their shadow rays are
  /// traced). Throws std::invalid_argument for a cell size that is not
  /// positive and finite.
  SurfaceCells(const AccelScene& accel, double cell_size, uint64_t max_slots);

  /// The cell of a hit on primitive (group, kind, prim): triangles use the
  /// barycentrics (u, v), spheres and cones the hit point in object space.
  CellRef locate(uint32_t group, PrimKind kind, uint32_t prim, double u, double v, const Vec3& p_object) const;

  /// The corners of cell `local` of a primitive: 3 for a triangle's
  /// sub-triangle, 4 for a sphere's or cone's patch (corners (i, j),
  /// (i+1, j), (i, j+1), (i+1, j+1) of its grid). Returns how many were
  /// written to out[].
  int corners(uint32_t group, PrimKind kind, uint32_t prim, uint32_t local, CellCorner out[kMaxCorners]) const;

  /// The centre of cell `local` (the corners' centroid on a triangle, the
  /// patch's middle on a sphere or cone), which no other cell shares.
  CellSample centre(uint32_t group, PrimKind kind, uint32_t prim, uint32_t local) const;

  /// The cell's corners' sample points, then its centre. Returns the count.
  int samples(uint32_t group, PrimKind kind, uint32_t prim, uint32_t local, CellSample out[kMaxSamples]) const;

  uint64_t slot_count() const { return slots_; }
  /// Corner vertices over the scene (CellCorner::vertex < this).
  uint64_t vertex_count() const { return vertices_; }
  double cell_size() const { return cell_size_; }
  /// Primitives left without cells by the memory bound.
  uint64_t uncovered_primitives() const { return uncovered_; }

 private:
  struct PrimCells {
    uint64_t first = CellRef::kNone;
    uint64_t first_vertex = 0;
    uint16_t n = 1;  ///< cells per side (triangle, sphere face) or along the cone's axis
    uint16_t m = 1;  ///< cone: cells per face around the axis
  };
  uint64_t build(double cell_size, uint64_t max_slots);

  // A cone's axis frame, fixed by its axis alone; kept because locate() runs per hit.
  struct ConeFrame {
    Vec3 axis, e1, e2;
    double length = 0;
  };

  const AccelScene& accel_;
  // [group][kind] -> per-primitive cells
  std::vector<std::vector<PrimCells>> prims_[3];
  std::vector<std::vector<ConeFrame>> cone_frames_;  // [group][cone]
  uint64_t slots_ = 0, vertices_ = 0, uncovered_ = 0;
  double cell_size_ = 0;
};

}  // namespace holoray
