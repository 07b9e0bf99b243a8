// holoray/render: the scene as the renderer needs it, built once from one or
// more SceneDescs (architecture.md: "build" step); afterwards only the
// per-frame object transforms change (set_transforms, between frames).
// Polygons are tessellated, `pp` normals flipped into the winding hemisphere,
// lights given the SPD intensities (nff-notes §4), materials resolved.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "accel/accel_scene.hpp"
#include "render/textures.hpp"
#include "scene/scene_desc.hpp"

namespace holoray {

/// Default ray-tree depth limit, counting the eye ray as depth 1 (nff-notes
/// §10.7), and the most RenderSettings::max_depth may be.
inline constexpr int kMaxRayDepth = 5;
inline constexpr int kDepthCap = 16;

/// A light ready for shading: position (world) and RGB intensity, the
/// radiance a white Lambertian surface facing it shows at unit falloff
/// (docs/lights.md); the kind, attenuation, spot cone and range of Tachyon
/// and glTF lights (scene_desc.hpp, Light). NFF lights are points without
/// falloff.
struct PointLight {
  Vec3 position;
  Vec3 intensity;
  LightKind kind = LightKind::point;
  Vec3 direction{0, 0, -1};
  double kc = 1, kl = 0, kq = 0;
  double fall_start = 0, fall_end = 0;
  bool smooth_cone = false;
  double range = 0;
  /// A point light whose intensity reaches every point whole (NFF's): the
  /// shading skips the falloff.
  bool unit_falloff = true;
  /// A reader's stand-in light at the eye (Light::headlight): the path
  /// integrator leaves it out where the render gives its own light.
  bool headlight = false;
  /// cos(fall_start) and cos(fall_end), computed once where the light is
  /// built (RenderScene), not once per shadow ray.
  double cos_fall_start = 1, cos_fall_end = 1;
  /// Light::radius (point, spot) and the cosine of half Light::angle
  /// (directional): the path integrator's soft lights.
  double radius = 0, cos_half_angle = 1;
};

/// An area light ready for the path integrator (scene_desc.hpp,
/// AreaLightDesc): world frame; `area` its emitting area.
struct AreaLight {
  Vec3 centre, axis_u, axis_v, normal;
  bool ellipse = false;
  Vec3 radiance;
  double area = 0;
};

/// Where a ray met a surface, resolved for shading.
struct SurfacePoint {
  Vec3 position;    ///< world
  Vec3 ng;          ///< unit geometric normal: outward (sphere, cone) or winding (polygon)
  Vec3 ns;          ///< unit shading normal, in the same hemisphere as ng
  int object = -1;  ///< object id: index in file order, files numbered one after another
  PrimKind kind = PrimKind::triangle;  ///< (beside `object`: the record stays 136 bytes)
  const Material* material = nullptr;
  /// The surface colour C of NFF's formula (glTF's base colour; the albedo
  /// AOV is albedo_of(), below): the
  /// material's colour, times its image texture at the hit's texture
  /// coordinates for a textured mesh material (RenderScene::surface).
  /// Tachyon materials: their constant colour (their texfuncs are looked up
  /// by the shading, at the path's optical distance).
  Vec3 colour;
  // The primitive hit and its barycentrics (Hit's), for the surface cells of
  // reuse/. Kept small: every hit carries them, cache or not.
  uint32_t group = 0, prim = 0;
  float u = 0, v = 0;  ///< triangle barycentrics (a cell index needs no more)
  /// glTF materials: metallic and roughness here, the material's factors
  /// times its metallic-roughness texture (Material::metal_rough_texture).
  /// blinn_phong materials: `highlight` in place of metallic, the weight
  /// of Material::specular there (its map_Ks texel, else 1).
  union {
    float metallic = 0;
    float highlight;
  };
  float roughness = 1;
};

/// The albedo AOV at a hit (linear RGB): the surface colour C; for a glTF
/// material its diffuse part, C (1 - metallic) (1 - transmission)
/// (Appendix B's c_diff at F = 0, what Blender's DiffCol pass holds; a
/// metal's colour is specular, a transmitting one's passes through).
inline Vec3 albedo_of(const SurfacePoint& sp) {
  if (sp.material->model == ShadingModel::gltf)
    return sp.colour * ((1 - static_cast<double>(sp.metallic)) * (1 - sp.material->transmission));
  return sp.colour;
}

/// One scene file of a shot: its description and whether it ever moves
/// (rigidly: set_transforms) or deforms (its mesh vertices: set_vertices).
struct ScenePart {
  const SceneDesc* desc = nullptr;
  bool movable = false;
  bool deformable = false;
};

/// The bounds (the file's object space) of what `desc` holds, leaving out
/// what is not "the scene" for precision and framing: planes (infinite),
/// lights' spheres (unshadowed) and, when `eye` is given, Tachyon sky domes
/// (spheres enclosing the eye). `left_out` (optional) tells whether
/// anything was left out. Empty when nothing remains.
Bounds3 finite_bounds(const SceneDesc& desc, const std::optional<Vec3>& eye, bool* left_out = nullptr);

/// The width (world units) of the patch a pixel sees at distance d along
/// its eye ray: base + spread * d. It chooses a mesh texture's MIP level
/// (footprint in texels, MipMap::sample_uv). A pinhole pixel: base 0,
/// spread its angle; an EIA pixel: its angle through the lens (pixel pitch
/// / gap), far wider. 0, 0: the finest level everywhere. Secondary rays use
/// the distance from their own origin (sharper than their true footprint).
struct PixelFootprint {
  double base = 0, spread = 0;
  double at(double distance) const { return base + spread * distance; }
};

/// A built scene: geometry, lights, materials and textures, shared by every
/// render and camera that reads it (render_context.hpp holds what one render
/// adds: depth, shadow cache, pixel footprint, background). Only the per-
/// frame motion (set_transforms, set_vertices) changes it, between renders.
class RenderScene {
 public:
  // Embree keeps a pointer to the scene's alpha cutout (accel_scene.hpp): not movable.
  RenderScene(RenderScene&&) = delete;
  RenderScene& operator=(RenderScene&&) = delete;
  /// A still scene. Throws std::runtime_error if Embree fails.
  explicit RenderScene(const SceneDesc& desc);
  /// Several scene files in one world (object ids continue from file to file;
  /// lights of all files, ambient from their total count; the first file's
  /// background). Transforms start as the identity.
  explicit RenderScene(const std::vector<ScenePart>& parts);

  /// Object-to-world transform per part for the frames that follow (paper
  /// §3); a shadow cache on the scene is then stale until its sync(). Not
  /// thread-safe against rendering. Throws std::invalid_argument as
  /// AccelScene::set_transforms does.
  void set_transforms(const std::vector<Affine>& object_to_world);
  /// New vertices (object space) and vertex normals for a deformable part
  /// (ScenePart::deformable; a skinned mesh posed for the next frame), in
  /// the order of its meshes' vertices, tagged `pose` (AccelScene::pose: a
  /// frame, not 0); `normals` empty keeps the flat triangles flat. Winding
  /// normals, shading normals and texture footprints follow; the BVH is
  /// refitted (a shadow cache is stale until its sync()). Not thread-safe against
  /// rendering. Vertices equal to the current ones change nothing (the
  /// pose keeps its earlier tag). Throws std::invalid_argument when the
  /// part is not deformable or a count differs from its build.
  void set_vertices(uint32_t part, const std::vector<Vec3>& vertices, const std::vector<Vec3>& normals, uint64_t pose);
  /// The scene file's ray-tree depth limit (eye ray = 1): the first file's
  /// own (Tachyon's `raydepth`), else kMaxRayDepth = 5, the SPD's.
  int file_max_depth() const { return file_max_depth_; }

  const AccelScene& accel() const { return *accel_; }
  /// Resolves a hit of `ray` (world) into position, normals, object and
  /// material; textures read at the MIP level of `footprint`.
  SurfacePoint surface(const Ray& ray, const Hit& hit, const PixelFootprint& footprint) const;

  const std::vector<PointLight>& lights() const { return lights_; }
  /// Every file's area lights (lights files): the path integrator's.
  const std::vector<AreaLight>& area_lights() const { return area_lights_; }
  /// The surface colour at a hit: its triangle's vertex colours
  /// interpolated (Tachyon vcstri), else its material's texture (Tachyon
  /// texfunc, render/textures.hpp) seen at `optic_dist` from the eye, else
  /// the material's colour.
  Vec3 surface_colour(const SurfacePoint& sp, double optic_dist) const;
  /// Whether any material follows Tachyon's shading (visibility reuse, which
  /// splits NFF's formula, then does not apply).
  bool has_tachyon_materials() const { return has_tachyon_; }
  /// Whether a Tachyon material lets light through (opacity < 1): then
  /// Tachyon's shadow rays are filtered through it instead of blocked.
  bool has_tachyon_transparency() const { return has_tachyon_transparency_; }
  /// Whether every material is NFF's without a texture: then nothing in the
  /// shading of a secondary hit reads more than its point and normal to
  /// float precision, and secondary rays take Embree's hits unrefined.
  bool only_plain_nff() const { return only_plain_nff_; }
  /// Light a mesh surface gives off at `sp`, seen from `distance` along
  /// the ray (Material::emission times its texture); zero for most.
  Vec3 emission(const SurfacePoint& sp, double distance, const PixelFootprint& footprint) const;
  const Vec3& ambient() const { return ambient_; }      ///< Ia (nff-notes §4: 1/(2 sqrt(n)))
  /// The scene file's background (the first file's; its fog colour under fog).
  const Vec3& background() const { return background_; }
  /// The first scene file's Tachyon fog, if any (applied by Tachyon shading).
  const std::optional<FogDesc>& fog() const { return fog_; }
  /// Geometry bounds (world); empty for a scene with no geometry.
  const Bounds3& bounds() const { return accel_->bounds(); }
  /// Offset for spawning secondary rays, relative to the scene's coordinate scale.
  double epsilon() const { return epsilon_; }
  /// Polygons with no area (all vertices collinear or repeated), skipped.
  size_t skipped_polygons() const { return skipped_polygons_; }
  size_t object_count() const { return object_material_.size(); }
  /// Object id of a primitive (as in SurfacePoint::object).
  int object_of(uint32_t group, PrimKind kind, uint32_t prim) const;

  // What another executor (the GPU path, src/gpu/) reads to lay the scene
  // out in its own arrays; the CPU path reads these through surface().
  /// The resolved materials, and which one each object wears.
  const std::vector<Material>& materials() const { return materials_; }
  /// The textures (Material::texture indexes them) and their image maps'
  /// MIP levels (TextureDesc::image indexes these).
  const std::vector<TextureDesc>& textures() const { return textures_; }
  const std::vector<MipMap>& mips() const { return mips_; }
  uint32_t material_of_object(int object) const { return object_material_[static_cast<size_t>(object)]; }
  /// A triangle's winding normal (object space of its group, unit).
  const Vec3& winding_normal(uint32_t group, uint32_t prim) const { return tri_normal_[group_base_[group][0] + prim]; }
  /// A smooth triangle's vertex normals (object space), null for a flat one.
  const std::array<Vec3, 3>* vertex_normals(uint32_t group, uint32_t prim) const {
    const int32_t p = tri_patch_[group_base_[group][0] + prim];
    return p >= 0 ? &patch_normals_[static_cast<size_t>(p)] : nullptr;
  }
  /// Whether any triangle carries vertex colours (Tachyon vcstri).
  bool has_vertex_colours() const { return !tri_colours_.empty(); }
  /// A triangle's texture coordinates (its vertices' u, v; v up) and its
  /// texture units per world unit; false for a triangle without.
  bool triangle_uv(uint32_t group, uint32_t prim, std::array<std::array<float, 2>, 3>& uv, float& uv_per_world) const {
    const size_t t = group_base_[group][0] + prim;
    if (t >= tri_uv_.size() || tri_uv_[t] < 0) return false;
    const TriangleUv& tu = tri_uvs_[static_cast<size_t>(tri_uv_[t])];
    uv = tu.uv, uv_per_world = tu.uv_per_world;
    return true;
  }
  /// A triangle's vertex colours (linear RGB), null for one without.
  const std::array<Vec3, 3>* vertex_colours(uint32_t group, uint32_t prim) const {
    const size_t t = group_base_[group][0] + prim;
    return t < tri_colour_.size() && tri_colour_[t] >= 0 ? &tri_colours_[static_cast<size_t>(tri_colour_[t])] : nullptr;
  }

 private:
  void update_epsilon();
  /// Appends a triangle mesh (one object, id `id`) to a group's triangles.
  void add_mesh(const TriangleMeshDesc& mesh, uint32_t id, ShadingModel shading, TriangleData& tris);

  int file_max_depth_ = kMaxRayDepth;
  std::unique_ptr<AccelScene> accel_;
  std::vector<Material> materials_;        // [0] is the default for objects before any `f`
  std::vector<uint32_t> object_material_;  // per object
  std::vector<uint32_t> tri_object_, sphere_object_, cone_object_;
  std::vector<std::array<uint32_t, 3>> group_base_;  // per group: first triangle, sphere, cone in the arrays
  std::vector<ShadingModel> group_shading_;          // per group: its file's (the vertex normal rule)
  std::vector<Vec3> tri_normal_;                 // winding normal per triangle
  std::vector<int32_t> tri_patch_;               // index into patch_normals_, -1 for flat `p`
  std::vector<std::array<Vec3, 3>> patch_normals_;
  // Per triangle, an index into tri_colours_ or -1; sized only once a
  // vertex-coloured mesh is added (shorter: the rest have none).
  std::vector<int32_t> tri_colour_;
  std::vector<std::array<Vec3, 3>> tri_colours_;
  // Per triangle, an index into tri_uvs_ or -1; sized only once a mesh with
  // texture coordinates is added.
  struct TriangleUv {
    std::array<std::array<float, 2>, 3> uv;
    float uv_per_world = 0;  // sqrt(uv area / world area): texture units per world unit across it
  };
  std::vector<int32_t> tri_uv_;
  std::vector<TriangleUv> tri_uvs_;
  /// Alpha-masked mesh materials (Material::alpha_mask) as Embree's cutout.
  class AlphaCutout final : public TriangleCutout {
   public:
    explicit AlphaCutout(const RenderScene& s) : s_(s) {}
    bool cut(uint32_t group, uint32_t prim, float u, float v) const override;

   private:
    const RenderScene& s_;
  };
  AlphaCutout cutout_{*this};
  /// The texture coordinates a hit's image reads (TextureDesc::uv_transform
  /// applied), and the triangle's record; null when the triangle has none.
  const TriangleUv* texture_uv(const TextureDesc& tex, size_t triangle, double u, double v, double& tu, double& tv) const;
  /// SurfacePoint::colour of a hit whose pixel footprint there is `width` (world units).
  Vec3 textured_colour(const SurfacePoint& sp, double u, double v, double width) const;
  /// A glTF material's metallic and roughness at a triangle hit
  /// (Material::metal_rough_texture), a blinn_phong one's highlight weight
  /// (Material::specular_texture).
  void apply_data_maps(SurfacePoint& sp, double width) const;
  /// The shading normal bent by the material's normal map at a triangle
  /// hit (Material::normal_texture), in the triangle's tangent frame.
  void apply_normal_map(SurfacePoint& sp, double width) const;
  /// Texture `texture` (a uv_image) at the hit's coordinates, its MIP level
  /// from a pixel footprint `width` wide (world units); false when it cannot be read there.
  bool texel_at(int texture, const SurfacePoint& sp, double u, double v, double width, Vec3& out) const;
  std::vector<PointLight> lights_;
  std::vector<AreaLight> area_lights_;
  std::vector<TextureDesc> textures_;  // every file's, Material::texture rebased
  std::vector<MipMap> mips_;           // every file's image maps, TextureDesc::image rebased
  bool has_tachyon_ = false, has_tachyon_transparency_ = false, only_plain_nff_ = true;
  std::optional<FogDesc> fog_;
  double finite_scale_ = 0;  // epsilon's scale without planes and lights' spheres (0: the scene has neither)
  Vec3 ambient_, background_;
  double epsilon_ = 1e-6;
  size_t skipped_polygons_ = 0;
};

}  // namespace holoray
