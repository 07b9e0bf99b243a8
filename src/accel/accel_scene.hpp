// holoray/accel: the only place that includes Embree. An RAII device and a
// two-level scene: one group of geometry per scene file (triangles, exact
// spheres, exact open cones); a group that moves is an Embree instance whose
// transform changes per frame, a group that never moves sits in the top level
// at no cost. Queried with single rays; the renderer never sees an Embree type.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "accel/shapes.hpp"
#include "math/transform.hpp"
#include "math/vec.hpp"

namespace holoray {

/// Which geometry a hit is on.
enum class PrimKind : uint32_t { triangle = 0, sphere = 1, cone = 2 };

/// Triangles as Embree takes them (object space, float).
struct TriangleData {
  std::vector<float> positions;    ///< xyz per vertex
  std::vector<uint32_t> indices;   ///< 3 per triangle
};

/// Says whether a triangle is cut away at barycentrics (u, v): an
/// alpha-masked texture (glTF alphaMode MASK). The BVH then ignores that hit
/// for every ray, eye and shadow alike (Embree filter functions). Called from
/// the traversal on any thread: thread-safe, cheap, no exceptions.
class TriangleCutout {
 public:
  virtual ~TriangleCutout() = default;
  /// `prim`: the triangle within its group; (u, v): weights of its vertices 1 and 2.
  virtual bool cut(uint32_t group, uint32_t prim, float u, float v) const = 0;
};

/// The geometry of one scene file, in its own (object) space.
struct GeometryGroup {
  TriangleData triangles;
  std::vector<Sphere> spheres;
  std::vector<Cone> cones;
  bool movable = false;  ///< instanced: set_transforms may move it
  /// Its triangles' vertices change between frames (a skinned mesh):
  /// set_positions refits its BVH (Embree's refit build). Implies movable.
  bool deformable = false;
  /// Asked about every candidate triangle hit when set (not owned; must
  /// outlive the AccelScene); null: every triangle is solid.
  const TriangleCutout* cutout = nullptr;
};

/// A ray segment o + t*d, t in (tnear, tfar), world frame; d need not be unit.
struct Ray {
  Vec3 org, dir;
  double tnear = 0, tfar = INFINITY;
};

/// A hit, refined in double precision: ray parameter t, the primitive, its
/// barycentrics (triangles: weights of vertices 1 and 2), the unit geometric
/// normal (world; outward for spheres and cones, winding for triangles) and
/// the hit point in the group's object space (what moves with the object).
struct Hit {
  double t = INFINITY;
  PrimKind kind = PrimKind::triangle;
  uint32_t group = 0;
  uint32_t prim = 0;
  double u = 0, v = 0;
  Vec3 ng;
  Vec3 p_object;
};

/// Embree's answer for one ray before the double-precision refinement:
/// which primitive (Embree's ids), float t, normal and barycentrics.
/// AccelScene::resolve turns it into the Hit that intersect() gives, bit for
/// bit; until then it costs nothing but the traversal, for callers that
/// need only which surface was hit and roughly where (the reverse
/// reprojection's lookups, temporal/reverse.cpp).
struct RawHit {
  unsigned geom_id = 0, inst_id = 0, prim_id = 0;
  float ng[3] = {0, 0, 0};
  float u = 0, v = 0, t = 0;
};

/// Hint for Embree's traversal: primary rays of one lens are coherent.
enum class RayCoherence { coherent, incoherent };

/// Width of the ray packets (Embree's rtcIntersect16 / rtcOccluded16; on
/// AVX2 machines Embree runs them as two 8-wide halves).
inline constexpr int kPacketSize = 16;

/// Up to kPacketSize rays traced together; lanes with active[k] false are
/// ignored. The rays of one lens all pass through its centre, which is what
/// makes a packet pay (issue 4, paper §6).
struct RayPacket {
  Ray rays[kPacketSize];
  bool active[kPacketSize] = {};
};

/// Shadow rays in Embree's 16-wide layout (RTCRay16: one float array per
/// coordinate, world frame), filled where the shading computes them, so that
/// no RayPacket of doubles is built and converted in between. Each value is
/// the double's static_cast<float>, as occluded(const RayPacket&) rounds, so
/// either gives the same answers for the same rays.
struct ShadowPacket {
  alignas(64) float org_x[kPacketSize], org_y[kPacketSize], org_z[kPacketSize], tnear[kPacketSize];
  float dir_x[kPacketSize], dir_y[kPacketSize], dir_z[kPacketSize], time[kPacketSize];
  float tfar[kPacketSize];
  unsigned mask[kPacketSize], id[kPacketSize], flags[kPacketSize];
  alignas(64) int valid[kPacketSize];  // -1: traced, 0: ignored

  /// Lane k: the segment from `org` (already rounded to float) along unit
  /// `dir` to `tfar`, traced where `traced`. Branch-free, so that a loop over
  /// the lanes computes every lane and keeps the ones it needs.
  void set(int k, const float org[3], const Vec3& dir, double tfar_, bool traced) {
    org_x[k] = org[0], org_y[k] = org[1], org_z[k] = org[2], tnear[k] = 0, time[k] = 0;
    dir_x[k] = static_cast<float>(dir.x), dir_y[k] = static_cast<float>(dir.y), dir_z[k] = static_cast<float>(dir.z);
    tfar[k] = static_cast<float>(tfar_);  // an infinity stays one
    mask[k] = ~0u, id[k] = static_cast<unsigned>(k), flags[k] = 0, valid[k] = -static_cast<int>(traced);
  }
};

class AccelScene {
 public:
  /// Hands the groups to Embree; their hierarchies (one per movable group
  /// and the top level) are built by build(), or by the first query: a
  /// scene only the GPU path traces never builds them (issue 71). Transforms
  /// start as the identity. Throws std::runtime_error with Embree's message
  /// on failure.
  explicit AccelScene(std::vector<GeometryGroup> groups);
  /// One static group (a still scene).
  AccelScene(TriangleData triangles, std::vector<Sphere> spheres, std::vector<Cone> cones);
  ~AccelScene();
  AccelScene(const AccelScene&) = delete;
  AccelScene& operator=(const AccelScene&) = delete;

  /// Builds (or, after set_transforms or set_positions, updates) Embree's
  /// hierarchies now, on the caller's oneTBB pool; a no-op when they stand.
  /// Every query calls it, so calling it is never needed for a right
  /// answer: a render calls it before its threads start, so that the build
  /// is not timed as tracing and is not run under a tile. Thread-safe.
  /// Throws std::runtime_error with Embree's message on failure.
  void build() const;
  /// Whether Embree's hierarchies stand for the current transforms and
  /// vertices (false before the first build() or query, and after a move).
  bool built() const;

  /// Object-to-world transform per group, for the next queries (not
  /// thread-safe against them). Throws std::invalid_argument when the count
  /// is wrong, a transform is singular, or a static group is given anything
  /// but the identity.
  void set_transforms(const std::vector<Affine>& object_to_world);
  /// New triangle vertices (object space, xyz per vertex, as many as it was
  /// built with) for a deformable group, named by the caller's `pose` tag
  /// (a frame; not 0, the pose it was built in); its BVH is refitted, not
  /// rebuilt. Not thread-safe against queries. Throws
  /// std::invalid_argument when the group is not deformable or the count
  /// differs.
  void set_positions(uint32_t group, const std::vector<float>& positions, uint64_t pose);
  /// The tag of the group's current vertices (0: as built). Two frames
  /// whose poses differ do not share its geometry: reuse treats it as moved.
  uint64_t pose(uint32_t group) const { return groups_[group].pose; }
  const Affine& transform(uint32_t group) const { return groups_[group].to_world; }
  /// transform(group).is_identity(), kept when the transform is set: asked per hit.
  bool is_identity(uint32_t group) const { return groups_[group].identity; }
  const Affine& inverse_transform(uint32_t group) const { return groups_[group].to_object; }
  size_t group_count() const { return groups_.size(); }
  /// The geometry of one group, in its object space (as built).
  const GeometryGroup& geometry(uint32_t group) const { return groups_[group].geo; }

  /// Nearest hit in (tnear, tfar); false when none. Refined in double; with
  /// `refined` false a triangle hit keeps Embree's float answer (t,
  /// barycentrics, the normalised geometric normal: secondary rays, within
  /// the image budget), while spheres and cones keep their double hits.
  bool intersect(const Ray& ray, Hit& hit, RayCoherence coherence = RayCoherence::incoherent,
                 bool refined = true) const;
  /// Any hit in (tnear, tfar) (shadow rays).
  bool occluded(const Ray& ray) const;
  /// intersect() for every active lane at once (rtcIntersect16); found[k] is
  /// false for inactive lanes. Hits are refined exactly as intersect() refines
  /// them, so a lane gives the same Hit as intersect() whenever Embree's packet
  /// and single-ray kernels pick the same primitive (all but exact ties);
  /// `refined` as for one ray.
  void intersect(const RayPacket& packet, Hit hits[kPacketSize], bool found[kPacketSize],
                 RayCoherence coherence = RayCoherence::incoherent, bool refined = true) const;
  /// intersect() without the refinement: raw[k] where found[k].
  void intersect_raw(const RayPacket& packet, RawHit raw[kPacketSize], bool found[kPacketSize],
                     RayCoherence coherence = RayCoherence::incoherent) const;
  /// The scene group, primitive kind and primitive of a raw hit.
  void primitive_of(const RawHit& raw, uint32_t& group, PrimKind& kind, uint32_t& prim) const;
  /// The refined hit of `ray`'s raw hit: what intersect() gives for it.
  void resolve(const Ray& ray, const RawHit& raw, Hit& hit) const {
    resolve(ray, raw.geom_id, raw.inst_id, raw.prim_id, raw.ng, raw.u, raw.v, raw.t, hit);
  }
  /// occluded() for every active lane at once (rtcOccluded16); false for
  /// inactive lanes. Coherent by default: a shading packet's shadow rays
  /// toward one light share their end point, and Embree's coherent packet
  /// traversal measured 5 % faster per gears_s4 EIA on them (same bits).
  /// Scenes with movable groups (instances) always take the incoherent
  /// traversal: Embree 3.13.5's coherent one never returns on them.
  void occluded(const RayPacket& packet, bool blocked[kPacketSize],
                RayCoherence coherence = RayCoherence::coherent) const;
  /// occluded() for the lanes of `packet` with valid[k] set; blocked[k] is
  /// false for the others. Same traversal and coherence rule as above.
  /// Embree traces the packet in place (no copy): a blocked lane's tfar
  /// comes back as -infinity.
  void occluded(ShadowPacket& packet, bool blocked[kPacketSize],
                RayCoherence coherence = RayCoherence::coherent) const;
  /// The ray against one primitive only, exactly (no BVH; for checking a
  /// reprojected point, temporal/). Triangles count as hit when the
  /// barycentrics are inside to 1e-9. Same refinement as intersect(), so the
  /// same ray and primitive give the same bits.
  bool intersect_primitive(const Ray& ray, uint32_t group, PrimKind kind, uint32_t prim, Hit& hit) const;

  /// Bounds of all geometry at the current transforms (world); empty for an empty scene.
  const Bounds3& bounds() const { return bounds_; }
  /// Bounds (world) of one group's geometry placed by `to_world` (its
  /// transform at some frame): its object-space box carried by the
  /// transform, so it may be loose; empty for an empty group.
  Bounds3 group_bounds(uint32_t group, const Affine& to_world) const;
  size_t triangle_count() const;
  size_t sphere_count() const;
  size_t cone_count() const;

  /// Raw handle for the benchmark's plain-Embree yardstick (an RTCScene),
  /// built.
  void* rtc_scene() const;

 private:
  struct Group {
    GeometryGroup geo;
    struct CutoutRef {
      const TriangleCutout* cutout = nullptr;
      uint32_t group = 0;
    } cutout_ref;  // Embree's user data for the triangles' filter functions
    std::vector<PreparedCone> cones;  // geo.cones prepared: what Embree's callbacks and refine() test
    Bounds3 object_bounds;
    Affine to_world, to_object;
    bool identity = true;
    uint64_t pose = 0;
  };
  bool refine(const Group& g, const Ray& ray, bool strict, double t_guess, Hit& hit) const;
  /// refine() (not strict) of two triangle hits in groups placed by the
  /// identity, two lanes per SSE2 instruction: the same bits. Each hit's
  /// group and prim are set; t_guess is Embree's t.
  void refine_triangle_pair(const Ray* const ray[2], const float t_guess[2], Hit* const hit[2]) const;
  /// Embree's hit record (ids, float normal and barycentrics, float t) into a
  /// refined Hit; shared by the single-ray and the packet queries.
  void resolve(const Ray& ray, unsigned geom_id, unsigned inst_id, unsigned prim_id, const float ng[3], float u,
               float v, float t, Hit& hit, bool refined = true) const;

  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::vector<Group> groups_;
  Bounds3 bounds_;
};

}  // namespace holoray
