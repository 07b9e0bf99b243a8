// holoray/accel: the only place that includes Embree. An RAII device and
// scene over three geometries (triangles, exact spheres, exact open cones),
// queried with single rays; the renderer never sees an Embree type.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "accel/shapes.hpp"
#include "math/vec.hpp"

namespace holoray {

/// Which geometry a hit is on; also its Embree geometry id.
enum class PrimKind : uint32_t { triangle = 0, sphere = 1, cone = 2 };

/// Triangles as Embree takes them (world frame, float).
struct TriangleData {
  std::vector<float> positions;    ///< xyz per vertex
  std::vector<uint32_t> indices;   ///< 3 per triangle
};

/// A ray segment o + t*d, t in (tnear, tfar), world frame; d need not be unit.
struct Ray {
  Vec3 org, dir;
  double tnear = 0, tfar = INFINITY;
};

/// Nearest hit: ray parameter t (refined to double precision), the primitive,
/// Embree's barycentrics (triangles) and the primitive's outward / winding
/// geometric normal (unit).
struct Hit {
  double t = INFINITY;
  PrimKind kind = PrimKind::triangle;
  uint32_t prim = 0;
  float u = 0, v = 0;
  Vec3 ng;
};

/// Hint for Embree's traversal: primary rays of one lens are coherent.
enum class RayCoherence { coherent, incoherent };

class AccelScene {
 public:
  /// Builds the BVH (Embree's build runs on the caller's oneTBB pool, so a
  /// tbb::global_control caps it). Throws std::runtime_error with Embree's
  /// message on failure.
  AccelScene(TriangleData triangles, std::vector<Sphere> spheres, std::vector<Cone> cones);
  ~AccelScene();
  AccelScene(const AccelScene&) = delete;
  AccelScene& operator=(const AccelScene&) = delete;

  /// Nearest hit in (tnear, tfar); false when none.
  bool intersect(const Ray& ray, Hit& hit, RayCoherence coherence = RayCoherence::incoherent) const;
  /// Any hit in (tnear, tfar) (shadow rays).
  bool occluded(const Ray& ray) const;

  /// Bounds of all geometry (world); empty for an empty scene.
  const Bounds3& bounds() const { return bounds_; }
  size_t triangle_count() const { return tri_.indices.size() / 3; }
  size_t sphere_count() const { return spheres_.size(); }
  size_t cone_count() const { return cones_.size(); }

  /// Raw handle for the benchmark's plain-Embree yardstick (an RTCScene).
  void* rtc_scene() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  TriangleData tri_;
  std::vector<Sphere> spheres_;
  std::vector<Cone> cones_;
  Bounds3 bounds_;
};

}  // namespace holoray
