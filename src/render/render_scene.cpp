#include "render/render_scene.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "scene/tessellate.hpp"

namespace holoray {

RenderScene::RenderScene(const SceneDesc& desc) : RenderScene(std::vector<ScenePart>{{&desc, false}}) {}

namespace {

// A Tachyon sphere around the first viewpoint's eye: a sky dome (umr.dat
// wraps its scene in one of radius 2e6), background rather than scene. (NFF
// scenes keep their epsilon as it always was.)
// Bounds of everything but planes, lights' spheres and sky domes, and the
// first viewpoint's eye: the scale of the scene's precision, and what a
// plane's square must reach beyond. `left_out`: whether any object was
// left out (then these bounds, not the BVH's, set epsilon).
struct FiniteBounds {
  Bounds3 bounds;
  bool left_out = false;
};

FiniteBounds finite_bounds(const std::vector<ScenePart>& parts) {
  FiniteBounds f;
  std::optional<Vec3> eye;
  if (!parts.empty() && parts.front().desc->viewpoint) eye = parts.front().desc->viewpoint->from;
  for (const ScenePart& part : parts) {
    bool left_out = false;
    const Bounds3 b = finite_bounds(*part.desc, eye, &left_out);
    f.left_out |= left_out;
    if (!b.empty()) f.bounds.extend(b.lo), f.bounds.extend(b.hi);
  }
  if (eye) f.bounds.extend(*eye);
  return f;
}

// A vertex normal as the shading reads it. NFF's `pp` rule turns it into the
// winding hemisphere (nff-notes §9); Tachyon keeps it as written and turns
// the interpolated normal to the viewer exactly when the winding normal
// faces away (triangle.c, stri_normal), which frame_of() then does.
Vec3 vertex_normal(const Vec3& n, const Vec3& winding, ShadingModel shading) {
  if (shading == ShadingModel::nff) return shading_normal_in_hemisphere(n, winding);
  return length(n) > 0 ? normalize(n) : winding;
}

// A triangle's shading normals: its vertices' normals (`normals`, indexed
// by `t`) as the shading reads them (vertex_normal) beside its winding
// normal `n`.
std::array<Vec3, 3> patch_of(const std::vector<Vec3>& normals, const uint32_t t[3], const Vec3& n, ShadingModel shading) {
  return {vertex_normal(normals[t[0]], n, shading), vertex_normal(normals[t[1]], n, shading),
          vertex_normal(normals[t[2]], n, shading)};
}

// Texture units per world unit across a triangle of texture coordinates
// (u_k, v_k) and Newell normal `n`: sqrt(uv area / world area); |n| is twice
// the world area as the cross product below is twice the uv area.
float uv_per_world(const double u[3], const double v[3], const Vec3& n) {
  const double uv_area = std::fabs((u[1] - u[0]) * (v[2] - v[0]) - (u[2] - u[0]) * (v[1] - v[0]));
  return static_cast<float>(std::sqrt(uv_area / length(n)));
}

// Makes room for `size` elements at once, growing geometrically (a scene of
// many small polygons stays linear), so that a million-triangle mesh fills
// each per-triangle array once: grown by push_back, the arrays would be
// copied and first-touched about twice over, and fresh pages are dear.
template <class T>
void make_room(std::vector<T>& v, size_t size) {
  if (size > v.capacity()) v.reserve(std::max(size, 2 * v.capacity()));
}

// Appends vertices to a group's float positions; returns the first one's index.
uint32_t append_positions(const std::vector<Vec3>& vertices, TriangleData& tris) {
  const auto base = static_cast<uint32_t>(tris.positions.size() / 3);
  make_room(tris.positions, tris.positions.size() + 3 * vertices.size());
  for (const Vec3& v : vertices) {
    tris.positions.push_back(static_cast<float>(v.x));
    tris.positions.push_back(static_cast<float>(v.y));
    tris.positions.push_back(static_cast<float>(v.z));
  }
  return base;
}

double coordinate_scale(const Bounds3& b) {
  double scale = 1;
  if (!b.empty()) {
    for (int a = 0; a < 3; ++a) scale = std::fmax(scale, std::fmax(std::fabs(b.lo[a]), std::fabs(b.hi[a])));
    scale = std::fmax(scale, length(b.diagonal()));
  }
  return scale;
}

// A plane as a square centred on the point of the plane nearest the finite
// bounds' centre, reaching `half` each way: a central square as wide as the
// scene, then rings of eight cells each twice as wide as the last. Embree's
// float triangle test errs in proportion to a triangle's coordinates, so the
// triangles under the scene stay scene-sized (one square 1000 times the scene
// put shadow-ray hits 4e-4 off on smallballs); an axis-aligned plane's
// vertices keep its coordinate exactly in float.
TriangleMeshDesc plane_square(const PlaneDesc& p, const Bounds3& finite, double half) {
  const Vec3 n = normalize(p.normal);
  const Vec3 c0 = finite.empty() ? p.point : finite.centre();
  const Vec3 c = c0 - n * dot(c0 - p.point, n);
  const Frame f = Frame::from_normal_up(c, n, std::fabs(n.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0});
  const double inner = finite.empty() ? 1.0 : std::fmax(1e-6, length(finite.diagonal()));
  TriangleMeshDesc m;
  auto vertex = [&](double a, double b) {
    Vec3 v = c + f.x * a + f.y * b;
    if (std::fabs(n.x) == 1) v.x = p.point.x;
    if (std::fabs(n.y) == 1) v.y = p.point.y;
    if (std::fabs(n.z) == 1) v.z = p.point.z;
    m.vertices.push_back(v);
    return static_cast<uint32_t>(m.vertices.size() - 1);
  };
  auto cell = [&](double a0, double b0, double a1, double b1) {  // counter-clockwise about n
    const uint32_t v0 = vertex(a0, b0), v1 = vertex(a1, b0), v2 = vertex(a1, b1), v3 = vertex(a0, b1);
    m.triangles.push_back({v0, v1, v2});
    m.triangles.push_back({v0, v2, v3});
  };
  cell(-inner, -inner, inner, inner);
  for (double a = inner; a < half; a *= 2) {
    const double e[4] = {-2 * a, -a, a, 2 * a};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        if (i != 1 || j != 1) cell(e[i], e[j], e[i + 1], e[j + 1]);
  }
  return m;
}

}  // namespace

Bounds3 finite_bounds(const SceneDesc& desc, const std::optional<Vec3>& eye, bool* left_out) {
  Bounds3 b;
  bool out = false;
  for (const ObjectDesc& obj : desc.objects) {
    if (std::holds_alternative<PlaneDesc>(obj.shape)) {
      out = true;
    } else if (const auto* s = std::get_if<SphereDesc>(&obj.shape)) {
      const double r = std::fabs(s->radius);
      const bool dome = desc.shading == ShadingModel::tachyon && eye && length(*eye - s->centre) < r;
      if (!s->casts_shadow || dome) {  // a light's sphere, a sky: not the scene
        out = true;
        continue;
      }
      b.extend(s->centre - Vec3{r, r, r});
      b.extend(s->centre + Vec3{r, r, r});
    } else if (const auto* c = std::get_if<ConeDesc>(&obj.shape)) {
      const double r = std::fmax(std::fabs(c->base_radius), std::fabs(c->apex_radius));
      for (const Vec3& e : {c->base, c->apex}) b.extend(e - Vec3{r, r, r}), b.extend(e + Vec3{r, r, r});
    } else if (const auto* p = std::get_if<PolygonDesc>(&obj.shape)) {
      for (const Vec3& v : p->vertices) b.extend(v);
    } else if (const auto* m = std::get_if<TriangleMeshDesc>(&obj.shape)) {
      for (const Vec3& v : m->vertices) b.extend(v);
    }
  }
  if (left_out) *left_out = out;
  return b;
}

RenderScene::RenderScene(const std::vector<ScenePart>& parts) {
  materials_.push_back(Material{});  // grey diffuse for objects before the first `f` (nff-notes §1)
  std::vector<GeometryGroup> groups;
  // NFF's ambient and per-light intensity come from the count of NFF lights
  // (nff-notes §4); Tachyon lights shine with their colour as written.
  // A reader's stand-in light (Light::headlight) only where no file has a
  // light, and one at most: a shot of several mesh files is lit once.
  const Light* kept_headlight = nullptr;
  bool own_lights = false;
  for (const ScenePart& part : parts) {
    own_lights |= !part.desc->area_lights.empty();
    for (const Light& l : part.desc->lights) {
      own_lights |= !l.headlight;
      if (l.headlight && !kept_headlight) kept_headlight = &l;
    }
  }
  if (own_lights) kept_headlight = nullptr;
  auto keep = [&](const Light& l) { return !l.headlight || &l == kept_headlight; };
  size_t light_count = 0;
  for (const ScenePart& part : parts)
    for (const Light& l : part.desc->lights)
      if (keep(l) && part.desc->shading == ShadingModel::nff && !l.photometric) ++light_count;
  const double level = 1.0 / (2.0 * std::sqrt(static_cast<double>(std::max<size_t>(1, light_count))));
  ambient_ = Vec3{level, level, level};
  if (!parts.empty()) background_ = parts.front().desc->background;
  if (!parts.empty() && parts.front().desc->max_depth) file_max_depth_ = *parts.front().desc->max_depth;
  if (!parts.empty()) fog_ = parts.front().desc->fog;
  // Tachyon fogs what a ray misses as if it were infinitely far: the fog's
  // colour, unless an exponential fog has no density.
  if (fog_ && !(fog_->mode != FogDesc::Mode::linear && fog_->density <= 0)) background_ = fog_->colour;
  const FiniteBounds fb = finite_bounds(parts);
  const Bounds3& finite = fb.bounds;
  const double plane_half = 1000 * coordinate_scale(finite);
  if (fb.left_out) finite_scale_ = coordinate_scale(finite);

  for (const ScenePart& part : parts) {
    const SceneDesc& desc = *part.desc;
    const auto material_base = static_cast<uint32_t>(materials_.size());
    const auto texture_base = static_cast<int>(textures_.size());
    const auto image_base = static_cast<int>(mips_.size());
    for (Material m : desc.materials) {
      // Every texture index of the file, rebased onto the scene's list.
      for (int* index : {&m.texture, &m.emission_texture, &m.metal_rough_texture, &m.normal_texture, &m.alpha_texture,
                         &m.specular_texture})
        if (*index >= 0) *index += texture_base;
      has_tachyon_ |= m.model == ShadingModel::tachyon;
      only_plain_nff_ &= m.model == ShadingModel::nff && m.texture < 0 && m.emission_texture < 0 &&
                         m.metal_rough_texture < 0 && m.normal_texture < 0 && m.alpha_texture < 0 &&
                         m.specular_texture < 0;
      has_tachyon_transparency_ |= m.model == ShadingModel::tachyon && m.transmittance > 0;
      materials_.push_back(m);
    }
    for (TextureDesc t : desc.textures) {
      if (t.image >= 0) t.image += image_base;
      textures_.push_back(t);
    }
    for (const ImageMap& img : desc.images) mips_.emplace_back(img);
    for (const Light& l : desc.lights)
      if (keep(l)) {
        const double intensity = desc.shading == ShadingModel::nff && !l.photometric ? level : 1.0;
        const bool unit = l.kind == LightKind::point && l.kc == 1 && l.kl == 0 && l.kq == 0 && !(l.range > 0);
        lights_.push_back({l.position, l.colour * intensity, l.kind, l.direction, l.kc, l.kl, l.kq, l.fall_start,
                           l.fall_end, l.smooth_cone, l.range, unit, l.headlight, std::cos(l.fall_start), std::cos(l.fall_end),
                           l.radius, std::cos(l.angle / 2)});
      }
    for (const AreaLightDesc& a : desc.area_lights)
      area_lights_.push_back({a.centre, a.axis_u, a.axis_v, a.normal, a.ellipse, a.radiance,
                              (a.ellipse ? M_PI : 4.0) * length(a.axis_u) * length(a.axis_v)});
    group_base_.push_back({static_cast<uint32_t>(tri_object_.size()), static_cast<uint32_t>(sphere_object_.size()),
                           static_cast<uint32_t>(cone_object_.size())});
    group_shading_.push_back(desc.shading);
    GeometryGroup& geo = groups.emplace_back();
    geo.movable = part.movable || part.deformable;
    geo.deformable = part.deformable;
    TriangleData& tris = geo.triangles;
    for (size_t oi = 0; oi < desc.objects.size(); ++oi) {
      const ObjectDesc& obj = desc.objects[oi];
      // Objects before any `f` (material -1) take the default, materials_[0].
      object_material_.push_back(obj.material < 0 ? 0 : material_base + static_cast<uint32_t>(obj.material));
      const auto id = static_cast<uint32_t>(object_material_.size() - 1);
      if (const auto* s = std::get_if<SphereDesc>(&obj.shape)) {
        geo.spheres.push_back({s->centre, s->radius, s->casts_shadow});
        sphere_object_.push_back(id);
      } else if (const auto* c = std::get_if<ConeDesc>(&obj.shape)) {
        geo.cones.push_back({c->base, c->apex, c->base_radius, c->apex_radius});
        cone_object_.push_back(id);
      } else if (const auto* plane = std::get_if<PlaneDesc>(&obj.shape)) {
        add_mesh(plane_square(*plane, finite, plane_half), id, desc.shading, tris);
      } else if (const auto* mesh = std::get_if<TriangleMeshDesc>(&obj.shape)) {
        add_mesh(*mesh, id, desc.shading, tris);
      } else {
        const auto& poly = std::get<PolygonDesc>(obj.shape);
        const Tessellation tess = tessellate_polygon(poly.vertices);
        if (tess.triangles.empty()) {
          ++skipped_polygons_;
          continue;
        }
        const uint32_t base = append_positions(poly.vertices, tris);
        for (const auto& t : tess.triangles) {
          for (int k : t) tris.indices.push_back(base + static_cast<uint32_t>(k));
          tri_object_.push_back(id);
          tri_normal_.push_back(tess.normal);
          if (poly.normals.empty()) {
            tri_patch_.push_back(-1);
          } else {
            tri_patch_.push_back(static_cast<int32_t>(patch_normals_.size()));
            patch_normals_.push_back({vertex_normal(poly.normals[t[0]], tess.normal, desc.shading),
                                      vertex_normal(poly.normals[t[1]], tess.normal, desc.shading),
                                      vertex_normal(poly.normals[t[2]], tess.normal, desc.shading)});
          }
        }
      }
    }
  }
  // Groups with alpha-masked materials get the cutout (Embree filters their triangles' hits).
  for (size_t gi = 0; gi < groups.size(); ++gi) {
    const uint32_t first = group_base_[gi][0];
    const uint32_t last = gi + 1 < group_base_.size() ? group_base_[gi + 1][0] : static_cast<uint32_t>(tri_object_.size());
    for (uint32_t t = first; t < last; ++t)
      if (materials_[object_material_[tri_object_[t]]].alpha_mask) {
        groups[gi].cutout = &cutout_;
        break;
      }
  }
  accel_ = std::make_unique<AccelScene>(std::move(groups));
  update_epsilon();
}

void RenderScene::set_transforms(const std::vector<Affine>& object_to_world) {
  accel_->set_transforms(object_to_world);
  update_epsilon();
}

void RenderScene::set_vertices(uint32_t part, const std::vector<Vec3>& vertices, const std::vector<Vec3>& normals,
                               uint64_t pose) {
  const AccelScene& accel = *accel_;
  if (part >= accel.group_count() || !accel.geometry(part).deformable)
    throw std::invalid_argument(fmt::format("scene part {} was not built deformable", part));
  const TriangleData& tris = accel.geometry(part).triangles;
  if (vertices.size() * 3 != tris.positions.size() || (!normals.empty() && normals.size() != vertices.size()))
    throw std::invalid_argument(fmt::format("scene part {} has {} vertices, got {} and {} normals", part,
                                            tris.positions.size() / 3, vertices.size(), normals.size()));
  std::vector<float> positions;
  positions.reserve(3 * vertices.size());
  for (const Vec3& v : vertices)
    positions.insert(positions.end(), {static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z)});
  // The same vertices (a held pose: the animation over, or not moving this
  // part): nothing changes, and the pose keeps its tag, so reuse still
  // takes the part as standing still.
  if (positions == tris.positions) return;
  // The triangles as add_mesh() built them, in the group's order.
  const uint32_t first = group_base_[part][0];
  for (size_t k = 0; k < tris.indices.size() / 3; ++k) {
    const size_t t = first + k;
    const uint32_t* idx = &tris.indices[3 * k];
    const std::array<Vec3, 3> corners{vertices[idx[0]], vertices[idx[1]], vertices[idx[2]]};
    const Vec3 n = polygon_normal(corners);
    if (!(length(n) > 0)) continue;  // collapsed this frame: Embree cannot hit it; keep the last normal
    tri_normal_[t] = n;
    if (tri_patch_[t] >= 0 && !normals.empty())
      patch_normals_[static_cast<size_t>(tri_patch_[t])] = patch_of(normals, idx, n, group_shading_[part]);
    if (t < tri_uv_.size() && tri_uv_[t] >= 0) {
      TriangleUv& tu = tri_uvs_[static_cast<size_t>(tri_uv_[t])];
      const double u[3] = {tu.uv[0][0], tu.uv[1][0], tu.uv[2][0]}, v[3] = {tu.uv[0][1], tu.uv[1][1], tu.uv[2][1]};
      tu.uv_per_world = uv_per_world(u, v, n);
    }
  }
  accel_->set_positions(part, positions, pose);
  update_epsilon();
}

void RenderScene::add_mesh(const TriangleMeshDesc& mesh, uint32_t id, ShadingModel shading, TriangleData& tris) {
  const uint32_t base = append_positions(mesh.vertices, tris);
  const size_t total = tri_object_.size() + mesh.triangles.size();  // the scene's triangles with this mesh
  make_room(tris.indices, tris.indices.size() + 3 * mesh.triangles.size());
  make_room(tri_object_, total);
  make_room(tri_normal_, total);
  make_room(tri_patch_, total);
  if (!mesh.normals.empty()) make_room(patch_normals_, patch_normals_.size() + mesh.triangles.size());
  if (!mesh.uvs.empty()) {
    make_room(tri_uv_, total);
    make_room(tri_uvs_, tri_uvs_.size() + mesh.triangles.size());
  }
  if (!mesh.colours.empty()) {
    make_room(tri_colour_, total);
    make_room(tri_colours_, tri_colours_.size() + mesh.triangles.size());
  }
  for (const auto& t : mesh.triangles) {
    // The Newell normal, as a `p` polygon of the same three vertices gets it.
    const std::array<Vec3, 3> corners{mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]};
    const Vec3 n = polygon_normal(corners);
    if (!(length(n) > 0)) {
      ++skipped_polygons_;
      continue;
    }
    for (uint32_t k : t) tris.indices.push_back(base + k);
    if (!mesh.uvs.empty()) {
      tri_uv_.resize(tri_object_.size(), -1);
      tri_uv_.push_back(static_cast<int32_t>(tri_uvs_.size()));
      TriangleUv tu;
      for (int c = 0; c < 3; ++c)
        tu.uv[c] = {static_cast<float>(mesh.uvs[t[c]][0]), static_cast<float>(mesh.uvs[t[c]][1])};
      const double u[3] = {mesh.uvs[t[0]][0], mesh.uvs[t[1]][0], mesh.uvs[t[2]][0]};
      const double v[3] = {mesh.uvs[t[0]][1], mesh.uvs[t[1]][1], mesh.uvs[t[2]][1]};
      tu.uv_per_world = uv_per_world(u, v, n);
      tri_uvs_.push_back(tu);
    }
    if (!mesh.colours.empty()) {
      tri_colour_.resize(tri_object_.size(), -1);
      tri_colour_.push_back(static_cast<int32_t>(tri_colours_.size()));
      tri_colours_.push_back({mesh.colours[t[0]], mesh.colours[t[1]], mesh.colours[t[2]]});
    }
    tri_object_.push_back(id);
    tri_normal_.push_back(n);
    if (mesh.normals.empty()) {
      tri_patch_.push_back(-1);
    } else {
      tri_patch_.push_back(static_cast<int32_t>(patch_normals_.size()));
      patch_normals_.push_back(patch_of(mesh.normals, t.data(), n, shading));
    }
  }
}

void RenderScene::update_epsilon() {
  // A plane's square is a thousand times the scene, and a Tachyon light's
  // sphere may sit far out: neither says anything of the precision the rest
  // of the scene needs.
  const double scale = finite_scale_ > 0 ? finite_scale_ : coordinate_scale(accel_->bounds());
  // Float geometry is exact to ~6e-8 of its coordinates; stay well clear of that.
  epsilon_ = 1e-5 * scale;
}

}  // namespace holoray
