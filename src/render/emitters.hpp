// holoray/render: the scene's emissive surfaces as lights for the path
// integrator's next-event estimation: every triangle whose material gives
// off light (Material::emission: glTF emissiveFactor x strength, MTL Ke),
// in world space at the scene's current transforms, drawn in proportion to
// its power (emission luminance x area; a textured emission by its factor),
// then uniformly over its area. Emission is two-sided, as Blender's
// Emission shader and a double-sided glTF material give it.
#pragma once

#include <cstdint>
#include <unordered_map>
#include <vector>

#include "render/render_scene.hpp"

namespace holoray {

class EmissiveTriangles {
 public:
  /// The emissive triangles of `scene` at its current transforms (build it
  /// again after set_transforms or set_vertices).
  explicit EmissiveTriangles(const RenderScene& scene);

  bool empty() const { return tris_.empty(); }
  size_t size() const { return tris_.size(); }

  /// A point drawn on the emitters (u_pick picks a triangle, u0 and u1 a
  /// point on it, all in [0, 1)): its position and unit normal (world),
  /// the SurfacePoint to read its emission at, and the area density of
  /// having drawn it (the pick's probability / the triangle's area).
  struct Sample {
    Vec3 position, normal;
    SurfacePoint surface;
    double pdf_area = 0;
  };
  Sample sample(double u_pick, double u0, double u1) const;
  /// The area density sample() gives a point of triangle `prim` of `group`;
  /// 0 for a triangle that is not an emitter.
  double pdf_area(uint32_t group, uint32_t prim) const;
  /// Emitter k (in the order sample() picks by): its group and triangle,
  /// the running sum of the picks up to and including it, its pick's
  /// probability and its area; for the GPU path's table.
  struct Entry {
    uint32_t group, prim;
    double cdf, pick, area;
  };
  Entry entry(size_t k) const;
  /// The emitters' power (emission luminance x area, summed): a point of
  /// a triangle of emission luminance L is drawn with area density L / it.
  double total_power() const { return total_power_; }

 private:
  struct Tri {
    uint32_t group, prim;
    Vec3 p0, e1, e2, normal;
    double area;
    const Material* material;
    int object;
  };
  std::vector<Tri> tris_;
  std::vector<double> cdf_;  // power, cumulative, normalised
  std::unordered_map<uint64_t, uint32_t> index_;
  double total_power_ = 0;
};

}  // namespace holoray
