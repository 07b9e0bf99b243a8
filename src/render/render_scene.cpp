#include "render/render_scene.hpp"

#include <cmath>

#include "scene/tessellate.hpp"

namespace holoray {

RenderScene::RenderScene(const SceneDesc& desc) {
  materials_.push_back(Material{});  // grey diffuse for objects before the first `f` (nff-notes §1)
  materials_.insert(materials_.end(), desc.materials.begin(), desc.materials.end());

  TriangleData tris;
  std::vector<Sphere> spheres;
  std::vector<Cone> cones;
  object_material_.reserve(desc.objects.size());
  for (size_t oi = 0; oi < desc.objects.size(); ++oi) {
    const ObjectDesc& obj = desc.objects[oi];
    object_material_.push_back(static_cast<uint32_t>(obj.material + 1));
    const auto id = static_cast<uint32_t>(oi);
    if (const auto* s = std::get_if<SphereDesc>(&obj.shape)) {
      spheres.push_back({s->centre, s->radius});
      sphere_object_.push_back(id);
    } else if (const auto* c = std::get_if<ConeDesc>(&obj.shape)) {
      cones.push_back({c->base, c->apex, c->base_radius, c->apex_radius});
      cone_object_.push_back(id);
    } else {
      const auto& poly = std::get<PolygonDesc>(obj.shape);
      const Tessellation tess = tessellate_polygon(poly.vertices);
      if (tess.triangles.empty()) {
        ++skipped_polygons_;
        continue;
      }
      const auto base = static_cast<uint32_t>(tris.positions.size() / 3);
      for (const Vec3& v : poly.vertices) {
        tris.positions.push_back(static_cast<float>(v.x));
        tris.positions.push_back(static_cast<float>(v.y));
        tris.positions.push_back(static_cast<float>(v.z));
      }
      for (const auto& t : tess.triangles) {
        for (int k : t) tris.indices.push_back(base + static_cast<uint32_t>(k));
        tri_object_.push_back(id);
        tri_normal_.push_back(tess.normal);
        if (poly.normals.empty()) {
          tri_patch_.push_back(-1);
        } else {
          tri_patch_.push_back(static_cast<int32_t>(patch_normals_.size()));
          patch_normals_.push_back({shading_normal_in_hemisphere(poly.normals[t[0]], tess.normal),
                                    shading_normal_in_hemisphere(poly.normals[t[1]], tess.normal),
                                    shading_normal_in_hemisphere(poly.normals[t[2]], tess.normal)});
        }
      }
    }
  }
  accel_ = std::make_unique<AccelScene>(std::move(tris), std::move(spheres), std::move(cones));

  const double n = static_cast<double>(std::max<size_t>(1, desc.lights.size()));
  const double level = 1.0 / (2.0 * std::sqrt(n));
  ambient_ = Vec3{level, level, level};
  for (const Light& l : desc.lights) lights_.push_back({l.position, l.colour * level});
  background_ = desc.background;

  const Bounds3& b = accel_->bounds();
  double scale = 1;
  if (!b.empty()) {
    for (int a = 0; a < 3; ++a) scale = std::fmax(scale, std::fmax(std::fabs(b.lo[a]), std::fabs(b.hi[a])));
    scale = std::fmax(scale, length(b.diagonal()));
  }
  // Float geometry is exact to ~6e-8 of its coordinates; stay well clear of that.
  epsilon_ = 1e-5 * scale;
}

SurfacePoint RenderScene::surface(const Ray& ray, const Hit& hit) const {
  SurfacePoint sp;
  sp.position = ray.org + ray.dir * hit.t;
  sp.ng = hit.ng;
  sp.ns = hit.ng;
  uint32_t obj = 0;
  switch (hit.kind) {
    case PrimKind::triangle: {
      obj = tri_object_[hit.prim];
      sp.ng = tri_normal_[hit.prim];
      sp.ns = sp.ng;
      const int32_t patch = tri_patch_[hit.prim];
      if (patch >= 0) {
        const auto& nn = patch_normals_[static_cast<size_t>(patch)];
        const double w0 = 1.0 - hit.u - hit.v;
        const Vec3 ns = nn[0] * w0 + nn[1] * hit.u + nn[2] * hit.v;
        if (length(ns) > 0) sp.ns = normalize(ns);
      }
      break;
    }
    case PrimKind::sphere: obj = sphere_object_[hit.prim]; break;
    case PrimKind::cone: obj = cone_object_[hit.prim]; break;
  }
  sp.object = static_cast<int>(obj);
  sp.material = &materials_[object_material_[obj]];
  return sp;
}

}  // namespace holoray
