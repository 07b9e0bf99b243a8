#include "render/render_scene.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "reuse/shadow_cache.hpp"
#include "scene/tessellate.hpp"

namespace holoray {

RenderScene::RenderScene(const SceneDesc& desc) : RenderScene(std::vector<ScenePart>{{&desc, false}}) {}

RenderScene::RenderScene(const std::vector<ScenePart>& parts) {
  materials_.push_back(Material{});  // grey diffuse for objects before the first `f` (nff-notes §1)
  std::vector<GeometryGroup> groups;
  size_t light_count = 0;
  for (const ScenePart& part : parts) light_count += part.desc->lights.size();
  const double level = 1.0 / (2.0 * std::sqrt(static_cast<double>(std::max<size_t>(1, light_count))));
  ambient_ = Vec3{level, level, level};
  if (!parts.empty()) background_ = parts.front().desc->background;

  for (const ScenePart& part : parts) {
    const SceneDesc& desc = *part.desc;
    const auto material_base = static_cast<uint32_t>(materials_.size());
    materials_.insert(materials_.end(), desc.materials.begin(), desc.materials.end());
    for (const Light& l : desc.lights) lights_.push_back({l.position, l.colour * level});
    group_base_.push_back({static_cast<uint32_t>(tri_object_.size()), static_cast<uint32_t>(sphere_object_.size()),
                           static_cast<uint32_t>(cone_object_.size())});
    GeometryGroup& geo = groups.emplace_back();
    geo.movable = part.movable;
    TriangleData& tris = geo.triangles;
    for (size_t oi = 0; oi < desc.objects.size(); ++oi) {
      const ObjectDesc& obj = desc.objects[oi];
      // Objects before any `f` (material -1) take the default, materials_[0].
      object_material_.push_back(obj.material < 0 ? 0 : material_base + static_cast<uint32_t>(obj.material));
      const auto id = static_cast<uint32_t>(object_material_.size() - 1);
      if (const auto* s = std::get_if<SphereDesc>(&obj.shape)) {
        geo.spheres.push_back({s->centre, s->radius});
        sphere_object_.push_back(id);
      } else if (const auto* c = std::get_if<ConeDesc>(&obj.shape)) {
        geo.cones.push_back({c->base, c->apex, c->base_radius, c->apex_radius});
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
  }
  accel_ = std::make_unique<AccelScene>(std::move(groups));
  update_epsilon();
}

void RenderScene::set_transforms(const std::vector<Affine>& object_to_world) {
  accel_->set_transforms(object_to_world);
  update_epsilon();
  if (shadow_cache_) shadow_cache_->sync();
}

void RenderScene::set_max_depth(int depth) {
  if (depth < 1 || depth > kDepthCap)
    throw std::invalid_argument(fmt::format("the ray depth must be from 1 to {}, got {}", kDepthCap, depth));
  max_depth_ = depth;
}

void RenderScene::update_epsilon() {
  const Bounds3& b = accel_->bounds();
  double scale = 1;
  if (!b.empty()) {
    for (int a = 0; a < 3; ++a) scale = std::fmax(scale, std::fmax(std::fabs(b.lo[a]), std::fabs(b.hi[a])));
    scale = std::fmax(scale, length(b.diagonal()));
  }
  // Float geometry is exact to ~6e-8 of its coordinates; stay well clear of that.
  epsilon_ = 1e-5 * scale;
}

int RenderScene::object_of(uint32_t group, PrimKind kind, uint32_t prim) const {
  const auto& base = group_base_[group];
  switch (kind) {
    case PrimKind::triangle: return static_cast<int>(tri_object_[base[0] + prim]);
    case PrimKind::sphere: return static_cast<int>(sphere_object_[base[1] + prim]);
    case PrimKind::cone: return static_cast<int>(cone_object_[base[2] + prim]);
  }
  return -1;
}

SurfacePoint RenderScene::surface(const Ray& ray, const Hit& hit) const {
  SurfacePoint sp;
  sp.position = ray.org + ray.dir * hit.t;
  sp.ng = hit.ng;
  sp.ns = hit.ng;
  const auto& base = group_base_[hit.group];
  uint32_t obj = 0;
  switch (hit.kind) {
    case PrimKind::triangle: {
      const uint32_t t = base[0] + hit.prim;
      obj = tri_object_[t];
      // The Newell normal of the whole polygon (object space), like the winding the file gave.
      const Affine& xf = accel_->transform(hit.group);
      const bool moved = !xf.is_identity();
      sp.ng = moved ? xf.normal(tri_normal_[t]) : tri_normal_[t];
      sp.ns = sp.ng;
      const int32_t patch = tri_patch_[t];
      if (patch >= 0) {
        const auto& nn = patch_normals_[static_cast<size_t>(patch)];
        const double w0 = 1.0 - hit.u - hit.v;
        const Vec3 ns = nn[0] * w0 + nn[1] * hit.u + nn[2] * hit.v;
        if (length(ns) > 0) sp.ns = moved ? xf.normal(ns) : normalize(ns);
      }
      break;
    }
    case PrimKind::sphere: obj = sphere_object_[base[1] + hit.prim]; break;
    case PrimKind::cone: obj = cone_object_[base[2] + hit.prim]; break;
  }
  sp.group = hit.group;
  sp.prim = hit.prim;
  sp.kind = hit.kind;
  sp.u = static_cast<float>(hit.u);
  sp.v = static_cast<float>(hit.v);
  sp.object = static_cast<int>(obj);
  sp.material = &materials_[object_material_[obj]];
  return sp;
}

}  // namespace holoray
