#include "accel/bvh_builder.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "accel/embree_api.hpp"

#if HOLORAY_EMBREE_MAJOR >= 4
#include <embree4/rtcore_builder.h>
#else
#include <embree3/rtcore_builder.h>
#endif

namespace holoray {

namespace {

// Embree's builder hands out nodes and leaves from its thread-local
// allocator on many threads at once; they live until the BVH is released,
// and build_bvh flattens them into index arrays before that.
struct Node;
struct Child {
  float lo[3], hi[3];
  Node* node = nullptr;
};
struct Node {
  int count = 0;  // children; 0 with `prims` set: a leaf
  Child child[kBvhMaxWidth];
  const uint32_t* prims = nullptr;
  int prim_count = 0;
};

void* create_node(RTCThreadLocalAllocator alloc, unsigned child_count, void*) {
  auto* n = new (rtcThreadLocalAlloc(alloc, sizeof(Node), 16)) Node;
  n->count = static_cast<int>(child_count);
  return n;
}

void set_children(void* node, void** children, unsigned count, void*) {
  auto* n = static_cast<Node*>(node);
  for (unsigned k = 0; k < count; ++k) n->child[k].node = static_cast<Node*>(children[k]);
}

void set_bounds(void* node, const RTCBounds** bounds, unsigned count, void*) {
  auto* n = static_cast<Node*>(node);
  for (unsigned k = 0; k < count; ++k) {
    const RTCBounds& b = *bounds[k];
    Child& c = n->child[k];
    c.lo[0] = b.lower_x, c.lo[1] = b.lower_y, c.lo[2] = b.lower_z;
    c.hi[0] = b.upper_x, c.hi[1] = b.upper_y, c.hi[2] = b.upper_z;
  }
}

void* create_leaf(RTCThreadLocalAllocator alloc, const RTCBuildPrimitive* prims, size_t count, void*) {
  auto* n = new (rtcThreadLocalAlloc(alloc, sizeof(Node), 16)) Node;
  auto* ids = static_cast<uint32_t*>(rtcThreadLocalAlloc(alloc, sizeof(uint32_t) * count, 4));
  for (size_t k = 0; k < count; ++k) ids[k] = prims[k].primID;
  n->prims = ids;
  n->prim_count = static_cast<int>(count);
  return n;
}

// A primitive split by a plane: each side keeps the box clipped there (the
// box of a box, so looser than the primitive's own piece, never tighter).
void split_primitive(const RTCBuildPrimitive* prim, unsigned dim, float pos, RTCBounds* left, RTCBounds* right, void*) {
  const float lo[3] = {prim->lower_x, prim->lower_y, prim->lower_z};
  const float hi[3] = {prim->upper_x, prim->upper_y, prim->upper_z};
  float l_hi[3] = {hi[0], hi[1], hi[2]}, r_lo[3] = {lo[0], lo[1], lo[2]};
  l_hi[dim] = pos, r_lo[dim] = pos;
  *left = RTCBounds{lo[0], lo[1], lo[2], 0, l_hi[0], l_hi[1], l_hi[2], 0};
  *right = RTCBounds{r_lo[0], r_lo[1], r_lo[2], 0, hi[0], hi[1], hi[2], 0};
}

void on_error(void* user, RTCError code, const char* message) {
  auto* last = static_cast<std::string*>(user);
  if (last->empty()) *last = fmt::format("Embree error {}: {}", static_cast<int>(code), message ? message : "");
}

// Depth-first into `out`, children's slots filled as they are placed.
struct Flattener {
  Bvh& out;
  int add(const Node* n, int level) {
    out.depth = std::max(out.depth, level);
    const int at = static_cast<int>(out.nodes.size());
    out.nodes.emplace_back();
    for (int k = 0; k < kBvhMaxWidth; ++k) {
      BvhNode& slot = out.nodes[static_cast<size_t>(at)];
      if (k >= n->count) {
        for (int a = 0; a < 3; ++a) slot.lo[a][k] = INFINITY, slot.hi[a][k] = -INFINITY;
        slot.index[k] = 0, slot.count[k] = -1;
        continue;
      }
      const Child& c = n->child[k];
      for (int a = 0; a < 3; ++a) slot.lo[a][k] = c.lo[a], slot.hi[a][k] = c.hi[a];
      if (c.node->prims) {
        slot.index[k] = static_cast<int32_t>(out.order.size());
        slot.count[k] = c.node->prim_count;
        out.order.insert(out.order.end(), c.node->prims, c.node->prims + c.node->prim_count);
      } else {
        slot.count[k] = 0;
        const int child = add(c.node, level + 1);
        out.nodes[static_cast<size_t>(at)].index[k] = child;  // `slot` may have moved
      }
    }
    return at;
  }
};

}  // namespace

Bvh build_bvh(const std::vector<PrimitiveBox>& boxes, int max_leaf, BvhQuality quality, int width) {
  if (max_leaf < 1 || max_leaf > 8) throw std::invalid_argument(fmt::format("max_leaf: expected 1 to 8, got {}", max_leaf));
  if (width != 4 && width != 8) throw std::invalid_argument(fmt::format("width: expected 4 or 8, got {}", width));
  Bvh out;
  out.width = width;
  if (boxes.empty()) {
    Node empty;
    Flattener{out}.add(&empty, 1);
    return out;
  }
  // Spatial splits duplicate references: room for twice as many.
  const bool high = quality == BvhQuality::high;
  std::vector<RTCBuildPrimitive> prims(boxes.size() * (high ? 2 : 1));
  for (size_t k = 0; k < boxes.size(); ++k) {
    const PrimitiveBox& b = boxes[k];
    prims[k] = RTCBuildPrimitive{b.lo[0], b.lo[1], b.lo[2], 0, b.hi[0], b.hi[1], b.hi[2], static_cast<unsigned>(k)};
  }
  std::string error;
  RTCDevice device = rtcNewDevice(nullptr);
  if (!device) throw std::runtime_error("cannot create the Embree device for the BVH builder");
  rtcSetDeviceErrorFunction(device, on_error, &error);
  RTCBVH bvh = rtcNewBVH(device);
  RTCBuildArguments a = rtcDefaultBuildArguments();
  a.buildQuality = high ? RTC_BUILD_QUALITY_HIGH : RTC_BUILD_QUALITY_MEDIUM;
  a.maxBranchingFactor = static_cast<unsigned>(width);
  // The GPU traversal's stack holds (width - 1) (depth - 1) + 1 entries
  // (HR_STACK, checked as the scene is laid out). Embree makes leaves of
  // up to maxLeafSize whatever their cost within 8 levels of maxDepth: 10
  // for 8-wide nodes gave leaves of 2 to 4 primitives on balls_s4 (1 at 4
  // wide) and 6x the primitives tested a ray.
  a.maxDepth = width == 4 ? 20 : 18;
  a.minLeafSize = 1;
  a.maxLeafSize = static_cast<unsigned>(max_leaf);
  a.traversalCost = 1.0f;
  a.intersectionCost = 1.0f;
  a.bvh = bvh;
  a.primitives = prims.data();
  a.primitiveCount = boxes.size();
  a.primitiveArrayCapacity = prims.size();
  a.createNode = create_node;
  a.setNodeChildren = set_children;
  a.setNodeBounds = set_bounds;
  a.createLeaf = create_leaf;
  a.splitPrimitive = high ? split_primitive : nullptr;
  const auto* root = static_cast<const Node*>(rtcBuildBVH(&a));
  if (root) {
    if (root->prims) {  // a single leaf: give it a root node
      Node top;
      top.count = 1;
      top.child[0].node = const_cast<Node*>(root);
      for (size_t k = 0; k < boxes.size(); ++k)
        for (int ax = 0; ax < 3; ++ax) {
          top.child[0].lo[ax] = std::min(k ? top.child[0].lo[ax] : INFINITY, boxes[k].lo[ax]);
          top.child[0].hi[ax] = std::max(k ? top.child[0].hi[ax] : -INFINITY, boxes[k].hi[ax]);
        }
      Flattener{out}.add(&top, 1);
    } else {
      Flattener{out}.add(root, 1);
    }
  }
  rtcReleaseBVH(bvh);
  rtcReleaseDevice(device);
  if (!root) throw std::runtime_error(fmt::format("building the GPU hierarchy: {}", error.empty() ? "Embree's builder failed" : error));
  return out;
}

namespace {

// Child k's box of `n` recomputed, and the node's whole box returned (its
// children's union), depth first.
PrimitiveBox refit_node(Bvh& bvh, int at, const std::vector<PrimitiveBox>& boxes) {
  PrimitiveBox whole{{INFINITY, INFINITY, INFINITY}, {-INFINITY, -INFINITY, -INFINITY}};
  for (int k = 0; k < kBvhMaxWidth; ++k) {
    const int32_t count = bvh.nodes[static_cast<size_t>(at)].count[k];
    if (count < 0) continue;
    PrimitiveBox box{{INFINITY, INFINITY, INFINITY}, {-INFINITY, -INFINITY, -INFINITY}};
    const int32_t index = bvh.nodes[static_cast<size_t>(at)].index[k];
    if (count == 0) {
      box = refit_node(bvh, index, boxes);
    } else {
      for (int32_t q = index; q < index + count; ++q) {
        const uint32_t prim = bvh.order[static_cast<size_t>(q)];
        if (prim >= boxes.size())
          throw std::invalid_argument(fmt::format("refit: the hierarchy names primitive {} of {}", prim, boxes.size()));
        for (int a = 0; a < 3; ++a)
          box.lo[a] = std::min(box.lo[a], boxes[prim].lo[a]), box.hi[a] = std::max(box.hi[a], boxes[prim].hi[a]);
      }
    }
    BvhNode& n = bvh.nodes[static_cast<size_t>(at)];  // the recursion above does not reallocate, but read it again
    for (int a = 0; a < 3; ++a) {
      n.lo[a][k] = box.lo[a], n.hi[a][k] = box.hi[a];
      whole.lo[a] = std::min(whole.lo[a], box.lo[a]), whole.hi[a] = std::max(whole.hi[a], box.hi[a]);
    }
  }
  return whole;
}

double area(const float lo[3], const float hi[3]) {
  const double d[3] = {std::max(0.0, double(hi[0]) - lo[0]), std::max(0.0, double(hi[1]) - lo[1]),
                       std::max(0.0, double(hi[2]) - lo[2])};
  return 2 * (d[0] * d[1] + d[1] * d[2] + d[2] * d[0]);
}

}  // namespace

void refit_bvh(Bvh& bvh, const std::vector<PrimitiveBox>& boxes) {
  if (!bvh.nodes.empty()) refit_node(bvh, 0, boxes);
}

double bvh_cost(const Bvh& bvh, const std::vector<PrimitiveBox>& boxes) {
  double nodes = 0, prims = 0;
  for (const BvhNode& n : bvh.nodes)
    for (int k = 0; k < kBvhMaxWidth; ++k) {
      if (n.count[k] < 0) continue;
      const float lo[3] = {n.lo[0][k], n.lo[1][k], n.lo[2][k]}, hi[3] = {n.hi[0][k], n.hi[1][k], n.hi[2][k]};
      nodes += area(lo, hi);
    }
  for (const PrimitiveBox& b : boxes) prims += area(b.lo, b.hi);
  return prims > 0 ? nodes / prims : nodes;
}

}  // namespace holoray
