#include "scene/mesh_reader.hpp"

#include <assimp/GltfMaterial.h>
#include <assimp/Importer.hpp>
#include <assimp/ObjMaterial.h>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/version.h>
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <charconv>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <numbers>
#include <stdexcept>
#include <string_view>
#include <unordered_map>

#include <unistd.h>

#include "image/image_io.hpp"
#include "scene/bump_map.hpp"
#include "scene/file_text.hpp"
#include "scene/gltf_check.hpp"
#include "scene/parse_error.hpp"
#include "scene/tachyon_reader.hpp"
#include "scene/texture_search.hpp"
#include "scene/nff_reader.hpp"

namespace holoray {

namespace {

Vec3 to_vec(const aiVector3D& v) { return {v.x, v.y, v.z}; }
Vec3 to_vec(const aiColor3D& c) { return {c.r, c.g, c.b}; }

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

Affine to_affine(const aiMatrix4x4& a) {
  Affine m;
  m.m = {a.a1, a.a2, a.a3, a.b1, a.b2, a.b3, a.c1, a.c2, a.c3};
  m.translation = {a.a4, a.b4, a.c4};
  return m;
}

class MeshReader {
 public:
  // `gltf_infinite_far`: per camera of a glTF file, whether it has no `zfar`
  // (check_gltf reads it from the JSON; assimp turns it into 100).
  MeshReader(const aiScene& s, std::string source, std::string ext, const MeshLimits& limits, MeshAnimation* animation,
             const SceneReadOptions& options, std::vector<bool> gltf_infinite_far)
      : s_(s), limits_(limits), options_(options), ext_(std::move(ext)), gltf_(ext_ == ".gltf" || ext_ == ".glb"),
        gltf_infinite_far_(std::move(gltf_infinite_far)), animation_(animation) {
    out_.source = std::move(source);
    camera_index_ = chosen_camera();
    camera_ = camera_index_ >= 0 ? s_.mCameras[camera_index_] : nullptr;
    if (animation_ && s_.mNumAnimations > 0) read_animation(*s_.mAnimations[0]);
    if (!animation_ && s_.mNumAnimations > 0)
      warn("its node animation is not played in a still (nodes stand at rest); a shot plays it (holoray animate)");
    if (animation_ && s_.mNumAnimations > 1)
      warn(fmt::format("{} animations: only the first is played", s_.mNumAnimations));
  }

  SceneDesc read() {
    read_materials();
    long triangles = 0;
    count(s_.mRootNode, triangles);
    if (triangles == 0) throw malformed_file(out_.source, "it holds no triangles");
    if (triangles > limits_.max_triangles)
      throw malformed_file(out_.source, fmt::format("{} triangles, over the limit of {}",
                                                    triangles, limits_.max_triangles));
    out_.objects.reserve(static_cast<size_t>(triangles));
    walk(s_.mRootNode, aiMatrix4x4(), aiMatrix4x4(), -1);
    for (const auto& [mesh, node] : deforming_) add_deforming_mesh(*mesh, node);
    read_lights();
    read_camera();
    return std::move(out_);
  }

 private:
  void warn(const std::string& message) {
    if (static_cast<long>(out_.warning_count++) >= limits_.max_warnings_kept) return;
    out_.warnings.push_back(fmt::format("{}: warning: {}", out_.source, message));
  }

  void read_materials() {
    for (unsigned k = 0; k < s_.mNumMaterials; ++k) {
      const aiMaterial& m = *s_.mMaterials[k];
      Material mat;
      // The importer's stand-in for "no material" (OBJ without MTL, PLY,
      // STL: each with its own grey): holoray's default, as NFF's, so the
      // same mesh looks the same from every format.
      const aiString name = m.GetName();  // by value: keep it while comparing
      // A glTF material may have no name and still be the file's own:
      // assimp's glTF importers append their stand-in, unnamed, last.
      const bool unnamed_stand_in = name.length == 0 && (!gltf_ || k + 1 == s_.mNumMaterials);
      if (unnamed_stand_in || std::string_view(name.C_Str()) == AI_DEFAULT_MATERIAL_NAME) {
        out_.materials.push_back(mat);
        continue;
      }
      // Without a diffuse colour of its own, a textured material is its
      // texture (factor 1: glTF 1's diffuse texture, an MTL map_Kd with no
      // Kd); an untextured one is holoray's grey. assimp may write the
      // colour even when the key is absent: only a success counts.
      const bool textured = m.GetTextureCount(aiTextureType_BASE_COLOR) > 0 || m.GetTextureCount(aiTextureType_DIFFUSE) > 0;
      aiColor3D diffuse;
      mat.colour = textured ? Vec3{1, 1, 1} : Vec3{0.8, 0.8, 0.8};
      if (m.Get(AI_MATKEY_COLOR_DIFFUSE, diffuse) == AI_SUCCESS) mat.colour = to_vec(diffuse);
      mat.kd = 1;
      float reflectivity = 0, shininess = 0, opacity = 1, ior = 1, metallic = -1, roughness = 1;
      m.Get(AI_MATKEY_REFLECTIVITY, reflectivity);
      m.Get(AI_MATKEY_SHININESS, shininess);
      m.Get(AI_MATKEY_OPACITY, opacity);
      const bool has_ior = m.Get(AI_MATKEY_REFRACTI, ior) == AI_SUCCESS;
      if (m.Get(AI_MATKEY_METALLIC_FACTOR, metallic) == AI_SUCCESS && metallic >= 0) {
        m.Get(AI_MATKEY_ROUGHNESS_FACTOR, roughness);
        if (gltf_) {
          // glTF 2.0's own model (Appendix B), shaded by render/gltf_brdf.hpp.
          mat.model = ShadingModel::gltf;
          mat.metallic = std::clamp(static_cast<double>(metallic), 0.0, 1.0);
          mat.roughness = std::clamp(static_cast<double>(roughness), 0.0, 1.0);
          if (!has_ior) ior = 1.5f;  // KHR_materials_ior's default
        } else {
          // Another format's metallic-roughness, approximated: a smooth metal mirrors.
          reflectivity = std::fmax(reflectivity, metallic * (1 - roughness));
          shininess = std::fmax(shininess, 2 / std::fmax(roughness * roughness, 1e-3f));
        }
      }
      mat.ks = mat.model == ShadingModel::gltf ? 0.0 : std::clamp(static_cast<double>(reflectivity), 0.0, 1.0);
      mat.shine = std::fmax(0.0, shininess);
      mat.transmittance = std::clamp(1.0 - opacity, 0.0, 1.0);
      // glTF's alphaMode (§3.9.4): OPAQUE ignores alpha, MASK cuts the
      // surface away where alpha < alphaCutoff, BLEND lets 1 - alpha through
      // (here: NFF's transmittance, from the factor's alpha only).
      aiString alpha_mode;
      if (gltf_ && m.Get(AI_MATKEY_GLTF_ALPHAMODE, alpha_mode) == AI_SUCCESS) {
        const std::string_view mode = alpha_mode.C_Str();
        if (mode != "BLEND") mat.transmittance = 0;
        if (mode == "MASK") {
          mat.alpha_mask = true;
          mat.alpha = std::clamp(static_cast<double>(opacity), 0.0, 1.0);
          float cutoff = 0.5f;
          m.Get(AI_MATKEY_GLTF_ALPHACUTOFF, cutoff);
          mat.alpha_cutoff = cutoff;
        }
      }
      mat.ior = ior > 0 ? ior : 1;
      // glTF's base colour factor is the diffuse colour above (assimp sets
      // both); the texture multiplies it (glTF 2.0 §3.9.2; MTL: Kd x map_Kd).
      int uv_set = -1;
      for (const aiTextureType t : {aiTextureType_BASE_COLOR, aiTextureType_DIFFUSE})
        if (m.GetTextureCount(t) > 0) {
          const TextureMap map = read_map(m, t);
          mat.texture = map.texture;
          uv_set = map.uv_set;
          break;
        }
      read_emission(m, mat, uv_set);
      if (!gltf_) {
        read_dissolve_map(m, mat, uv_set, opacity);
        read_highlight(m, mat, uv_set);
        read_bump_map(m, mat, uv_set);
      }
      if (mat.model == ShadingModel::gltf) {
        read_data_maps(m, mat, uv_set);
        float transmission = 0;
        if (m.Get(AI_MATKEY_TRANSMISSION_FACTOR, transmission) == AI_SUCCESS && std::isfinite(transmission))
          mat.transmission = std::clamp(static_cast<double>(transmission), 0.0, 1.0);
        if (m.GetTextureCount(aiTextureType_TRANSMISSION) > 0)
          warn(fmt::format("material '{}': its transmission texture is not applied (the factor is)", m.GetName().C_Str()));
      }
      uv_set_.resize(out_.materials.size(), -1);
      uv_set_.push_back(uv_set);
      out_.materials.push_back(mat);
    }
  }

  // Light the surface gives off (glTF emissiveFactor x emissiveTexture x
  // KHR_materials_emissive_strength; MTL Ke), added to the shaded colour.
  // Its map must read the base colour map's coordinates: a mesh keeps one set.
  void read_emission(const aiMaterial& m, Material& mat, int& uv_set) {
    aiColor3D e;
    if (m.Get(AI_MATKEY_COLOR_EMISSIVE, e) != AI_SUCCESS) return;
    float strength = 1;
    m.Get(AI_MATKEY_EMISSIVE_INTENSITY, strength);
    mat.emission = to_vec(e) * static_cast<double>(strength);
    if (!is_finite(mat.emission)) mat.emission = {};
    if (!(mat.emission.x > 0 || mat.emission.y > 0 || mat.emission.z > 0)) return;
    mat.emission_texture = read_map_on_set(m, aiTextureType_EMISSIVE, true, "emissive", uv_set);
  }

  // Map `type` of the material (colour or data, as read_map), provided it
  // reads the coordinate set of the material's other maps (`uv_set`, which
  // it sets when it is the first): a mesh keeps one set. Its texture index,
  // or -1 (none, or on another set: a warning).
  int read_map_on_set(const aiMaterial& m, aiTextureType type, bool colour, const char* what, int& uv_set) {
    if (m.GetTextureCount(type) == 0) return -1;
    const TextureMap map = read_map(m, type, colour);
    if (uv_set >= 0 && map.uv_set != uv_set) {
      warn(fmt::format("material '{}': its {} texture reads texture coordinate set {} and its other textures set {}: "
                       "it is not applied (a mesh keeps one set)",
                       m.GetName().C_Str(), what, map.uv_set, uv_set));
      return -1;
    }
    uv_set = map.uv_set;
    return map.texture;
  }

  // MTL's map_d (assimp's OPACITY slot): a cut-out, as glTF's MASK with
  // cutoff 0.5, its coverage `d` times the map; the dissolve then lets
  // nothing through where the surface stays.
  void read_dissolve_map(const aiMaterial& m, Material& mat, int& uv_set, float opacity) {
    mat.alpha_texture = read_map_on_set(m, aiTextureType_OPACITY, false, "map_d", uv_set);
    if (mat.alpha_texture < 0) return;
    mat.alpha_mask = true;
    mat.alpha = std::clamp(static_cast<double>(opacity), 0.0, 1.0);
    mat.transmittance = 0;
  }

  // MTL's illumination model 2 and up (assimp's Phong or Blinn shading
  // model; `illum` 0 and 1, and no `illum`, have no highlight): Ks (N.H)^Ns
  // per light, times map_Ks's first channel. Other formats' Phong materials
  // (a specular colour) alike. An exponent below 1 gives none: (N.H)^Ns
  // would light the whole hemisphere nearly evenly, adding Ks to every lit
  // point, and exporters write Ns 0 for "no gloss" (3ds Max; Blender for
  // roughness 1, which it reads back as a faint, fully rough lobe).
  void read_highlight(const aiMaterial& m, Material& mat, int& uv_set) {
    int model = 0;
    aiColor3D ks;
    const bool phong = m.Get(AI_MATKEY_SHADING_MODEL, model) == AI_SUCCESS &&
                       (model == aiShadingMode_Phong || model == aiShadingMode_Blinn);
    const Vec3 specular = m.Get(AI_MATKEY_COLOR_SPECULAR, ks) == AI_SUCCESS ? to_vec(ks) : Vec3{};
    if (!phong || !is_finite(specular) || !(specular.x > 0 || specular.y > 0 || specular.z > 0) || !(mat.shine >= 1)) {
      if (m.GetTextureCount(aiTextureType_SPECULAR) > 0)
        warn(fmt::format("material '{}': its map_Ks is not applied: the material has no highlight (it needs a "
                         "non-zero Ks, Ns of 1 or more and illum 2 or more)",
                         m.GetName().C_Str()));
      return;
    }
    mat.model = ShadingModel::blinn_phong;
    mat.specular = Vec3{std::fmax(specular.x, 0.0), std::fmax(specular.y, 0.0), std::fmax(specular.z, 0.0)};
    mat.specular_texture = read_map_on_set(m, aiTextureType_SPECULAR, false, "map_Ks", uv_set);
  }

  // MTL's `norm` (a normal map), else its `bump` (assimp's HEIGHT slot): a
  // grey image is a height map, made a normal map by normals_from_heights
  // with `-bm` as its strength; a coloured one is a normal map already (as
  // Blender writes and reads `bump`), `-bm` scaling its x and y.
  void read_bump_map(const aiMaterial& m, Material& mat, int& uv_set) {
    const bool norm = m.GetTextureCount(aiTextureType_NORMALS) > 0;
    const aiTextureType type = norm ? aiTextureType_NORMALS : aiTextureType_HEIGHT;
    const int texture = read_map_on_set(m, type, false, norm ? "norm" : "bump", uv_set);
    if (texture < 0) return;
    float bm = 1;
    if (m.Get(AI_MATKEY_OBJ_BUMPMULT(type, 0), bm) != AI_SUCCESS || !std::isfinite(bm)) bm = 1;
    mat.normal_texture = texture;
    TextureDesc& tex = out_.textures[static_cast<size_t>(texture)];
    if (norm || !is_grey(out_.images[static_cast<size_t>(tex.image)])) {
      mat.normal_scale = bm;
      return;
    }
    const int heights = tex.image;
    tex.image = cached_image(out_.images[static_cast<size_t>(heights)].path + fmt::format("\n(heights {})", bm),
                             [&] { return normals_from_heights(out_.images[static_cast<size_t>(heights)], bm); });
  }

  // glTF's metallicRoughnessTexture (assimp's UNKNOWN slot) and
  // normalTexture with its scale: data, not colour (decoded linearly).
  void read_data_maps(const aiMaterial& m, Material& mat, int& uv_set) {
    mat.metal_rough_texture = read_map_on_set(m, aiTextureType_UNKNOWN, false, "metallic-roughness", uv_set);
    mat.normal_texture = read_map_on_set(m, aiTextureType_NORMALS, false, "normal", uv_set);
    float scale = 1;
    if (mat.normal_texture >= 0 && m.Get(AI_MATKEY_GLTF_TEXTURE_SCALE(aiTextureType_NORMALS, 0), scale) == AI_SUCCESS &&
        std::isfinite(scale))
      mat.normal_scale = scale;
  }

  // A material's image map as a uv_image texture: its index in
  // out_.textures, and the texture coordinate set it reads.
  struct TextureMap {
    int texture;
    int uv_set;
  };
  // `colour`: the image holds colours (sRGB codes); else data (linear).
  TextureMap read_map(const aiMaterial& m, aiTextureType type, bool colour = true) {
    aiString path;
    unsigned uv_set = 0;
    aiTextureMapMode modes[2] = {aiTextureMapMode_Wrap, aiTextureMapMode_Wrap};
    m.GetTexture(type, 0, &path, nullptr, &uv_set, nullptr, nullptr, modes);
    m.Get(AI_MATKEY_UVWSRC(type, 0), uv_set);
    TextureDesc tex;
    tex.kind = TextureDesc::Kind::uv_image;
    auto wrap = [](aiTextureMapMode mode) {
      return mode == aiTextureMapMode_Clamp ? TextureWrap::clamp
             : mode == aiTextureMapMode_Mirror ? TextureWrap::mirror
                                               : TextureWrap::repeat;
    };
    tex.wrap_u = wrap(modes[0]);
    tex.wrap_v = wrap(modes[1]);
    int mag = 0;
    if (m.Get(AI_MATKEY_GLTF_MAPPINGFILTER_MAG(type, 0), mag) == AI_SUCCESS) tex.nearest = mag == 9728;  // GL NEAREST
    aiUVTransform t;
    if (gltf_ && m.Get(AI_MATKEY_UVTRANSFORM(type, 0), t) == AI_SUCCESS) tex.uv_transform = gltf_uv_transform(t);
    tex.image = image_of(m.GetName().C_Str(), path.C_Str(), colour);
    tex.srgb = out_.images[static_cast<size_t>(tex.image)].srgb;
    out_.textures.push_back(tex);
    return {static_cast<int>(out_.textures.size()) - 1, static_cast<int>(uv_set)};
  }

  // KHR_texture_transform (offset o, rotation r, scale s) as the glTF 2.0
  // extension defines it, in glTF's texture space (v down): uv' = T(o) R(r)
  // S(s) uv, R = [[cos r, sin r], [-sin r, cos r]]. assimp's glTF 2
  // importer hands over an aiUVTransform made from them for its own v-up
  // space (rotation -r, translation moved to rotate about the centre);
  // undoing that gives o back exactly, and the result is written for
  // holoray's v-up coordinates: v_gltf = 1 - v.
  static std::array<double, 6> gltf_uv_transform(const aiUVTransform& t) {
    const double r = -t.mRotation, sx = t.mScaling.x, sy = t.mScaling.y;
    const double c = std::cos(r), s = std::sin(r);
    const double ox = t.mTranslation.x - 0.5 * sx * (-c + s + 1);
    const double oy = 0.5 * sy * (s + c - 1) + 1 - sy - t.mTranslation.y;
    const double m00 = c * sx, m01 = s * sy, m10 = -s * sx, m11 = c * sy;  // R S
    // u' = m00 u + m01 (1 - v) + ox;  v' = 1 - (m10 u + m11 (1 - v) + oy)
    return {m00, -m01, m01 + ox, -m10, m11, 1 - m11 - oy};
  }

  // The image `path` names (embedded in the file, or beside it) as an
  // ImageMap, read once per path; an image that cannot be read is named in a
  // warning and replaced by a magenta checker, never black. A colour
  // image's codes are sRGB but for float images (OpenEXR, HDR), whose
  // values are linear; a data image (`colour` false) is linear.
  int image_of(const std::string& material, const std::string& path, bool colour = true) {
    return cached_image(colour ? path : path + "\n(data)", [&] { return read_image_map(material, path, colour); });
  }

  // The index in out_.images of the image cached under `key`, made by
  // `make` the first time.
  int cached_image(const std::string& key, const std::function<ImageMap()>& make) {
    if (const auto it = image_index_.find(key); it != image_index_.end()) return it->second;
    out_.images.push_back(make());
    const int index = static_cast<int>(out_.images.size()) - 1;
    image_index_[key] = index;
    return index;
  }

  // image_of()'s image, read (or the checker, with a warning).
  ImageMap read_image_map(const std::string& material, const std::string& path, bool colour) {
    ImageMap img;
    img.path = path;
    try {
      ImageHeader header;
      if (const aiTexture* e = s_.GetEmbeddedTexture(path.c_str())) {
        read_embedded(*e, header, img);
      } else {
        const TextureLookup where = find_texture(path, out_.source, options_.texture_paths);
        if (!where.found) {
          std::string tried;
          for (const std::string& t : where.tried) tried += fmt::format("{}{}", tried.empty() ? "" : ", ", t);
          throw std::runtime_error(fmt::format("not found; looked for {}", tried));
        }
        read_texture_file(*where.found, header, img);
      }
      img.srgb = colour && header.format != "openexr" && header.format != "hdr";
    } catch (const std::exception& e) {
      const auto* read_error = dynamic_cast<const ImageReadError*>(&e);
      warn(fmt::format("material '{}': cannot read texture '{}' ({}): a checker shows where it goes", material, path,
                       read_error ? read_error->reason() : std::string(e.what())));
      checker(img);
      img.srgb = true;
    }
    return img;
  }

  // A texture file into `img`: 8-bit PNGs and JPEGs (most textures) as
  // their codes, the rest through the float image.
  static void read_texture_file(const std::string& file, ImageHeader& header, ImageMap& img) {
    if (auto codes = read_image_codes(file, &header)) codes_to_image_map(*codes, img);
    else to_image_map(read_image(file, &header), img);
  }

  // An embedded image into `img`: raw texels (assimp's BGRA), or a
  // compressed file (PNG, JPEG) read as files on disk are, from a temporary
  // copy (the readers take paths).
  static void read_embedded(const aiTexture& t, ImageHeader& header, ImageMap& img) {
    if (t.mHeight > 0) {
      if (int64_t{t.mWidth} * t.mHeight > kMaxImagePixels)
        throw std::runtime_error(fmt::format("{}x{} texels (at most {})", t.mWidth, t.mHeight, kMaxImagePixels));
      ImageCodes raw{static_cast<int>(t.mWidth), static_cast<int>(t.mHeight), 4,
                     std::vector<uint8_t>(size_t{t.mWidth} * t.mHeight * 4)};
      for (size_t k = 0; k < size_t{t.mWidth} * t.mHeight; ++k) {
        const aiTexel& c = t.pcData[k];
        uint8_t* o = &raw.codes[4 * k];
        o[0] = c.r, o[1] = c.g, o[2] = c.b, o[3] = c.a;
      }
      header = {raw.width, raw.height, 4, "raw"};
      codes_to_image_map(raw, img);
      return;
    }
    const std::filesystem::path tmp =
        std::filesystem::temp_directory_path() /
        fmt::format("holoray-texture-{}-{}.{}", ::getpid(), static_cast<const void*>(&t), t.achFormatHint[0] ? t.achFormatHint : "img");
    {
      std::ofstream out(tmp, std::ios::binary);
      out.write(reinterpret_cast<const char*>(t.pcData), static_cast<std::streamsize>(t.mWidth));
      if (!out) throw std::runtime_error("cannot copy the embedded image to a temporary file");
    }
    struct Remove {
      std::filesystem::path p;
      ~Remove() {
        std::error_code ec;
        std::filesystem::remove(p, ec);
      }
    } remove{tmp};
    try {
      read_texture_file(tmp.string(), header, img);
    } catch (const ImageReadError& e) {
      throw std::runtime_error(e.reason());
    }
  }

  // 8-bit RGB codes, row 0 at the bottom (v up, as the texture coordinates),
  // and the alpha of grey+alpha and RGBA images (their last channel), from a
  // width x height image of `channels` whose texel (x, y), rows from the top,
  // starts at texel(x, y); code(v) turns one of its values into a code.
  // Channel c of the RGB codes is the image's channel min(c, last), as
  // as_rgb takes it, read in place (as_rgb's copy of a 2048x2048 texture was
  // 48 MiB of fresh pages).
  template <class Texel, class Code>
  static void fill_image_map(int width, int height, int channels, Texel texel, Code code, ImageMap& img) {
    img.width = width;
    img.height = height;
    img.rgb.resize(size_t(width) * height * 3);
    const bool alpha = channels == 2 || channels == 4;
    if (alpha) img.alpha.resize(size_t(width) * height);
    const int last = channels - 1;
    const int ch[3] = {0, std::min(1, last), std::min(2, last)};
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        const size_t at = size_t(y) * width + x;
        const auto* p = texel(x, height - 1 - y);
        for (int c = 0; c < 3; ++c) img.rgb[at * 3 + c] = code(p[ch[c]]);
        if (alpha) img.alpha[at] = code(p[last]);
      }
  }

  // A float image's codes: lround of the scaled value, half away from zero,
  // which for x >= 0 is the floor of x + 1/2 taken in double (exact there,
  // where float's sum could round up; lround was a libm call per channel).
  // NaN gives 0.
  static void to_image_map(const ImageBuffer& raw, ImageMap& img) {
    fill_image_map(
        raw.width, raw.height, raw.channels, [&](int x, int y) { return raw.at(x, y); },
        [](float v) {
          const float x = std::clamp(v, 0.0f, 1.0f) * 255.0f;
          return static_cast<unsigned char>(x >= 0 ? static_cast<int>(static_cast<double>(x) + 0.5) : 0);
        },
        img);
  }

  // to_image_map() of an 8-bit image read as codes: code(c / 255) is c, so
  // the codes are copied.
  static void codes_to_image_map(const ImageCodes& raw, ImageMap& img) {
    fill_image_map(
        raw.width, raw.height, raw.channels,
        [&](int x, int y) { return raw.codes.data() + (size_t(y) * raw.width + x) * raw.channels; },
        [](uint8_t v) { return v; }, img);
  }

  // 8x8 squares of magenta and dark grey: a missing texture stands out.
  static void checker(ImageMap& img) {
    img.width = img.height = 8;
    img.rgb.resize(8 * 8 * 3);
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 8; ++x) {
        const bool on = (x + y) % 2 == 0;
        unsigned char* p = &img.rgb[(size_t(y) * 8 + x) * 3];
        p[0] = on ? 255 : 40, p[1] = on ? 0 : 40, p[2] = on ? 255 : 40;
      }
  }

  void count(const aiNode* node, long& triangles) const {
    for (unsigned k = 0; k < node->mNumMeshes; ++k) {
      const aiMesh& mesh = *s_.mMeshes[node->mMeshes[k]];
      if (mesh.mPrimitiveTypes & aiPrimitiveType_TRIANGLE) triangles += mesh.mNumFaces;
    }
    for (unsigned k = 0; k < node->mNumChildren; ++k) count(node->mChildren[k], triangles);
  }

  // The keys of each channel, in seconds, by node name.
  void read_animation(const aiAnimation& anim) {
    const double tps = anim.mTicksPerSecond > 0 ? anim.mTicksPerSecond : 25.0;  // assimp's documented fallback
    animation_->duration_s = anim.mDuration / tps;
    for (unsigned c = 0; c < anim.mNumChannels; ++c) {
      const aiNodeAnim& ch = *anim.mChannels[c];
      NodeTrack track;
      auto time = [&](double ticks, const char* what) {
        if (!std::isfinite(ticks))
          throw malformed_file(out_.source, fmt::format("node '{}' has a {} key at a time that is not finite",
                                                        ch.mNodeName.C_Str(), what));
        return ticks / tps;
      };
      auto bad = [&](const char* what) {
        return std::runtime_error(fmt::format("cannot read '{}': node '{}' has a {} key that is not finite", out_.source,
                                              ch.mNodeName.C_Str(), what));
      };
      for (unsigned k = 0; k < ch.mNumPositionKeys; ++k) {
        if (!is_finite(to_vec(ch.mPositionKeys[k].mValue))) throw bad("translation");
        track.translation.emplace_back(time(ch.mPositionKeys[k].mTime, "translation"), to_vec(ch.mPositionKeys[k].mValue));
      }
      for (unsigned k = 0; k < ch.mNumScalingKeys; ++k) {
        if (!is_finite(to_vec(ch.mScalingKeys[k].mValue))) throw bad("scale");
        track.scale.emplace_back(time(ch.mScalingKeys[k].mTime, "scale"), to_vec(ch.mScalingKeys[k].mValue));
      }
      for (unsigned k = 0; k < ch.mNumRotationKeys; ++k) {
        const aiQuaternion& q = ch.mRotationKeys[k].mValue;
        if (!(std::isfinite(q.w) && std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z))) throw bad("rotation");
        track.rotation.emplace_back(time(ch.mRotationKeys[k].mTime, "rotation"), Quaternion{q.w, q.x, q.y, q.z});
      }
      auto by_time = [](const auto& a, const auto& b) { return a.first < b.first; };
      std::stable_sort(track.translation.begin(), track.translation.end(), by_time);
      std::stable_sort(track.scale.begin(), track.scale.end(), by_time);
      std::stable_sort(track.rotation.begin(), track.rotation.end(), by_time);
      track_of_[ch.mNodeName.C_Str()] = static_cast<int>(animation_->tracks.size());
      animation_->tracks.push_back(std::move(track));
    }
    // Morph weights, keyed per node (glTF animates a node's mesh weights).
    for (unsigned c = 0; c < anim.mNumMorphMeshChannels; ++c) {
      const aiMeshMorphAnim& ch = *anim.mMorphMeshChannels[c];
      auto& keys = morph_keys_[ch.mName.C_Str()];
      for (unsigned k = 0; k < ch.mNumKeys; ++k) {
        const aiMeshMorphKey& key = ch.mKeys[k];
        if (!std::isfinite(key.mTime))
          throw malformed_file(out_.source, fmt::format("node '{}' has a morph weight key at a time that is not finite",
                                                        ch.mName.C_Str()));
        std::vector<double> w;
        for (unsigned i = 0; i < key.mNumValuesAndWeights; ++i) {
          const unsigned target = key.mValues[i];
          if (target >= 1024 || !std::isfinite(key.mWeights[i]))
            throw malformed_file(out_.source, fmt::format("node '{}' has a bad morph weight key (target {}, weight {})",
                                                          ch.mName.C_Str(), target, key.mWeights[i]));
          if (target >= w.size()) w.resize(target + 1, 0.0);
          w[target] = key.mWeights[i];
        }
        keys.emplace_back(key.mTime / tps, std::move(w));
      }
      std::stable_sort(keys.begin(), keys.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    }
  }

  // `world`: the parent's rest transform to the file's frame (lights,
  // cameras, the default view); `rel`: the parent's transform to the frame
  // of the moving part it belongs to (part -1: the file's, standing still).
  // An animated node starts a part of its own: its track replaces its rest
  // transform.
  void walk(const aiNode* node, const aiMatrix4x4& parent_world, const aiMatrix4x4& parent_rel, int part) {
    const aiMatrix4x4 world = parent_world * node->mTransformation;
    global_[node->mName.C_Str()] = world;
    aiMatrix4x4 rel = parent_rel * node->mTransformation;
    if (const auto it = track_of_.find(node->mName.C_Str()); it != track_of_.end()) {
      MeshAnimation::Part p;
      p.node = node->mName.C_Str();
      p.scene.source = out_.source;
      if (part >= 0) p.chain = animation_->parts[static_cast<size_t>(part)].chain;
      p.chain.push_back({to_affine(parent_rel), it->second});
      part = static_cast<int>(animation_->parts.size());
      animation_->parts.push_back(std::move(p));
      rel = aiMatrix4x4();
    }
    if (part >= 0 && camera_ != nullptr && node->mName == camera_->mName) {
      MeshAnimation::Camera cam;
      cam.chain = animation_->parts[static_cast<size_t>(part)].chain;
      cam.fixed = to_affine(rel);
      animation_->camera = cam;  // its lens and angle: read_camera()
    }
    place_[node->mName.C_Str()] = {part, to_affine(rel)};
    Xform xf{rel, aiMatrix3x3(rel)};
    xf.normal.Inverse().Transpose();
    SceneDesc& target = part < 0 ? out_ : animation_->parts[static_cast<size_t>(part)].scene;
    for (unsigned k = 0; k < node->mNumMeshes; ++k) {
      const aiMesh& mesh = *s_.mMeshes[node->mMeshes[k]];
      // Posed once every joint's place is known (after the walk).
      if (mesh.mNumBones > 0 || mesh.mNumAnimMeshes > 0) deforming_.push_back({&mesh, node->mName.C_Str()});
      else add_mesh(mesh, xf, world, target);
    }
    for (unsigned k = 0; k < node->mNumChildren; ++k) walk(node->mChildren[k], world, rel, part);
  }

  // Where a joint node sits: its part's chain, then its frame in that part.
  MeshAnimation::DeformingMesh::Joint joint_at(const std::string& node) const {
    const NodePlace& at = place_.at(node);
    MeshAnimation::DeformingMesh::Joint j;
    if (at.part >= 0) j.chain = animation_->parts[static_cast<size_t>(at.part)].chain;
    j.fixed = at.rel;
    return j;
  }

  // A skinned or morphed mesh: its morph targets and weights, its joints
  // and their weights (MeshAnimation::DeformingMesh), then the mesh posed
  // at time 0 (a shot: a part of its own, which the sequence poses frame by
  // frame) or at rest with the default morph weights (a still: the file's
  // own part).
  void add_deforming_mesh(const aiMesh& mesh, const std::string& node) {
    MeshAnimation::DeformingMesh d;
    d.mesh = mesh.mName.C_Str();
    const unsigned nv = mesh.mNumVertices;
    for (unsigned v = 0; v < nv; ++v) d.vertices.push_back(to_vec(mesh.mVertices[v]));
    if (mesh.HasNormals())
      for (unsigned v = 0; v < nv; ++v) d.normals.push_back(to_vec(mesh.mNormals[v]));
    read_targets(mesh, node, d);
    if (mesh.mNumBones > 0) {
      read_skin(mesh, node, d);
    } else {  // morphed only: its node carries it
      d.joints.push_back(joint_at(node));
      d.first.push_back(0);
      for (unsigned v = 0; v < nv; ++v) {
        d.influences.emplace_back(0, 1.0);
        d.first.push_back(static_cast<uint32_t>(d.influences.size()));
      }
    }
    std::vector<Vec3> vertices, normals;
    pose_mesh(d, animation_ ? d.weights_at(0) : d.weights, animation_ ? animation_->tracks : std::vector<NodeTrack>{},
              0, vertices, normals);
    SceneDesc* target = &out_;
    if (animation_) {
      MeshAnimation::Part p;
      p.node = node;
      p.scene.source = out_.source;
      d.part = animation_->parts.size();
      animation_->parts.push_back(std::move(p));
      target = &animation_->parts.back().scene;
    }
    const size_t before = target->objects.size();
    add_mesh(mesh, Xform{}, aiMatrix4x4(), *target, &vertices, &normals);
    if (animation_ && target->objects.size() > before) animation_->deforming.push_back(std::move(d));
  }

  // The mesh's morph targets (assimp's aiAnimMesh: absolute positions and
  // normals), their default weights and their node's weight keys.
  void read_targets(const aiMesh& mesh, const std::string& node, MeshAnimation::DeformingMesh& d) const {
    const unsigned nv = mesh.mNumVertices;
    for (unsigned k = 0; k < mesh.mNumAnimMeshes; ++k) {
      const aiAnimMesh& am = *mesh.mAnimMeshes[k];
      MeshAnimation::DeformingMesh::Target t;
      t.vertices = d.vertices;
      t.normals = d.normals;
      if (am.HasPositions() && am.mNumVertices == nv)
        for (unsigned v = 0; v < nv; ++v) t.vertices[v] = to_vec(am.mVertices[v]);
      if (am.HasNormals() && am.mNumVertices == nv && !t.normals.empty())
        for (unsigned v = 0; v < nv; ++v) t.normals[v] = to_vec(am.mNormals[v]);
      for (const std::vector<Vec3>* list : {&t.vertices, &t.normals})
        for (const Vec3& p : *list)
          if (!is_finite(p))
            throw malformed_file(out_.source, fmt::format("mesh '{}': morph target {} is not finite", d.mesh, k));
      d.targets.push_back(std::move(t));
      d.weights.push_back(std::isfinite(am.mWeight) ? am.mWeight : 0.0);
    }
    if (const auto it = morph_keys_.find(node); it != morph_keys_.end())
      for (auto [seconds, w] : it->second) {
        w.resize(d.targets.size(), 0.0);  // weights for targets the mesh lacks are dropped
        d.weight_keys.emplace_back(seconds, std::move(w));
      }
  }

  // The mesh's joints and per-vertex weights (aiBone).
  void read_skin(const aiMesh& mesh, const std::string& node, MeshAnimation::DeformingMesh& d) const {
    const unsigned nv = mesh.mNumVertices;
    std::vector<std::vector<std::pair<uint32_t, double>>> of_vertex(nv);
    for (unsigned b = 0; b < mesh.mNumBones; ++b) {
      const aiBone& bone = *mesh.mBones[b];
      if (!place_.count(bone.mName.C_Str()))
        throw malformed_file(out_.source, fmt::format("mesh '{}' is skinned to joint '{}', which is not a node of the "
                                                      "scene",
                                                      d.mesh, bone.mName.C_Str()));
      MeshAnimation::DeformingMesh::Joint j = joint_at(bone.mName.C_Str());
      j.inverse_bind = to_affine(bone.mOffsetMatrix);
      d.joints.push_back(std::move(j));
      for (unsigned k = 0; k < bone.mNumWeights; ++k) {
        const aiVertexWeight& w = bone.mWeights[k];
        if (w.mVertexId >= nv || !std::isfinite(w.mWeight) || w.mWeight < 0)
          throw malformed_file(out_.source, fmt::format("mesh '{}': joint '{}' has a bad weight (vertex {}, weight "
                                                        "{}); expected a vertex below {} and a weight of 0 or more",
                                                        d.mesh, bone.mName.C_Str(), w.mVertexId, w.mWeight, nv));
        if (w.mWeight > 0) of_vertex[w.mVertexId].emplace_back(b, w.mWeight);
      }
    }
    // A vertex without weight stays with the mesh's node: one more joint,
    // that node's frame, binding the identity.
    const auto unweighted = static_cast<uint32_t>(d.joints.size());
    d.joints.push_back(joint_at(node));
    d.first.push_back(0);
    for (auto& list : of_vertex) {
      double sum = 0;
      for (const auto& [j, w] : list) sum += w;
      if (sum > 0)
        for (const auto& [j, w] : list) d.influences.emplace_back(j, w / sum);
      else
        d.influences.emplace_back(unweighted, 1.0);
      d.first.push_back(static_cast<uint32_t>(d.influences.size()));
    }
  }

  // `xf` places the vertices in `target`'s frame; `world` (rest) bounds the
  // default view. `posed` (a skinned mesh's vertices and normals, file
  // frame) replaces the file's vertices and normals.
  void add_mesh(const aiMesh& mesh, const Xform& xf, const aiMatrix4x4& world, SceneDesc& target,
                const std::vector<Vec3>* posed = nullptr, const std::vector<Vec3>* posed_normals = nullptr) {
    if (!(mesh.mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) {
      warn(fmt::format("mesh '{}': points and lines are not rendered", mesh.mName.C_Str()));
      return;
    }
    // One object per mesh, its vertices shared by index (a triangle per
    // object cost ~200 bytes of description per triangle).
    TriangleMeshDesc m;
    m.vertices.reserve(mesh.mNumVertices);
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      const Vec3 p = posed ? (*posed)[v] : xf.point(mesh.mVertices[v]);
      if (!is_finite(p))
        throw malformed_file(out_.source, fmt::format("mesh '{}' has a vertex that is not finite", mesh.mName.C_Str()));
      m.vertices.push_back(p);
    }
    if (mesh.HasNormals()) {
      m.normals.reserve(mesh.mNumVertices);
      // A zero or broken normal in the file becomes zero: the build step
      // puts the triangle's own normal in its place.
      for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
        const Vec3 n = posed_normals ? (*posed_normals)[v] : xf.norm(mesh.mNormals[v]);
        m.normals.push_back(is_finite(n) ? n : Vec3{});
      }
    }
    m.triangles.reserve(mesh.mNumFaces);
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines SortByPType left in a mixed mesh
      m.triangles.push_back({face.mIndices[0], face.mIndices[1], face.mIndices[2]});
      for (unsigned c = 0; c < 3; ++c)
        bounds_.extend(&target == &out_ || posed ? m.vertices[face.mIndices[c]]
                                                 : to_vec(world * mesh.mVertices[face.mIndices[c]]));
    }
    if (m.triangles.empty()) return;
    // The texture coordinates the mesh's material reads, if it has a map.
    const int uv_set = mesh.mMaterialIndex < uv_set_.size() ? uv_set_[mesh.mMaterialIndex] : -1;
    if (uv_set >= 0) {
      if (uv_set < AI_MAX_NUMBER_OF_TEXTURECOORDS && mesh.HasTextureCoords(static_cast<unsigned>(uv_set))) {
        m.uvs.reserve(mesh.mNumVertices);
        for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
          const aiVector3D& t = mesh.mTextureCoords[uv_set][v];
          if (!std::isfinite(t.x) || !std::isfinite(t.y))
            throw malformed_file(out_.source, fmt::format("mesh '{}' has a texture coordinate that is not finite",
                                                          mesh.mName.C_Str()));
          m.uvs.push_back({t.x, t.y});
        }
      } else {
        warn(fmt::format("mesh '{}': its material's texture reads texture coordinate set {}, which the mesh does not "
                         "have (it has {}): the texture is not applied",
                         mesh.mName.C_Str(), uv_set, mesh.GetNumUVChannels()));
      }
    }
    ObjectDesc obj;
    obj.shape = std::move(m);
    obj.material = mesh.mMaterialIndex < out_.materials.size() ? static_cast<int>(mesh.mMaterialIndex) : -1;
    if (&target != &out_ && target.materials.empty()) {
      target.materials = out_.materials;
      target.textures = out_.textures;
      target.images = out_.images;
    }
    target.objects.push_back(std::move(obj));
  }

  aiMatrix4x4 global(const aiString& name) const {
    const auto it = global_.find(name.C_Str());
    return it == global_.end() ? aiMatrix4x4() : it->second;
  }

  // Point, spot and directional lights, placed by their nodes. glTF's
  // (KHR_lights_punctual) keep their photometric meaning: candela for point
  // and spot lights, lux for directional ones, falling off with the square
  // of the distance, converted to the renderer's unit by docs/lights.md's
  // rule (/ 683 lm/W, / pi). Other formats' lights are unitless, as NFF's.
  void read_lights() {
    for (unsigned k = 0; k < s_.mNumLights; ++k) {
      const aiLight& l = *s_.mLights[k];
      const aiMatrix4x4 m = global(l.mName);
      Light light;
      light.position = to_vec(m * l.mPosition);
      light.colour = to_vec(l.mColorDiffuse);
      switch (l.mType) {
        case aiLightSource_POINT: light.kind = LightKind::point; break;
        case aiLightSource_SPOT: light.kind = LightKind::spot; break;
        case aiLightSource_DIRECTIONAL: light.kind = LightKind::directional; break;
        default:
          warn(fmt::format("light '{}': only point, spot and directional lights are rendered", l.mName.C_Str()));
          continue;
      }
      if (light.kind != LightKind::point) {
        const Vec3 d = to_vec(aiMatrix3x3(m) * l.mDirection);
        if (!(length(d) > 0) || !is_finite(d)) {
          warn(fmt::format("light '{}': its direction is zero or not finite; the light is dropped", l.mName.C_Str()));
          continue;
        }
        light.direction = normalize(d);
      }
      if (!is_finite(light.position) || !is_finite(light.colour)) {
        warn(fmt::format("light '{}': not finite; the light is dropped", l.mName.C_Str()));
        continue;
      }
      if (gltf_) {
        light.photometric = true;
        light.colour = light.colour * kGltfLightToRadiance;
        if (light.kind != LightKind::directional) light.kq = 1, light.kc = 0, light.kl = 0;
        if (light.kind == LightKind::spot) {
          // glTF's cone angles are measured from the axis.
          light.fall_end = std::clamp(static_cast<double>(l.mAngleOuterCone), 0.0, std::numbers::pi / 2);
          light.fall_start = std::clamp(static_cast<double>(l.mAngleInnerCone), 0.0, light.fall_end);
          light.smooth_cone = true;
        }
        light.range = light_range(l.mName);
      } else if (light.kind == LightKind::spot) {
        // aiLight's cone angles are full angles; falloff linear in the angle between them.
        light.fall_end = std::clamp(0.5 * l.mAngleOuterCone, 0.0, std::numbers::pi);
        light.fall_start = std::clamp(0.5 * l.mAngleInnerCone, 0.0, light.fall_end);
      }
      out_.lights.push_back(light);
    }
  }

  // KHR_lights_punctual's `range`, which assimp keeps on the light's node; 0: none.
  double light_range(const aiString& name) const {
    const aiNode* node = s_.mRootNode->FindNode(name);
    if (node == nullptr || node->mMetaData == nullptr) return 0;
    float f = 0;
    double d = 0;
    if (node->mMetaData->Get("PBR_LightRange", f)) d = f;
    else if (!node->mMetaData->Get("PBR_LightRange", d)) return 0;
    return d > 0 && std::isfinite(d) ? d : 0;
  }

  // The index of the camera the viewpoint is: the one named in the options,
  // else the file's first; -1: none. Throws std::invalid_argument naming the
  // file's cameras.
  int chosen_camera() const {
    if (options_.camera_name.empty()) return s_.mNumCameras > 0 ? 0 : -1;
    std::string names;
    for (unsigned k = 0; k < s_.mNumCameras; ++k) {
      if (options_.camera_name == s_.mCameras[k]->mName.C_Str()) return static_cast<int>(k);
      names += fmt::format("{}'{}'", k ? ", " : "", s_.mCameras[k]->mName.C_Str());
    }
    throw std::invalid_argument(fmt::format("camera name: '{}' has no camera '{}' ({})", out_.source, options_.camera_name,
                                            names.empty() ? "it has none" : "its cameras: " + names));
  }

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
  void read_lens(const aiCamera& c, Viewpoint& vp) {
    const double aspect = c.mAspect > 0 && std::isfinite(c.mAspect) ? c.mAspect : 0;
    const double a = aspect > 0 ? aspect : 1;
    const double h = c.mHorizontalFOV;
    const auto assimp_at_least = [](unsigned minor) {
      return aiGetVersionMajor() > 5 || (aiGetVersionMajor() == 5 && aiGetVersionMinor() >= minor);
    };
    const auto degrees = [](double radians) { return radians * 180 / std::numbers::pi; };
    using Axis = Viewpoint::FovAxis;
    vp.fov_axis = Axis::horizontal;
    if (c.mOrthographicWidth > 0) {
      vp.ortho_size = 2 * c.mOrthographicWidth;
    } else if (gltf_) {
      vp.angle_deg = degrees(assimp_at_least(3) ? 2 * std::atan(std::tan(h / 2) / a) : h / a);
      vp.fov_axis = Axis::vertical;
    } else if (ext_ == ".irr") {
      vp.angle_deg = degrees(h / a);
      vp.fov_axis = Axis::vertical;
    } else if (ext_ == ".blend") {
      vp.angle_deg = degrees(h);
      vp.fov_axis = Axis::larger;
    } else if (ext_ == ".fbx") {
      vp.angle_deg = degrees(assimp_at_least(4) ? 2 * h : h);
    } else if (ext_ == ".3ds") {
      vp.angle_deg = 2400 / degrees(h);
    } else {
      vp.angle_deg = degrees(h);
    }
    if (!(vp.angle_deg > 0 && vp.angle_deg < 180)) {
      warn(fmt::format("camera '{}': a field of view of {:.4g} deg cannot be rendered; 45 deg instead", c.mName.C_Str(),
                       vp.angle_deg));
      vp.angle_deg = 45;
    }
    // The image the camera was made for, 512 px on its shorter side.
    if (aspect > 0 && aspect != 1) {
      vp.xres = aspect > 1 ? static_cast<int>(std::lround(512 * aspect)) : 512;
      vp.yres = aspect > 1 ? 512 : static_cast<int>(std::lround(512 / aspect));
    }
    vp.camera = c.mName.C_Str();
    if (c.mClipPlaneNear > 0 && std::isfinite(c.mClipPlaneNear)) vp.clip_near = c.mClipPlaneNear;
    // glTF's zfar is optional (an infinite projection, §5.12); assimp fills
    // in 100 where it is missing, keeping the file's camera order.
    const auto k = static_cast<size_t>(camera_index_);
    const bool infinite = gltf_ && k < gltf_infinite_far_.size() && gltf_infinite_far_[k];
    if (!infinite && c.mClipPlaneFar > vp.clip_near && std::isfinite(c.mClipPlaneFar)) vp.clip_far = c.mClipPlaneFar;
  }

  // The distance along the view direction `dir` (unit) from `eye` at which a
  // file camera, which has no point it looks at, places its focal plane: the
  // depth of the scene's bounding-box centre; its distance when the centre
  // lies behind the eye.
  double centre_depth(const Vec3& eye, const Vec3& dir) const {
    const Vec3 to_centre = bounds_.centre() - eye;
    const double depth = dot(to_centre, dir);
    const double d = depth > 0 ? depth : length(to_centre);
    return d > 0 && std::isfinite(d) ? d : 1;
  }

  void read_camera() {
    Viewpoint vp;
    if (camera_ != nullptr) {
      const aiCamera& c = *camera_;
      const aiMatrix4x4 m = global(c.mName);
      // assimp's glTF importer copies the node's translation into mPosition
      // (which the node transform already holds).
      // A keyframed 3DS file's camera (assimp: mLookAt reset to +z) has its
      // first key in the node transform, and its target is lost: it is aimed
      // at the scene's centre instead, with a warning.
      const bool lost_target = ext_ == ".3ds" && c.mLookAt == aiVector3D(0, 0, 1);
      const aiVector3D local_from = gltf_ || lost_target ? aiVector3D(0, 0, 0) : c.mPosition;
      vp.from = to_vec(m * local_from);
      aiVector3D look = ext_ == ".irr" ? c.mLookAt - c.mPosition : c.mLookAt;
      if (lost_target) {
        const Vec3 to_centre = bounds_.centre() - vp.from;
        aiMatrix3x3 to_node(m);
        to_node.Inverse();
        look = to_node * aiVector3D(float(to_centre.x), float(to_centre.y), float(to_centre.z));
        warn(fmt::format("camera '{}': assimp does not keep a keyframed 3DS camera's target; it is aimed at the scene's "
                         "centre instead", c.mName.C_Str()));
      }
      const Vec3 dir = normalize(to_vec(aiMatrix3x3(m) * look));
      vp.up = to_vec(aiMatrix3x3(m) * c.mUp);
      read_lens(c, vp);
      const double focus = centre_depth(vp.from, dir);
      vp.at = vp.from + dir * focus;
      vp.focus = Viewpoint::Focus::scene_centre_depth;
      if (animation_ && animation_->camera) {
        MeshAnimation::Camera& moving = *animation_->camera;
        moving.from = to_vec(local_from);
        moving.look = to_vec(look);
        moving.up = to_vec(c.mUp);
        moving.optics = vp;
        moving.focus_distance = focus;
      }
    } else {
      // A three-quarter view from +z (raised toward +y, moved toward +x),
      // framing the bounding sphere: radius r at distance r / sin(angle / 2),
      // widened so it fills 90 % of the view.
      const Vec3 centre = bounds_.centre();
      const double r = std::fmax(0.5 * length(bounds_.diagonal()), 1e-6);
      vp.angle_deg = 40;
      const double distance = r / std::sin(vp.angle_deg / 2 * std::numbers::pi / 180) / 0.9;
      vp.from = centre + normalize(Vec3{0.5, 0.5, 1}) * distance;
      vp.at = centre;
      vp.up = {0, 1, 0};
    }
    out_.viewpoint = vp;
    if (out_.lights.empty()) {
      Light headlight;
      headlight.position = vp.from;
      headlight.headlight = true;
      out_.lights.push_back(headlight);
    }
  }

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


// A PLY header declares its element counts and assimp's reader trusts them:
// one declaring 10^12 vertices keeps it busy for hours. Every element takes
// at least one byte (ASCII: a digit and a separator; binary: a property), so
// counts beyond the file's size are refused before assimp sees the file.
void check_ply_header(std::ifstream& in, const std::string& path, uintmax_t size) {
  std::string line;
  if (!std::getline(in, line) || (line.rfind("ply", 0) != 0 && line.rfind("PLY", 0) != 0)) return;  // assimp reports it
  uintmax_t declared = 0;
  for (int lines = 0; lines < 10000 && std::getline(in, line); ++lines) {
    if (line.rfind("end_header", 0) == 0) break;
    std::istringstream words(line);
    std::string keyword, name, count;
    if (!(words >> keyword >> name >> count) || keyword != "element") continue;
    uintmax_t n = 0;
    const auto [end, ec] = std::from_chars(count.data(), count.data() + count.size(), n);
    if (ec != std::errc() || end != count.data() + count.size() || n > size || declared + n > size)
      throw malformed_file(path, fmt::format("its header declares {} {} elements, more than a file of {} bytes holds",
                                             count, name, size));
    declared += n;
  }
}

}  // namespace

namespace {
Affine chain_at(const std::vector<MeshAnimation::Link>& chain, const std::vector<NodeTrack>& tracks, double seconds) {
  Affine m;
  for (const MeshAnimation::Link& l : chain) m = m * l.fixed * tracks.at(static_cast<size_t>(l.track)).at(seconds);
  return m;
}
}  // namespace

Affine MeshAnimation::transform(size_t part, double seconds) const {
  return chain_at(parts.at(part).chain, tracks, seconds);
}

Viewpoint MeshAnimation::camera_at(double seconds) const {
  const Camera& c = camera.value();
  const Affine m = chain_at(c.chain, tracks, seconds) * c.fixed;
  Viewpoint vp = c.optics;
  vp.from = m.point(c.from);
  vp.at = vp.from + normalize(m.dir(c.look)) * c.focus_distance;
  vp.up = m.dir(c.up);
  return vp;
}

std::vector<double> MeshAnimation::DeformingMesh::weights_at(double seconds) const {
  if (weight_keys.empty()) return weights;
  if (seconds <= weight_keys.front().first) return weight_keys.front().second;
  if (seconds >= weight_keys.back().first) return weight_keys.back().second;
  size_t hi = 1;
  while (weight_keys[hi].first < seconds) ++hi;
  const auto& [t0, w0] = weight_keys[hi - 1];
  const auto& [t1, w1] = weight_keys[hi];
  const double a = t1 > t0 ? (seconds - t0) / (t1 - t0) : 1.0;
  std::vector<double> w(w0.size());
  for (size_t i = 0; i < w.size(); ++i) w[i] = w0[i] + (w1[i] - w0[i]) * a;
  return w;
}

void pose_mesh(const MeshAnimation::DeformingMesh& mesh, const std::vector<double>& weights,
               const std::vector<NodeTrack>& tracks, double seconds, std::vector<Vec3>& vertices,
               std::vector<Vec3>& normals) {
  std::vector<Affine> joint(mesh.joints.size());
  for (size_t j = 0; j < joint.size(); ++j) {
    const MeshAnimation::DeformingMesh::Joint& at = mesh.joints[j];
    joint[j] = (tracks.empty() ? Affine{} : chain_at(at.chain, tracks, seconds)) * at.fixed * at.inverse_bind;
  }
  const size_t n = mesh.vertices.size();
  vertices.resize(n);
  normals.resize(mesh.normals.empty() ? 0 : n);
  for (size_t v = 0; v < n; ++v) {
    Vec3 p = mesh.vertices[v], nv = normals.empty() ? Vec3{} : mesh.normals[v];
    for (size_t t = 0; t < mesh.targets.size() && t < weights.size(); ++t) {
      if (weights[t] == 0) continue;
      p += (mesh.targets[t].vertices[v] - mesh.vertices[v]) * weights[t];
      if (!normals.empty()) nv += (mesh.targets[t].normals[v] - mesh.normals[v]) * weights[t];
    }
    Affine blend;
    blend.m.fill(0);
    for (uint32_t k = mesh.first[v]; k < mesh.first[v + 1]; ++k) {
      const auto& [j, w] = mesh.influences[k];
      for (int c = 0; c < 9; ++c) blend.m[c] += w * joint[j].m[c];
      blend.translation += joint[j].translation * w;
    }
    vertices[v] = blend.point(p);
    if (!normals.empty()) {
      const Vec3 nn = blend.normal(nv);
      normals[v] = is_finite(nn) ? nn : Vec3{};  // a collapsed blend: the triangle's own normal stands in
    }
  }
}

void MeshAnimation::pose(size_t k, double seconds, std::vector<Vec3>& vertices, std::vector<Vec3>& normals) const {
  const DeformingMesh& d = deforming.at(k);
  pose_mesh(d, d.weights_at(seconds), tracks, seconds, vertices, normals);
}

SceneDesc read_mesh_file(const std::string& path, const MeshLimits& limits, MeshAnimation* animation,
                         const SceneReadOptions& options) {
  std::ifstream in = open_for_reading(path);
  const std::string ext = lower_extension(path);
  std::error_code ec;
  if (ext == ".ply") check_ply_header(in, path, std::filesystem::file_size(path, ec));
  GltfFacts gltf;
  if (ext == ".gltf" || ext == ".glb") gltf = check_gltf(in, path, ext == ".glb");
  Assimp::Importer importer;
  // Points and lines are dropped by SortByPType; triangulated polygons keep
  // their file order. Node transforms are applied by the reader itself, so
  // that cameras and lights move with their nodes.
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const aiScene* scene = importer.ReadFile(path, aiProcess_Triangulate | aiProcess_SortByPType);
  if (!scene || !scene->mRootNode || (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE))
    throw malformed_file(path, importer.GetErrorString());
  if (animation) *animation = MeshAnimation{};
  return MeshReader(*scene, path, ext, limits, animation, options, std::move(gltf.infinite_far)).read();
}

SceneDesc read_scene_file(const std::string& path, MeshAnimation* animation, const SceneReadOptions& options) {
  const std::string ext = lower_extension(path);
  if (animation) *animation = MeshAnimation{};
  if ((ext == ".nff" || ext == ".dat") && !options.camera_name.empty())
    throw std::invalid_argument(fmt::format("camera name: '{}' has one viewpoint and no named cameras", path));
  if (ext == ".nff") return read_nff_file(path);
  if (ext == ".dat") return read_tachyon_file(path);
  return read_mesh_file(path, {}, animation, options);
}

}  // namespace holoray
