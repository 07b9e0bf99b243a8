#include "render/emitters.hpp"

#include <algorithm>
#include <cmath>

#include "render/shading_vec.hpp"
#include "shading/common.h"
#include "shading/warp.h"

namespace holoray {

namespace {

uint64_t key(uint32_t group, uint32_t prim) { return uint64_t{group} << 32 | prim; }

}  // namespace

EmissiveTriangles::EmissiveTriangles(const RenderScene& scene) {
  const AccelScene& accel = scene.accel();
  std::vector<double> power;
  for (uint32_t g = 0; g < accel.group_count(); ++g) {
    const TriangleData& t = accel.geometry(g).triangles;
    const Affine& to_world = accel.transform(g);
    const uint32_t count = static_cast<uint32_t>(t.indices.size() / 3);
    for (uint32_t p = 0; p < count; ++p) {
      const int object = scene.object_of(g, PrimKind::triangle, p);
      const Material& m = scene.materials()[scene.material_of_object(object)];
      const double lum = shading::hr_luminance(to_f(m.emission));
      if (!(lum > 0)) continue;
      Vec3 v[3];
      for (int k = 0; k < 3; ++k) {
        const float* q = &t.positions[size_t{t.indices[size_t{p} * 3 + k]} * 3];
        v[k] = to_world.point(Vec3{q[0], q[1], q[2]});
      }
      const Vec3 n = cross(v[1] - v[0], v[2] - v[0]);
      const double area = 0.5 * length(n);
      if (!(area > 0)) continue;
      index_[key(g, p)] = static_cast<uint32_t>(tris_.size());
      tris_.push_back(Tri{g, p, v[0], v[1] - v[0], v[2] - v[0], n / (2 * area), area, &m, object});
      power.push_back(lum * area);
    }
  }
  double total = 0;
  for (double w : power) total += w;
  total_power_ = total;
  cdf_.resize(power.size());
  double run = 0;
  for (size_t k = 0; k < power.size(); ++k) cdf_[k] = (run += power[k]) / total;
  if (!cdf_.empty()) cdf_.back() = 1;
}

EmissiveTriangles::Sample EmissiveTriangles::sample(double u_pick, double u0, double u1) const {
  const size_t k = std::min<size_t>(std::upper_bound(cdf_.begin(), cdf_.end(), u_pick) - cdf_.begin(), tris_.size() - 1);
  const Tri& t = tris_[k];
  const double p_pick = cdf_[k] - (k ? cdf_[k - 1] : 0.0);
  const shading::vec2 b = shading::hr_uniform_triangle(shading::vec2(float(u0), float(u1)));
  Sample s;
  s.position = t.p0 + t.e1 * b.x + t.e2 * b.y;
  s.normal = t.normal;
  s.pdf_area = p_pick / t.area;
  SurfacePoint& sp = s.surface;
  sp.position = s.position;
  sp.ng = sp.ns = t.normal;
  sp.object = t.object;
  sp.kind = PrimKind::triangle;
  sp.material = t.material;
  sp.group = t.group, sp.prim = t.prim;
  sp.u = b.x, sp.v = b.y;
  return s;
}

double EmissiveTriangles::pdf_area(uint32_t group, uint32_t prim) const {
  const auto it = index_.find(key(group, prim));
  if (it == index_.end()) return 0;
  const size_t k = it->second;
  return (cdf_[k] - (k ? cdf_[k - 1] : 0.0)) / tris_[k].area;
}

EmissiveTriangles::Entry EmissiveTriangles::entry(size_t k) const {
  const Tri& t = tris_.at(k);
  return {t.group, t.prim, cdf_[k], cdf_[k] - (k ? cdf_[k - 1] : 0.0), t.area};
}

}  // namespace holoray
