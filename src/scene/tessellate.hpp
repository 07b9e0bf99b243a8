// holoray/scene: planar polygon to triangles, for NFF `p` and `pp`
// (nff-notes §8, §9). Ear clipping in the polygon's plane, so the concave
// 144-vertex gear faces come out right where a fan would not.
#pragma once

#include <array>
#include <span>
#include <vector>

#include "math/vec.hpp"

namespace holoray {

/// Triangles of one polygon, as indices into its vertex list.
struct Tessellation {
  Vec3 normal;                              // unit winding normal (front = counter-clockwise side)
  std::vector<std::array<int, 3>> triangles; // each wound like the polygon
};

/// Unit normal of the polygon's winding by Newell's method (robust where the
/// first corner is degenerate, as in teapot_s1); zero when the polygon has no area.
Vec3 polygon_normal(std::span<const Vec3> vertices);

/// Triangulates a simple planar polygon, convex or concave, by ear clipping in
/// its own plane, the ear with the smallest world bounding box first (fat
/// triangles for the BVH, not slivers fanned across the face); O(n^2). Zero-area triangles (collinear or repeated vertices) are
/// dropped; a polygon with no area gives no triangles. Never fails: on a
/// self-intersecting polygon it still terminates, clipping the best corner left.
Tessellation tessellate_polygon(std::span<const Vec3> vertices);

/// The `pp` rule (nff-notes §9): a vertex normal that points away from the
/// winding normal is flipped into its hemisphere; a zero one is replaced by it.
Vec3 shading_normal_in_hemisphere(const Vec3& vertex_normal, const Vec3& winding_normal);

}  // namespace holoray
