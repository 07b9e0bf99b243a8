// holoray/scene: the scene description as plain structs, exactly what a file
// said, before any rendering object is built (architecture.md: "Parsing never
// builds render objects"). Every item keeps the source location it came from.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "math/vec.hpp"

namespace holoray {

/// 1-based line and column in the scene file; 0 when the item was made in code.
struct SourceLoc {
  int line = 0;
  int col = 0;
};

/// NFF `v` (nff-notes §2), or a Tachyon camera turned into one
/// (docs/tachyon-notes.md §2). World units; `up` as written (not orthogonalised).
struct Viewpoint {
  Vec3 from, at, up;
  double angle_deg = 45;   // full-image field of view across `fov_axis` (NFF: vertical, nff-notes §2)
  double hither = 0;       // read and kept; the integral camera ignores it (see README)
  int xres = 0, yres = 0;  // 0 when the file gives no `resolution`
  /// Tachyon's screen: right = up x view (NFF's is view x up), so an image of
  /// the same world comes out mirrored left to right (tachyon-notes §2).
  bool mirrored = false;
  SourceLoc loc;
  /// The image side `angle_deg` (or `ortho_size`) spans: NFF, Tachyon and
  /// glTF (`yfov`) give the vertical angle; Collada's `xfov`, FBX, 3DS and
  /// ASE the horizontal one; a Blender camera's sensor fit "auto" the
  /// larger side (docs/guide/scenes.md, "File cameras").
  enum class FovAxis { vertical, horizontal, larger };
  FovAxis fov_axis = FovAxis::vertical;
  /// An orthographic camera's full extent across `fov_axis`, scene units
  /// (glTF 2.0 §5.13: 2 ymag); 0: a perspective camera.
  double ortho_size = 0;
  /// Where `at` comes from. A file camera (mesh files) has a direction but
  /// no point looked at: the point is placed at `focus_distance` along it,
  /// the depth of the scene's bounding-box centre (mesh_reader.cpp).
  enum class Focus { look_at, scene_centre_depth, option };
  Focus focus = Focus::look_at;
  std::string camera;      // a mesh file's camera name ("" for NFF, Tachyon, a viewpoint made in code)
  /// A file camera's clipping range, distances along its axis: what a
  /// pinhole view through it shows, as the file's own tools show it. The
  /// lens array ignores it (each lens is its own camera), and so does
  /// everything for NFF's `hither`.
  double clip_near = 0, clip_far = INFINITY;

  /// The full vertical angle, degrees, of a `width` x `height` image
  /// (square pixels) whose `fov_axis` side spans `angle_deg`.
  double vertical_angle_deg(int width, int height) const;
  /// The full vertical extent of such an orthographic image (ortho_size > 0).
  double vertical_ortho_size(int width, int height) const;
  /// The same viewpoint, `at` moved to `distance` along from -> at
  /// (focus = option). Throws std::invalid_argument unless distance > 0 and finite.
  Viewpoint focused_at(double distance) const;
};

/// How a light falls off; NFF lights are all `point` with no attenuation.
enum class LightKind { point, directional, spot };

/// NFF `l`: point light, no falloff, never visible to eye rays (nff-notes §4).
/// Tachyon `light`, `directional_light`, `spotlight` (tachyon-notes §4) also
/// set the other fields; their colour is the intensity as written.
struct Light {
  Vec3 position;
  Vec3 colour{1, 1, 1};  // optional RGB, multiplies the per-light intensity
  LightKind kind = LightKind::point;
  Vec3 direction{0, 0, -1};           ///< directional: where the light travels; spot: the cone's axis (unit)
  double kc = 1, kl = 0, kq = 0;      ///< intensity / (kc + kl d + kq d^2), d in world units
  double fall_start = 0, fall_end = 0;  ///< spot: full intensity to fall_start, none past fall_end (radians off axis)
  /// Spot falloff between fall_start and fall_end: false, linear in the
  /// angle (Tachyon); true, KHR_lights_punctual's smooth one, the square of
  /// (cos a - cos fall_end) / (cos fall_start - cos fall_end).
  bool smooth_cone = false;
  /// KHR_lights_punctual `range` (world units): the light fades to nothing
  /// there by the extension's window, (1 - (d/range)^4)^2 clamped; 0: none.
  double range = 0;
  /// The colour is already the renderer's radiance unit (docs/lights.md):
  /// a glTF light converted from candela or lux. NFF's 1/sqrt(lights)
  /// scaling (nff-notes §4) is not applied to it.
  bool photometric = false;
  /// Put there by a reader because the file has no light (mesh files): the
  /// build step keeps it only when no file of the scene has a light of its
  /// own, and keeps one such light at most.
  bool headlight = false;
  /// Point and spot lights: the radius of the disk, facing the lit point,
  /// that the path integrator draws the light's position on (soft shadows;
  /// Blender's shadow_soft_size, as Cycles draws it); 0: a point. Whitted's
  /// integrator lights from the centre.
  double radius = 0;
  /// Directional lights: the angular diameter of the disk the light comes
  /// from (radians; Blender's sun `angle`), for the path integrator; 0: one direction.
  double angle = 0;
  SourceLoc loc;
};

/// An area light (Blender's square, rectangle, disk and ellipse lights,
/// from a lights file): a flat Lambertian emitter, one-sided, lighting the
/// path integrator's scene (Whitted's integrator leaves it out). World
/// frame, scene units.
struct AreaLightDesc {
  Vec3 centre;
  /// Half its extents along its local x and y (perpendicular): a rectangle
  /// spans centre +- axis_u +- axis_v, an ellipse is inscribed in it.
  Vec3 axis_u{0.5, 0, 0}, axis_v{0, 0.5, 0};
  bool ellipse = false;
  /// The side it emits toward: axis_u x axis_v or its opposite (Blender's
  /// local -z).
  Vec3 normal{0, 0, -1};
  /// The radiance of its surface (linear RGB; Blender: power c / (4 area)).
  Vec3 radiance{1, 1, 1};
  SourceLoc loc;
};

/// Which shading formula a material follows: NFF's Whitted model
/// (render/shading.hpp), Tachyon's (tachyon-notes §3) or glTF 2.0's
/// metallic-roughness BRDF (the specification's Appendix B). A Tachyon
/// scene's materials are all `tachyon`; the NFF reader and the mesh reader
/// (for all but glTF 2.0 materials) make `nff` ones; glTF 2.0 materials are
/// `gltf`. `blinn_phong` is NFF's model plus the highlight of MTL's
/// illumination model 2 (a specular colour, Material::specular): the mesh
/// reader makes it for a non-glTF material with a specular colour whose
/// file asks for highlights (MTL `illum` 2 or more).
enum class ShadingModel { nff, tachyon, gltf, blinn_phong };

/// NFF `f` (nff-notes §5): colour, Kd, Ks (mirror weight and highlight weight),
/// Phong exponent, transmittance T (weight of the refracted ray) and ior.
/// A Tachyon texture (tachyon-notes §3) fills the same fields with its own
/// meaning: kd = `diffuse`, ks = `specular` (mirror weight only), shine =
/// `phong_size`, transmittance = 1 - `opacity` (no refraction, ior 1), plus
/// the fields below.
struct Material {
  Vec3 colour{0.8, 0.8, 0.8};
  double kd = 1, ks = 0, shine = 0, transmittance = 0, ior = 1;
  ShadingModel model = ShadingModel::nff;
  double ambient = 0;        ///< tachyon: `ambient`, times the texture colour
  double phong = 0;          ///< tachyon: highlight weight (`phong plastic|metal W`)
  bool phong_metal = false;  ///< tachyon: the highlight takes the surface colour, not the light's
  /// Index into SceneDesc::textures; -1: constant `colour`. Tachyon: its
  /// texfunc. NFF-model (mesh) materials: a uv_image whose linear texel
  /// multiplies `colour` (glTF base colour factor x texture, MTL Kd x map_Kd).
  int texture = -1;
  bool emitter = false;      ///< tachyon: a light's sphere, seen in `colour`, unshaded
  /// glTF alphaMode MASK: where alpha (`alpha` times the texture's alpha)
  /// is below `alpha_cutoff` the surface is not there, for every ray.
  bool alpha_mask = false;
  double alpha = 1, alpha_cutoff = 0.5;
  /// MTL `map_d`: the uv_image (index into SceneDesc::textures) whose
  /// coverage multiplies `alpha` in place of the colour texture's alpha:
  /// its alpha channel, else its first channel (linear); -1: none.
  int alpha_texture = -1;
  /// NFF-model (mesh) materials: light the surface gives off, added to
  /// NFF's formula as it stands (glTF emissiveFactor x strength, MTL Ke),
  /// times `emission_texture` (a uv_image, index into SceneDesc::textures;
  /// -1: none) where given. Linear RGB.
  Vec3 emission{0, 0, 0};
  int emission_texture = -1;
  /// glTF materials (model `gltf`): metallicFactor and roughnessFactor in
  /// [0, 1]; `colour` is the base colour, `ior` the dielectric's index
  /// (KHR_materials_ior; 1.5 by default, F0 = 0.04).
  double metallic = 0, roughness = 1;
  /// glTF materials: KHR_materials_transmission's factor, the share of the
  /// dielectric's diffuse light that passes through (thin-walled).
  double transmission = 0;
  /// glTF materials: the metallicRoughnessTexture (linear; blue scales
  /// metallic, green roughness). Index into SceneDesc::textures reading the
  /// base colour map's coordinates, as every map below; -1: none.
  int metal_rough_texture = -1;
  /// Mesh materials (glTF, and the others but Tachyon's): a tangent-space
  /// normal map (glTF normalTexture, MTL `norm`, and `bump` made one by
  /// normals_from_heights), linear, x and y scaled by `normal_scale`.
  int normal_texture = -1;
  double normal_scale = 1;
  /// blinn_phong: MTL's Ks (linear RGB) and exponent `shine` (Ns): each seen
  /// light adds Ks (N.H)^Ns times its intensity, H the half vector (MTL's
  /// illumination model 2), times `specular_texture`'s first channel
  /// (map_Ks, linear) where given.
  Vec3 specular{0, 0, 0};
  int specular_texture = -1;
  SourceLoc loc;
};

/// An RGB image in 8 bits, rows in the order the file stores them (Tachyon's image maps).
struct ImageMap {
  std::string path;  ///< as resolved (or the IMAGEDEF name), for messages
  int width = 0, height = 0;
  int depth = 1;  ///< slices of a volume image (Tachyon `IMAGEDEF ... RESOLUTION x y z`)
  std::vector<unsigned char> rgb;  ///< width*height*depth*3, x fastest, then y, then z
  /// The codes are sRGB-encoded (a mesh's colour texture): its MIP levels
  /// average the light the codes stand for. Tachyon's image maps (false)
  /// average the codes, as Tachyon does.
  bool srgb = false;
  /// width*height alpha codes (linear coverage), or empty: opaque. Read only
  /// by alpha-masked materials.
  std::vector<unsigned char> alpha;
};

/// How a UV-mapped image repeats outside [0, 1] (glTF sampler wrapS /
/// wrapT, glTF 2.0 §5.26; OBJ/MTL maps repeat).
enum class TextureWrap { repeat, clamp, mirror };

/// Tachyon `texfunc` (tachyon-notes §3): a colour that varies over the
/// surface, evaluated at the world-space hit point; or (uv_image) a mesh
/// file's image texture, looked up at the hit's texture coordinates.
struct TextureDesc {
  enum class Kind {
    checker3d = 1,
    wood = 4,
    cylinder_checker = 6,
    cylindrical_image = 7,
    spherical_image = 8,
    planar_image = 9,
    volume_image = 10,
    uv_image = 100,  ///< a mesh's base colour map (glTF baseColorTexture, MTL map_Kd): not a Tachyon texfunc
  };
  Kind kind = Kind::checker3d;
  Vec3 centre, rotate, scale{1, 1, 1}, uaxis{1, 0, 0}, vaxis{0, 1, 0}, waxis{0, 0, 1};
  int image = -1;  ///< index into SceneDesc::images (image maps)
  // uv_image only: the sampler and the texel encoding.
  TextureWrap wrap_u = TextureWrap::repeat, wrap_v = TextureWrap::repeat;
  bool nearest = false;  ///< magnification filter NEAREST (glTF); else linear
  bool srgb = true;      ///< texel codes are sRGB-encoded (glTF base colour, MTL map_Kd), decoded to linear
  /// Where a hit's (u, v) reads the image (both v up, TriangleMeshDesc::uvs):
  /// u' = m[0] u + m[1] v + m[2], v' = m[3] u + m[4] v + m[5] (glTF
  /// KHR_texture_transform; the identity otherwise).
  std::array<double, 6> uv_transform{1, 0, 0, 0, 1, 0};
  SourceLoc loc;
};

/// NFF `s`: negative radius means only the inside is visible.
struct SphereDesc {
  Vec3 centre;
  double radius = 1;
  /// False for a Tachyon light's own sphere: seen by eye and mirror rays,
  /// never by shadow rays (Tachyon's lights cast no shadows).
  bool casts_shadow = true;
};

/// NFF `c`: open truncated cone (no caps) from base to apex. Both radii
/// negative means only the inside is visible; radii otherwise share a sign.
struct ConeDesc {
  Vec3 base, apex;
  double base_radius = 1, apex_radius = 1;
};

/// NFF `p` / `pp`: planar, possibly concave polygon; front side is where the
/// vertices run counter-clockwise. `normals` is empty for `p`, one per vertex for `pp`.
struct PolygonDesc {
  std::vector<Vec3> vertices;
  std::vector<Vec3> normals;
};

/// Triangles sharing one object id and material (a Tachyon box or ring),
/// flat-shaded unless `normals` gives one per vertex.
struct TriangleMeshDesc {
  std::vector<Vec3> vertices;
  std::vector<Vec3> normals;
  /// One per vertex (Tachyon vcstri and coloured vertex arrays): the surface
  /// colour, interpolated over each triangle, in place of the material's.
  std::vector<Vec3> colours;
  std::vector<std::array<uint32_t, 3>> triangles;  ///< counter-clockwise seen from the front
  /// One per vertex, or empty: the texture coordinates (u, v) the material's
  /// uv_image reads, v up from the image's bottom row (assimp's and OBJ's
  /// convention; glTF's v down is flipped by assimp's importer).
  std::vector<std::array<double, 2>> uvs;
};

/// Tachyon `plane`: infinite. Built as a square centred on `point`, a
/// thousand times wider than the rest of the scene (RenderScene), where its
/// edge lies below a pixel of any view that sees the rest.
struct PlaneDesc {
  Vec3 point, normal;
};

/// One primitive of the file; its index in SceneDesc::objects is its object id.
struct ObjectDesc {
  std::variant<SphereDesc, ConeDesc, PolygonDesc, TriangleMeshDesc, PlaneDesc> shape;
  int material = -1;  // index into SceneDesc::materials; -1: before any `f` (default grey)
  SourceLoc loc;
};

/// Tachyon `fog` (tachyon-notes §3): each shaded colour C at distance r along
/// its ray segment becomes f C + (1 - f) colour, with f = (end - r) / (end -
/// start) (linear), exp(-density (r - start)) (exp) or exp(-(density (r -
/// start))^2) (exp2), clamped to [0, 1].
struct FogDesc {
  enum class Mode { linear, exp, exp2 };
  Mode mode = Mode::linear;
  double start = 0, end = 1, density = 1;
  Vec3 colour;
};

/// A whole scene as read from one file.
struct SceneDesc {
  std::string source;                 // file name used in messages
  std::optional<Viewpoint> viewpoint; // NFF `v`, when present
  Vec3 background{0, 0, 0};           // NFF `b`; black when absent (nff-notes §3)
  std::vector<Light> lights;
  std::vector<AreaLightDesc> area_lights;  ///< from a lights file (scene/lights_file.hpp)
  std::vector<Material> materials;
  std::vector<ObjectDesc> objects;
  std::vector<TextureDesc> textures;  ///< Tachyon texfuncs, by Material::texture
  std::vector<ImageMap> images;       ///< image maps, by TextureDesc::image
  /// Whose conventions the lights follow: NFF's (intensity from the light
  /// count, nff-notes §4) or Tachyon's (the colour as written).
  ShadingModel shading = ShadingModel::nff;
  std::optional<FogDesc> fog;  ///< Tachyon `fog`, when on
  /// Ray-tree depth the file asks for (Tachyon `raydepth`), eye ray = 1.
  std::optional<int> max_depth;
  /// "file:line:col: warning: ..." for input that was accepted but is
  /// suspect (a polygon with no area, a negative sphere radius), in file
  /// order; only the first NffLimits::max_warnings_kept are kept as text.
  std::vector<std::string> warnings;
  /// Every warning, kept or not.
  size_t warning_count = 0;
};

}  // namespace holoray
