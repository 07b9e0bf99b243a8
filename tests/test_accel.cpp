// AccelScene's packets against its single rays: the shadow packets
// (rtcOccluded16, coherent traversal where the scene allows it), as
// RayPackets and as ShadowPackets filled lane by lane, in a static scene and
// in one whose geometry is an instance; and the refined hits of an
// intersection packet (triangles of unmoved groups refined two lanes at a
// time), bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "accel/accel_scene.hpp"
#include "accel/bvh_builder.hpp"
#include "math/transform.hpp"
#include "util/parallel.hpp"

namespace holoray {
namespace {

// A 6x6 grid of small triangles and a row of spheres hanging over z = 0:
// shadow rays from the floor toward a light above see some blocked, some not.
GeometryGroup occluders(bool movable) {
  GeometryGroup g;
  g.movable = movable;
  for (int y = 0; y < 6; ++y)
    for (int x = 0; x < 6; ++x) {
      const float cx = -1.5f + 0.6f * static_cast<float>(x), cy = -1.5f + 0.6f * static_cast<float>(y);
      const auto base = static_cast<uint32_t>(g.triangles.positions.size() / 3);
      for (const float v : {cx, cy, 1.0f, cx + 0.4f, cy, 1.0f, cx, cy + 0.4f, 1.0f}) g.triangles.positions.push_back(v);
      for (uint32_t k = 0; k < 3; ++k) g.triangles.indices.push_back(base + k);
    }
  for (int k = 0; k < 4; ++k) g.spheres.push_back(Sphere{Vec3{-1.2 + 0.8 * k, 0.3, 1.6}, 0.25});
  return g;
}

// Every shadow packet of floor points toward a light at (0.2, -0.1, 4), 16
// neighbouring points at a time, gives each lane the single-ray answer.
void expect_packets_agree_with_single_rays(const AccelScene& accel) {
  const Vec3 light{0.2, -0.1, 4};
  int blocked_lanes = 0, lanes = 0;
  for (int row = 0; row < 40; ++row)
    for (int col = 0; col < 40; col += 4) {
      RayPacket packet;
      for (int k = 0; k < kPacketSize; ++k) {
        const Vec3 p{-2 + 0.1 * (col + k % 4), -2 + 0.1 * row + 0.025 * (k / 4), 0};
        const Vec3 to = light - p;
        packet.rays[k] = Ray{p, to / length(to), 1e-6, length(to) - 1e-6};
        packet.active[k] = (k + row) % 7 != 0;  // some lanes off, as in shading
      }
      bool blocked[kPacketSize];
      accel.occluded(packet, blocked);
      // The same segments from tnear 0, written straight into Embree's layout
      // as the shading writes them.
      ShadowPacket direct;
      for (int k = 0; k < kPacketSize; ++k) {
        const Ray& r = packet.rays[k];
        const float org[3] = {static_cast<float>(r.org.x), static_cast<float>(r.org.y), static_cast<float>(r.org.z)};
        direct.set(k, org, r.dir, r.tfar, packet.active[k]);
      }
      bool direct_blocked[kPacketSize];
      accel.occluded(direct, direct_blocked);
      for (int k = 0; k < kPacketSize; ++k) {
        const Ray& r = packet.rays[k];
        const bool single = packet.active[k] && accel.occluded(r);
        ASSERT_EQ(blocked[k], single) << "row " << row << ", column " << col << ", lane " << k;
        const bool single_from_0 = packet.active[k] && accel.occluded(Ray{r.org, r.dir, 0, r.tfar});
        ASSERT_EQ(direct_blocked[k], single_from_0) << "ShadowPacket: row " << row << ", column " << col << ", lane " << k;
        lanes += packet.active[k];
        blocked_lanes += blocked[k];
      }
    }
  // The scene blocks some of the rays and lets others through: the
  // comparison saw both answers.
  EXPECT_GT(blocked_lanes, lanes / 20);
  EXPECT_LT(blocked_lanes, lanes - lanes / 20);
}

TEST(ShadowPackets, AgreeWithSingleRaysInAStaticScene) {
  std::vector<GeometryGroup> groups;
  groups.push_back(occluders(false));
  expect_packets_agree_with_single_rays(AccelScene(std::move(groups)));
}

// The instanced scene takes Embree's incoherent packet traversal: the
// coherent one, in Embree 3.13.5, never returned on animated shots (the
// Video and Skinning tests caught that; this small scene does not hang it).
TEST(ShadowPackets, AgreeWithSingleRaysInAnInstancedMovedScene) {
  std::vector<GeometryGroup> groups;
  groups.push_back(occluders(true));
  AccelScene accel(std::move(groups));
  accel.set_transforms({Affine::translate(Vec3{0.1, 0.05, 0.2}) * Affine::rotate_axis(2, 10)});
  expect_packets_agree_with_single_rays(accel);
}

// Embree's hierarchy is built by the first query (or build()), not when
// the scene is made (a GPU render never needs it); a move or new vertices
// after it leave it stale, and the next query sees them. Many threads
// asking at once get the same answers one thread gets.
TEST(AccelScene, TheFirstQueryBuildsTheHierarchyAndAMoveIsSeenByTheNext) {
  std::vector<GeometryGroup> groups;
  groups.push_back(occluders(false));
  groups.push_back(occluders(true));
  AccelScene accel(std::move(groups));
  EXPECT_FALSE(accel.built());
  // Straight down through the first triangle of the grid (its corner at
  // -1.5, -1.5, z 1) and a sphere of the static group.
  const Ray down{Vec3{-1.4, -1.4, 5}, Vec3{0, 0, -1}, 0, 100};
  Hit hit;
  ASSERT_TRUE(accel.intersect(down, hit));
  EXPECT_TRUE(accel.built());
  EXPECT_NEAR(hit.t, 4.0, 1e-9);
  // The movable group lifted by 1: the same ray meets it first, at z 2.
  accel.set_transforms({Affine{}, Affine::translate(Vec3{0, 0, 1})});
  EXPECT_FALSE(accel.built());
  ASSERT_TRUE(accel.intersect(down, hit));
  EXPECT_NEAR(hit.t, 3.0, 1e-6);
  EXPECT_EQ(hit.group, 1u);
  // Unmoved again, then 2 x 64 first queries at once on the stale scene.
  accel.set_transforms({Affine{}, Affine{}});
  auto ray = [](int k) { return Ray{Vec3{-1.4 + 0.6 * (k % 6), -1.4 + 0.6 * (k / 6 % 6), 5}, Vec3{0, 0, -1}, 0, 100}; };
  std::vector<double> t(128, -1);
  parallel_for_n(128, 0, [&](int k) {
    Hit h;
    if (accel.intersect(ray(k), h)) t[static_cast<size_t>(k)] = h.t;
  });
  EXPECT_TRUE(accel.built());
  int on_floor = 0;
  for (int k = 0; k < 128; ++k) {
    Hit h;
    ASSERT_TRUE(accel.intersect(ray(k), h)) << "ray " << k;
    EXPECT_EQ(t[static_cast<size_t>(k)], h.t) << "ray " << k;
    on_floor += std::abs(h.t - 4.0) < 1e-9;
  }
  EXPECT_GT(on_floor, 64);  // most meet the triangles; some a sphere first
}

// Rays fanning down from above the occluders (a lens's eye rays): each
// packet lane's refined hit has the single ray's bits, whether its triangle
// was refined in a pair (an unmoved group), alone (the packet's odd one
// out), or through an instance's transform (the moved group), and spheres.
TEST(IntersectPackets, RefinedHitsEqualSingleRaysBitForBit) {
  std::vector<GeometryGroup> groups;
  groups.push_back(occluders(false));
  groups.push_back(occluders(true));
  AccelScene accel(std::move(groups));
  accel.set_transforms({Affine{}, Affine::translate(Vec3{0.3, 0.1, -0.4}) * Affine::rotate_axis(2, 25)});
  int compared = 0, triangles = 0;
  for (int row = 0; row < 30; ++row)
    for (int col = 0; col < 30; col += 4) {
      RayPacket packet;
      const Vec3 eye{0.1 * (col - 15), 0.1 * (row - 15), 6};
      for (int k = 0; k < kPacketSize; ++k) {
        const Vec3 target{-2 + 0.13 * (col + k % 4), -2 + 0.13 * row + 0.03 * (k / 4), 0};
        packet.rays[k] = Ray{eye, (target - eye) / length(target - eye), 0, INFINITY};
        packet.active[k] = (k * 3 + row) % 11 != 0;
      }
      Hit hits[kPacketSize];
      bool found[kPacketSize];
      accel.intersect(packet, hits, found, RayCoherence::coherent);
      for (int k = 0; k < kPacketSize; ++k) {
        Hit one;
        const bool single = packet.active[k] && accel.intersect(packet.rays[k], one);
        ASSERT_EQ(found[k], single) << "row " << row << ", column " << col << ", lane " << k;
        if (!single) continue;
        const Hit& h = hits[k];
        ASSERT_EQ(h.kind, one.kind);
        ASSERT_EQ(h.group, one.group);
        ASSERT_EQ(h.prim, one.prim);
        for (const auto& [a, b] : {std::pair{&h.t, &one.t}, std::pair{&h.u, &one.u}, std::pair{&h.v, &one.v}})
          ASSERT_EQ(std::memcmp(a, b, sizeof *a), 0) << "row " << row << ", column " << col << ", lane " << k;
        ASSERT_EQ(std::memcmp(&h.ng, &one.ng, sizeof h.ng), 0) << "row " << row << ", column " << col << ", lane " << k;
        ASSERT_EQ(std::memcmp(&h.p_object, &one.p_object, sizeof h.p_object), 0);
        ++compared;
        triangles += h.kind == PrimKind::triangle && h.group == 0;
      }
    }
  // Pairs of unmoved triangles, and the other kinds, were all compared.
  EXPECT_GT(triangles, 200);
  EXPECT_GT(compared, triangles + 100);
}

// Embree's builder into our nodes (the GPU path's hierarchy), at both
// qualities and both widths: every primitive reachable from the root, each
// child box holding what is under it (the fast build, without spatial
// splits: each primitive's whole box, and in exactly one leaf), no slot
// past the width used, and no deeper than the GPU's stack allows.
// Every child box holds its node's children's boxes, and every primitive
// sits in at least one leaf (exactly one without spatial splits); with
// `whole`, each leaf's box holds its primitives' whole boxes (no split
// clipped them: a fast build, or a refit).
void expect_boxes_hold_their_primitives(const Bvh& bvh, const std::vector<PrimitiveBox>& boxes, bool whole, bool once) {
  const int width = bvh.width;
  EXPECT_LE((width - 1) * (bvh.depth - 1) + 1, 64);  // HR_STACK
  std::vector<int> seen(boxes.size(), 0);
  // Depth first from the root, each child checked against its parent's slot.
  std::vector<int> stack{0};
  while (!stack.empty()) {
    const BvhNode& n = bvh.nodes[size_t(stack.back())];
    stack.pop_back();
    for (int c = 0; c < kBvhMaxWidth; ++c) {
      if (c >= width) EXPECT_EQ(n.count[c], -1);
      if (n.count[c] < 0) continue;
      if (n.count[c] == 0) {
        const BvhNode& child = bvh.nodes[size_t(n.index[c])];
        for (int g = 0; g < kBvhMaxWidth; ++g)
          for (int a = 0; a < 3 && child.count[g] >= 0; ++a) {
            EXPECT_GE(child.lo[a][g], n.lo[a][c]);
            EXPECT_LE(child.hi[a][g], n.hi[a][c]);
          }
        stack.push_back(n.index[c]);
        continue;
      }
      ASSERT_LE(n.count[c], 4);
      for (int r = 0; r < n.count[c]; ++r) {
        const uint32_t p = bvh.order[size_t(n.index[c] + r)];
        ++seen[p];
        if (whole)
          for (int a = 0; a < 3; ++a) {
            EXPECT_GE(boxes[p].lo[a], n.lo[a][c]);
            EXPECT_LE(boxes[p].hi[a], n.hi[a][c]);
          }
      }
    }
  }
  for (size_t p = 0; p < boxes.size(); ++p) {
    ASSERT_GE(seen[p], 1) << "primitive " << p;
    if (once) ASSERT_EQ(seen[p], 1) << "primitive " << p;
  }
}

std::vector<PrimitiveBox> scattered_boxes(uint32_t seed) {
  std::vector<PrimitiveBox> boxes;
  auto next = [&] { return (seed = seed * 1664525u + 1013904223u) / 4294967296.0f; };
  for (int k = 0; k < 5000; ++k) {
    const float x = 100 * next(), y = 100 * next(), z = 10 * next(), w = 0.1f + 3 * next();
    boxes.push_back({{x, y, z}, {x + w, y + w * next(), z + w}});
  }
  return boxes;
}

TEST(BvhBuilder, EveryPrimitiveSitsUnderBoxesThatHoldIt) {
  const std::vector<PrimitiveBox> boxes = scattered_boxes(7);
  for (const int width : {4, 8})
    for (const BvhQuality q : {BvhQuality::high, BvhQuality::fast}) {
      SCOPED_TRACE(width);
      const Bvh bvh = build_bvh(boxes, 4, q, width);
      EXPECT_EQ(bvh.width, width);
      expect_boxes_hold_their_primitives(bvh, boxes, q == BvhQuality::fast, q == BvhQuality::fast);
    }
}

// A refit keeps the tree and recomputes its boxes: over the boxes it was
// built on, a fast build's nodes come back bit for bit; over moved boxes
// every leaf holds its primitives' whole boxes again (split leaves too);
// and the node cost grows as primitives part.
TEST(BvhBuilder, ARefitHoldsTheMovedPrimitivesAndItsCostGrowsAsTheyPart) {
  const std::vector<PrimitiveBox> boxes = scattered_boxes(11);
  for (const int width : {4, 8})
    for (const BvhQuality q : {BvhQuality::high, BvhQuality::fast}) {
      SCOPED_TRACE(testing::Message() << width << (q == BvhQuality::fast ? " fast" : " high"));
      const Bvh built = build_bvh(boxes, 4, q, width);
      if (q == BvhQuality::fast) {
        Bvh same = built;
        refit_bvh(same, boxes);
        ASSERT_EQ(same.nodes.size(), built.nodes.size());
        EXPECT_EQ(std::memcmp(same.nodes.data(), built.nodes.data(), built.nodes.size() * sizeof(BvhNode)), 0);
      }
      // A small drift, then half the primitives carried 1000 units away.
      std::vector<PrimitiveBox> drift = boxes, parted = boxes;
      for (size_t p = 0; p < boxes.size(); ++p)
        for (int a = 0; a < 3; ++a) {
          const float d = 0.3f * float((p * 7 + size_t(a) * 3) % 5) - 0.6f;
          drift[p].lo[a] += d, drift[p].hi[a] += d;
          if (p % 2) parted[p].lo[a] += 1000, parted[p].hi[a] += 1000;
        }
      Bvh drifted = built, apart = built;
      refit_bvh(drifted, drift);
      refit_bvh(apart, parted);
      expect_boxes_hold_their_primitives(drifted, drift, true, q == BvhQuality::fast);
      expect_boxes_hold_their_primitives(apart, parted, true, q == BvhQuality::fast);
      EXPECT_LT(bvh_cost(drifted, drift), 1.2 * bvh_cost(built, boxes));
      EXPECT_GT(bvh_cost(apart, parted), 3 * bvh_cost(build_bvh(parted, 4, q, width), parted));
    }
}

}  // namespace
}  // namespace holoray
