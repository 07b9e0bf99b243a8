// holoray/accel: a bounding volume hierarchy built by Embree's own builder
// (rtcBuildBVH: SAH, with spatial splits at high quality) into plain
// arrays of ours, for a traversal that is not Embree's (the GPU path,
// src/gpu/). Nodes are up to kBvhWidth wide; a leaf's primitives are a run
// of `order`. Indices, no pointers: the arrays can be copied to a device.
#pragma once

#include <cstdint>
#include <vector>

namespace holoray {

inline constexpr int kBvhWidth = 4;

/// A primitive's box (world, float) for the builder.
struct PrimitiveBox {
  float lo[3], hi[3];
};

/// One node: up to kBvhWidth children, each a box and either an inner node
/// (count 0, `index` into nodes) or a leaf (count > 0 primitives from
/// order[index]); unused slots have count -1 and an empty box.
struct BvhNode {
  float lo[3][kBvhWidth], hi[3][kBvhWidth];  // [axis][child]
  int32_t index[kBvhWidth];
  int32_t count[kBvhWidth];
};

/// nodes[0] is the root (a scene with one leaf's worth of primitives still
/// gets a root node). `order` lists primitive numbers (indices into the
/// boxes given), a primitive possibly in several leaves (spatial splits).
struct Bvh {
  std::vector<BvhNode> nodes;
  std::vector<uint32_t> order;
  int depth = 0;  ///< levels of nodes, the root's counted
};

/// How hard the builder works: `high` is SAH with spatial splits (a
/// primitive may sit in several leaves), for a scene traced many times;
/// `fast` is Embree's medium quality without splits, for a hierarchy rebuilt
/// every frame of an animation (docs/design/gpu.md has both measured).
enum class BvhQuality { high, fast };

/// Builds the hierarchy of `boxes` (at most `max_leaf` primitives a leaf,
/// 1 to 8). Empty input: one node with no children. Throws
/// std::runtime_error with Embree's message when its builder fails
/// (out of memory), std::invalid_argument for a bad max_leaf.
Bvh build_bvh(const std::vector<PrimitiveBox>& boxes, int max_leaf = 4, BvhQuality quality = BvhQuality::high);

}  // namespace holoray
