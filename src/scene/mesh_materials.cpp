// holoray/scene: a mesh file's materials (mesh_import.hpp).
#include "scene/mesh_import.hpp"

#include "scene/bump_map.hpp"

namespace holoray::mesh_import {

void MeshReader::read_materials() {
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

void MeshReader::read_emission(const aiMaterial& m, Material& mat, int& uv_set) {
  aiColor3D e;
  if (m.Get(AI_MATKEY_COLOR_EMISSIVE, e) != AI_SUCCESS) return;
  float strength = 1;
  m.Get(AI_MATKEY_EMISSIVE_INTENSITY, strength);
  mat.emission = to_vec(e) * static_cast<double>(strength);
  if (!is_finite(mat.emission)) mat.emission = {};
  if (!(mat.emission.x > 0 || mat.emission.y > 0 || mat.emission.z > 0)) return;
  mat.emission_texture = read_map_on_set(m, aiTextureType_EMISSIVE, true, "emissive", uv_set);
}

int MeshReader::read_map_on_set(const aiMaterial& m, aiTextureType type, bool colour, const char* what, int& uv_set) {
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

void MeshReader::read_dissolve_map(const aiMaterial& m, Material& mat, int& uv_set, float opacity) {
  mat.alpha_texture = read_map_on_set(m, aiTextureType_OPACITY, false, "map_d", uv_set);
  if (mat.alpha_texture < 0) return;
  mat.alpha_mask = true;
  mat.alpha = std::clamp(static_cast<double>(opacity), 0.0, 1.0);
  mat.transmittance = 0;
}

void MeshReader::read_highlight(const aiMaterial& m, Material& mat, int& uv_set) {
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

void MeshReader::read_bump_map(const aiMaterial& m, Material& mat, int& uv_set) {
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

void MeshReader::read_data_maps(const aiMaterial& m, Material& mat, int& uv_set) {
  mat.metal_rough_texture = read_map_on_set(m, aiTextureType_UNKNOWN, false, "metallic-roughness", uv_set);
  mat.normal_texture = read_map_on_set(m, aiTextureType_NORMALS, false, "normal", uv_set);
  float scale = 1;
  if (mat.normal_texture >= 0 && m.Get(AI_MATKEY_GLTF_TEXTURE_SCALE(aiTextureType_NORMALS, 0), scale) == AI_SUCCESS &&
      std::isfinite(scale))
    mat.normal_scale = scale;
}

MeshReader::TextureMap MeshReader::read_map(const aiMaterial& m, aiTextureType type, bool colour) {
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

std::array<double, 6> MeshReader::gltf_uv_transform(const aiUVTransform& t) {
  const double r = -t.mRotation, sx = t.mScaling.x, sy = t.mScaling.y;
  const double c = std::cos(r), s = std::sin(r);
  const double ox = t.mTranslation.x - 0.5 * sx * (-c + s + 1);
  const double oy = 0.5 * sy * (s + c - 1) + 1 - sy - t.mTranslation.y;
  const double m00 = c * sx, m01 = s * sy, m10 = -s * sx, m11 = c * sy;  // R S
  // u' = m00 u + m01 (1 - v) + ox;  v' = 1 - (m10 u + m11 (1 - v) + oy)
  return {m00, -m01, m01 + ox, -m10, m11, 1 - m11 - oy};
}

}  // namespace holoray::mesh_import
