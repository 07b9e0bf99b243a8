// holoray/accel: a bounding volume hierarchy built by Embree's own builder
// (rtcBuildBVH: SAH, with spatial splits at high quality) into plain
// arrays of ours, for a traversal that is not Embree's (the GPU path,
// src/gpu/). Nodes are 4 or 8 wide; a leaf's primitives are a run of
// `order`. Indices, no pointers: the arrays can be copied to a device.
#pragma once

#include <cstdint>
#include <vector>

namespace holoray {

inline constexpr int kBvhMaxWidth = 8;

/// A primitive's box (world, float) for the builder.
struct PrimitiveBox {
  float lo[3], hi[3];
};

/// One node: up to Bvh::width children, each a box and either an inner
/// node (count 0, `index` into nodes) or a leaf (count > 0 primitives from
/// order[index]); unused slots (those past the width too) have count -1 and
/// an empty box.
struct BvhNode {
  float lo[3][kBvhMaxWidth], hi[3][kBvhMaxWidth];  // [axis][child]
  int32_t index[kBvhMaxWidth];
  int32_t count[kBvhMaxWidth];
};

/// nodes[0] is the root (a scene with one leaf's worth of primitives still
/// gets a root node). `order` lists primitive numbers (indices into the
/// boxes given), a primitive possibly in several leaves (spatial splits).
struct Bvh {
  std::vector<BvhNode> nodes;
  std::vector<uint32_t> order;
  int depth = 0;  ///< levels of nodes, the root's counted
  int width = 4;  ///< children a node holds at most: 4 or 8
};

/// How hard the builder works: `high` is SAH with spatial splits (a
/// primitive may sit in several leaves), for a scene traced many times;
/// `fast` is Embree's medium quality without splits, for a hierarchy rebuilt
/// every frame of an animation (docs/design/gpu.md has both measured).
enum class BvhQuality { high, fast };

/// Builds the hierarchy of `boxes` (at most `max_leaf` primitives a leaf,
/// 1 to 8) with nodes `width` (4 or 8) wide, at most 20 levels deep (4
/// wide: a depth-first walk's stack then holds (width - 1) (depth - 1) + 1
/// <= 64 entries) or 18 (8 wide: the caller checks). Empty input: one node with no
/// children. Throws std::runtime_error with Embree's message when its
/// builder fails (out of memory), std::invalid_argument for a bad max_leaf
/// or width.
Bvh build_bvh(const std::vector<PrimitiveBox>& boxes, int max_leaf = 4, BvhQuality quality = BvhQuality::high,
              int width = 4);

/// The same tree over primitives that moved: every child's box recomputed
/// bottom up from `boxes` (numbered as the build's), the nodes, leaves and
/// order kept. A primitive the build split across leaves takes its whole
/// box in each (looser, never missing it). Throws std::invalid_argument when
/// `order` names a primitive past `boxes`.
void refit_bvh(Bvh& bvh, const std::vector<PrimitiveBox>& boxes);

/// How loose `bvh`'s boxes are around `boxes` (numbered as the build's):
/// the summed surface areas of every child's box over those of the
/// primitives' own boxes (the surface area heuristic's node cost, measured
/// against the primitives rather than the root, so that it does not change
/// when the whole scene moves rigidly). A refit tree whose primitives parted
/// grows it, where its boxes now span the gap; the caller rebuilds past a
/// bound (gpu_scene.cpp).
double bvh_cost(const Bvh& bvh, const std::vector<PrimitiveBox>& boxes);

}  // namespace holoray
