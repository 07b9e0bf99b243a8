// holoray/scene, internal to the mesh reader: an assimp scene turned into a
// SceneDesc (and a MeshAnimation) by one MeshReader, its jobs a file each:
//   mesh_reader.cpp          the reader's frame and the format dispatcher
//   mesh_materials.cpp       materials: colours, highlights, emission, maps
//   mesh_textures.cpp        image maps: files, embedded textures, the cache
//   mesh_geometry.cpp        the node walk and the triangle meshes
//   mesh_animation.cpp       node tracks, skins and morph targets; posing
//   mesh_lights_cameras.cpp  lights and the viewpoint's camera
#pragma once

#include <assimp/GltfMaterial.h>
#include <assimp/ObjMaterial.h>
#include <assimp/material.h>
#include <assimp/scene.h>
#include <fmt/format.h>

#include <array>
#include <functional>
#include <numbers>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "image/image_io.hpp"
#include "scene/mesh_reader.hpp"
#include "scene/parse_error.hpp"

namespace holoray::mesh_import {

inline Vec3 to_vec(const aiVector3D& v) { return {v.x, v.y, v.z}; }
inline Vec3 to_vec(const aiColor3D& c) { return {c.r, c.g, c.b}; }

// A node's transform to the world, applied to points, directions and normals.
struct Xform {
  aiMatrix4x4 m;
  aiMatrix3x3 normal;  // inverse transpose of the linear part
  Vec3 point(const aiVector3D& p) const { return to_vec(m * p); }
  Vec3 dir(const aiVector3D& d) const { return to_vec(aiMatrix3x3(m) * d); }
  Vec3 norm(const aiVector3D& n) const { return normalize(to_vec(normal * n)); }
};

// docs/lights.md: a glTF light of 1 cd (point, spot) or 1 lx (directional)
// lights a white Lambertian surface facing it from 1 m to the radiance
// 1 / (683 pi) W/(m^2 sr): 683 lm/W at 555 nm, as Blender's importer reads
// them (1 cd -> 4 pi / 683 W; 1 lx -> 1 / 683 W/m^2).
constexpr double kGltfLightToRadiance = 1 / (683 * std::numbers::pi);

inline Affine to_affine(const aiMatrix4x4& a) {
  Affine m;
  m.m = {a.a1, a.a2, a.a3, a.b1, a.b2, a.b3, a.c1, a.c2, a.c3};
  m.translation = {a.a4, a.b4, a.c4};
  return m;
}

/// One file as assimp read it, turned into a SceneDesc by read(): its
/// materials and image maps, its node hierarchy's triangle meshes, its
/// lights and the viewpoint's camera; with a MeshAnimation, its node
/// tracks, skins and morph targets too. Throws SceneError (malformed_file)
/// for what the file cannot give.
class MeshReader {
 public:
  // `gltf_infinite_far`: per camera of a glTF file, whether it has no `zfar`
  // (check_gltf reads it from the JSON; assimp turns it into 100).
  MeshReader(const aiScene& s, std::string source, std::string ext, const MeshLimits& limits, MeshAnimation* animation,
             const SceneReadOptions& options, std::vector<bool> gltf_infinite_far);

  SceneDesc read();

 private:
  void warn(const std::string& message);

  void read_materials();

  // Light the surface gives off (glTF emissiveFactor x emissiveTexture x
  // KHR_materials_emissive_strength; MTL Ke), added to the shaded colour.
  // Its map must read the base colour map's coordinates: a mesh keeps one set.
  void read_emission(const aiMaterial& m, Material& mat, int& uv_set);

  // Map `type` of the material (colour or data, as read_map), provided it
  // reads the coordinate set of the material's other maps (`uv_set`, which
  // it sets when it is the first): a mesh keeps one set. Its texture index,
  // or -1 (none, or on another set: a warning).
  int read_map_on_set(const aiMaterial& m, aiTextureType type, bool colour, const char* what, int& uv_set);

  // MTL's map_d (assimp's OPACITY slot): a cut-out, as glTF's MASK with
  // cutoff 0.5, its coverage `d` times the map; the dissolve then lets
  // nothing through where the surface stays.
  void read_dissolve_map(const aiMaterial& m, Material& mat, int& uv_set, float opacity);

  // MTL's illumination model 2 and up (assimp's Phong or Blinn shading
  // model; `illum` 0 and 1, and no `illum`, have no highlight): Ks (N.H)^Ns
  // per light, times map_Ks's first channel. Other formats' Phong materials
  // (a specular colour) alike. An exponent below 1 gives none: (N.H)^Ns
  // would light the whole hemisphere nearly evenly, adding Ks to every lit
  // point, and exporters write Ns 0 for "no gloss" (3ds Max; Blender for
  // roughness 1, which it reads back as a faint, fully rough lobe).
  void read_highlight(const aiMaterial& m, Material& mat, int& uv_set);

  // MTL's `norm` (a normal map), else its `bump` (assimp's HEIGHT slot): a
  // grey image is a height map, made a normal map by normals_from_heights
  // with `-bm` as its strength; a coloured one is a normal map already (as
  // Blender writes and reads `bump`), `-bm` scaling its x and y.
  void read_bump_map(const aiMaterial& m, Material& mat, int& uv_set);

  // glTF's metallicRoughnessTexture (assimp's UNKNOWN slot) and
  // normalTexture with its scale: data, not colour (decoded linearly).
  void read_data_maps(const aiMaterial& m, Material& mat, int& uv_set);

  // A material's image map as a uv_image texture: its index in
  // out_.textures, and the texture coordinate set it reads.
  struct TextureMap {
    int texture;
    int uv_set;
  };
  // `colour`: the image holds colours (sRGB codes); else data (linear).
  TextureMap read_map(const aiMaterial& m, aiTextureType type, bool colour = true);

  // KHR_texture_transform (offset o, rotation r, scale s) as the glTF 2.0
  // extension defines it, in glTF's texture space (v down): uv' = T(o) R(r)
  // S(s) uv, R = [[cos r, sin r], [-sin r, cos r]]. assimp's glTF 2
  // importer hands over an aiUVTransform made from them for its own v-up
  // space (rotation -r, translation moved to rotate about the centre);
  // undoing that gives o back exactly, and the result is written for
  // holoray's v-up coordinates: v_gltf = 1 - v.
  static std::array<double, 6> gltf_uv_transform(const aiUVTransform& t);

  // The image `path` names (embedded in the file, or beside it) as an
  // ImageMap, read once per path; an image that cannot be read is named in a
  // warning and replaced by a magenta checker, never black. A colour
  // image's codes are sRGB but for float images (OpenEXR, HDR), whose
  // values are linear; a data image (`colour` false) is linear.
  int image_of(const std::string& material, const std::string& path, bool colour = true);

  // The index in out_.images of the image cached under `key`, made by
  // `make` the first time.
  int cached_image(const std::string& key, const std::function<ImageMap()>& make);

  // image_of()'s image, read (or the checker, with a warning).
  ImageMap read_image_map(const std::string& material, const std::string& path, bool colour);

  // A texture file into `img`: 8-bit PNGs and JPEGs (most textures) as
  // their codes, the rest through the float image.
  static void read_texture_file(const std::string& file, ImageHeader& header, ImageMap& img);

  // An embedded image into `img`: raw texels (assimp's BGRA), or a
  // compressed file (PNG, JPEG) read as files on disk are, from a temporary
  // copy (the readers take paths).
  static void read_embedded(const aiTexture& t, ImageHeader& header, ImageMap& img);

  // 8-bit RGB codes, row 0 at the bottom (v up, as the texture coordinates),
  // and the alpha of grey+alpha and RGBA images (their last channel), from a
  // width x height image of `channels` whose texel (x, y), rows from the top,
  // starts at texel(x, y); code(v) turns one of its values into a code.
  // Channel c of the RGB codes is the image's channel min(c, last), as
  // as_rgb takes it, read in place (as_rgb's copy of a 2048x2048 texture was
  // 48 MiB of fresh pages).
  template <class Texel, class Code>
  static void fill_image_map(int width, int height, int channels, Texel texel, Code code, ImageMap& img);

  // A float image's codes: lround of the scaled value, half away from zero,
  // which for x >= 0 is the floor of x + 1/2 taken in double (exact there,
  // where float's sum could round up; lround was a libm call per channel).
  // NaN gives 0.
  static void to_image_map(const ImageBuffer& raw, ImageMap& img);

  // to_image_map() of an 8-bit image read as codes: code(c / 255) is c, so
  // the codes are copied.
  static void codes_to_image_map(const ImageCodes& raw, ImageMap& img);

  // 8x8 squares of magenta and dark grey: a missing texture stands out.
  static void checker(ImageMap& img);

  void count(const aiNode* node, long& triangles) const;

  // The keys of each channel, in seconds, by node name.
  void read_animation(const aiAnimation& anim);

  // `world`: the parent's rest transform to the file's frame (lights,
  // cameras, the default view); `rel`: the parent's transform to the frame
  // of the moving part it belongs to (part -1: the file's, standing still).
  // An animated node starts a part of its own: its track replaces its rest
  // transform.
  void walk(const aiNode* node, const aiMatrix4x4& parent_world, const aiMatrix4x4& parent_rel, int part);

  // Where a joint node sits: its part's chain, then its frame in that part.
  MeshAnimation::DeformingMesh::Joint joint_at(const std::string& node) const;

  // A skinned or morphed mesh: its morph targets and weights, its joints
  // and their weights (MeshAnimation::DeformingMesh), then the mesh posed
  // at time 0 (a shot: a part of its own, which the sequence poses frame by
  // frame) or at rest with the default morph weights (a still: the file's
  // own part).
  void add_deforming_mesh(const aiMesh& mesh, const std::string& node);

  // The mesh's morph targets (assimp's aiAnimMesh: absolute positions and
  // normals), their default weights and their node's weight keys.
  void read_targets(const aiMesh& mesh, const std::string& node, MeshAnimation::DeformingMesh& d) const;

  // The mesh's joints and per-vertex weights (aiBone).
  void read_skin(const aiMesh& mesh, const std::string& node, MeshAnimation::DeformingMesh& d) const;

  // `xf` places the vertices in `target`'s frame; `world` (rest) bounds the
  // default view. `posed` (a skinned mesh's vertices and normals, file
  // frame) replaces the file's vertices and normals.
  void add_mesh(const aiMesh& mesh, const Xform& xf, const aiMatrix4x4& world, SceneDesc& target,
                const std::vector<Vec3>* posed = nullptr, const std::vector<Vec3>* posed_normals = nullptr);

  aiMatrix4x4 global(const aiString& name) const;

  // Point, spot and directional lights, placed by their nodes. glTF's
  // (KHR_lights_punctual) keep their photometric meaning: candela for point
  // and spot lights, lux for directional ones, falling off with the square
  // of the distance, converted to the renderer's unit by docs/lights.md's
  // rule (/ 683 lm/W, / pi). Other formats' lights are unitless, as NFF's.
  void read_lights();

  // KHR_lights_punctual's `range`, which assimp keeps on the light's node; 0: none.
  double light_range(const aiString& name) const;

  // The index of the camera the viewpoint is: the one named in the options,
  // else the file's first; -1: none. Throws std::invalid_argument naming the
  // file's cameras.
  int chosen_camera() const;

  // The camera's lens as its format defines it. assimp's importers do not
  // follow aiCamera's documentation (mHorizontalFOV, "half the horizontal
  // angle"); each stores what its own format gives (assimp 5.2.5 and 5.4.3,
  // read from their sources):
  //  - glTF 2.0 (§5.12, yfov: vertical): 5.2 stores yfov * aspect, 5.3 on
  //    the horizontal angle 2 atan(aspect tan(yfov / 2)); both read back to
  //    yfov. Orthographic (§5.13): mOrthographicWidth is xmag, half the width.
  //  - Blender (.blend): 2 atan(sensor_x / 2 lens), on the image's larger
  //    side (sensor fit "auto", Blender's default).
  //  - FBX: FieldOfView, the full horizontal angle in 5.2, half of it from 5.4.
  //  - 3DS: the chunk's `lens` as if it were degrees; 3ds Max's horizontal
  //    angle is 2400 / lens degrees (lib3ds; the same scene's ASE export,
  //    CAMERA_FOV, agrees: FileCamera.ThreeDsAndAseCamerasOfOneSceneAgree).
  //  - Irrlicht: fovy * aspect, and mLookAt is the point looked at.
  //  - Collada (xfov, or yfov with aspect_ratio made into xfov), ASE and the
  //    rest: the full horizontal angle.
  // tests/blender/test_file_cameras.py checks them against Blender's imports
  // of the same files.
  void read_lens(const aiCamera& c, Viewpoint& vp);

  // The distance along the view direction `dir` (unit) from `eye` at which a
  // file camera, which has no point it looks at, places its focal plane: the
  // depth of the scene's bounding-box centre; its distance when the centre
  // lies behind the eye.
  double centre_depth(const Vec3& eye, const Vec3& dir) const;

  void read_camera();

  const aiScene& s_;
  MeshLimits limits_;
  SceneReadOptions options_;
  std::string ext_;  // the file's extension, lower case: its format (read_lens)
  bool gltf_;        // the file went through assimp's glTF 2 importer (read_lens)
  std::vector<bool> gltf_infinite_far_;  // per camera: glTF's zfar absent
  int camera_index_ = -1;                // the viewpoint's camera (chosen_camera), -1: none
  const aiCamera* camera_ = nullptr;     // s_.mCameras[camera_index_], null: none
  MeshAnimation* animation_;  // null: nodes at rest
  std::unordered_map<std::string, int> track_of_;  // node name -> animation_->tracks index
  std::vector<int> uv_set_;                         // per material: the texture coordinate set its maps read, -1: none
  std::unordered_map<std::string, int> image_index_;  // texture path -> out_.images index
  SceneDesc out_;
  Bounds3 bounds_;
  std::unordered_map<std::string, aiMatrix4x4> global_;
  struct NodePlace {
    int part = -1;  // the moving part the node belongs to, -1: the file's still part
    Affine rel;     // the node's frame -> that part's frame (the file's at rest)
  };
  std::unordered_map<std::string, NodePlace> place_;
  std::vector<std::pair<const aiMesh*, std::string>> deforming_;  // (mesh, its node), posed after the walk
  // Morph weight keys by node name: (seconds, weight per target index).
  std::unordered_map<std::string, std::vector<std::pair<double, std::vector<double>>>> morph_keys_;
};

}  // namespace holoray::mesh_import
