// holoray/render: a hit resolved into its surface point, beside the
// materials it reads (RenderScene::surface and what it calls): the normals
// (winding, patch, normal map), the object and material, the surface colour
// from vertex colours or textures at the MIP level of the pixel's
// footprint, glTF's data maps, emission and the alpha cutout Embree asks
// about. render_scene.cpp builds the scene these read.
#include <algorithm>
#include <cmath>

#include "render/render_scene.hpp"
#include "render/textures.hpp"

namespace holoray {

Vec3 RenderScene::surface_colour(const SurfacePoint& sp, double optic_dist) const {
  if (sp.kind == PrimKind::triangle && !tri_colour_.empty()) {
    const size_t t = group_base_[sp.group][0] + size_t{sp.prim};
    if (t < tri_colour_.size() && tri_colour_[t] >= 0) {
      const auto& c = tri_colours_[static_cast<size_t>(tri_colour_[t])];
      const double u = sp.u, v = sp.v;
      return c[0] * (1 - u - v) + c[1] * u + c[2] * v;
    }
  }
  const Material& m = *sp.material;
  if (m.texture < 0) return m.colour;
  const TextureDesc& t = textures_[static_cast<size_t>(m.texture)];
  return texture_colour(t, t.image >= 0 ? &mips_[static_cast<size_t>(t.image)] : nullptr, m.colour, sp.position,
                        optic_dist);
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

SurfacePoint RenderScene::surface(const Ray& ray, const Hit& hit, const PixelFootprint& footprint) const {
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
      const bool moved = !accel_->is_identity(hit.group);
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
  sp.colour = sp.material->colour;
  if (sp.material->texture >= 0 && sp.material->model != ShadingModel::tachyon && hit.kind == PrimKind::triangle)
    sp.colour = textured_colour(sp, hit.u, hit.v, footprint.at(hit.t * length(ray.dir)));
  const Material& m = *sp.material;
  if (m.model == ShadingModel::gltf) {
    sp.metallic = static_cast<float>(m.metallic);
    sp.roughness = static_cast<float>(m.roughness);
  } else if (m.model == ShadingModel::blinn_phong) {
    sp.highlight = 1;
  }
  // Only a mesh's triangles carry texture coordinates.
  const bool data_maps = m.metal_rough_texture >= 0 || m.specular_texture >= 0;
  if (hit.kind == PrimKind::triangle && (data_maps || m.normal_texture >= 0)) {
    const double width = footprint.at(hit.t * length(ray.dir));
    if (data_maps) apply_data_maps(sp, width);
    if (m.normal_texture >= 0) apply_normal_map(sp, width);
  }
  return sp;
}

// glTF 2.0 §3.9.3: metallic in the blue channel, roughness in the green,
// each scaling its factor. MTL's map_Ks (a blinn_phong material's only
// data map): its first channel scales Ks.
void RenderScene::apply_data_maps(SurfacePoint& sp, double width) const {
  const Material& m = *sp.material;
  Vec3 texel;
  if (m.model == ShadingModel::blinn_phong) {
    if (texel_at(m.specular_texture, sp, sp.u, sp.v, width, texel)) sp.highlight = static_cast<float>(texel.x);
  } else if (texel_at(m.metal_rough_texture, sp, sp.u, sp.v, width, texel)) {
    sp.metallic = static_cast<float>(std::clamp(m.metallic * texel.z, 0.0, 1.0));
    sp.roughness = static_cast<float>(std::clamp(m.roughness * texel.y, 0.0, 1.0));
  }
}

// glTF 2.0 §3.9.4: the normal texture's RGB as a tangent-space normal,
// (2c - 1) with x and y times the scale. The tangent frame is the
// triangle's own: the tangent along increasing u, the bitangent along
// increasing v (the image's up, OpenGL's convention, which glTF's normal
// maps and Blender's follow), both made orthonormal to the interpolated
// normal. A file's own TANGENT attribute and a texture transform's
// rotation of the frame are not read.
void RenderScene::apply_normal_map(SurfacePoint& sp, double width) const {
  const Material& m = *sp.material;
  Vec3 texel;
  if (!texel_at(m.normal_texture, sp, sp.u, sp.v, width, texel)) return;
  const size_t t = group_base_[sp.group][0] + size_t{sp.prim};
  const TriangleUv& tu = tri_uvs_[static_cast<size_t>(tri_uv_[t])];  // texel_at found it
  const TriangleData& tris = accel_->geometry(sp.group).triangles;
  const uint32_t* idx = &tris.indices[3 * size_t{sp.prim}];
  auto vertex = [&](int c) {
    const float* p = &tris.positions[3 * size_t{idx[c]}];
    return Vec3{p[0], p[1], p[2]};
  };
  const Vec3 p0 = vertex(0), e1 = vertex(1) - p0, e2 = vertex(2) - p0;
  const double du1 = tu.uv[1][0] - tu.uv[0][0], dv1 = tu.uv[1][1] - tu.uv[0][1];
  const double du2 = tu.uv[2][0] - tu.uv[0][0], dv2 = tu.uv[2][1] - tu.uv[0][1];
  const double det = du1 * dv2 - du2 * dv1;
  if (!(std::fabs(det) > 0)) return;  // the texture is not spread over the triangle: no frame
  Vec3 dpdu = (e1 * dv2 - e2 * dv1) / det, dpdv = (e2 * du1 - e1 * du2) / det;
  if (!accel_->is_identity(sp.group)) {
    const Affine& xf = accel_->transform(sp.group);
    dpdu = xf.dir(dpdu), dpdv = xf.dir(dpdv);
  }
  const Vec3 n = sp.ns;
  const Vec3 along = dpdu - n * dot(n, dpdu);
  if (!(length(along) > 0)) return;
  const Vec3 tangent = normalize(along);
  Vec3 bitangent = cross(n, tangent);
  if (dot(bitangent, dpdv) < 0) bitangent = -bitangent;
  const double x = (2 * texel.x - 1) * m.normal_scale, y = (2 * texel.y - 1) * m.normal_scale, z = 2 * texel.z - 1;
  const Vec3 mapped = tangent * x + bitangent * y + n * z;
  if (length(mapped) > 0) sp.ns = normalize(mapped);
}

Vec3 RenderScene::textured_colour(const SurfacePoint& sp, double u, double v, double width) const {
  const Material& mat = *sp.material;
  Vec3 texel;
  if (!texel_at(mat.texture, sp, u, v, width, texel)) return mat.colour;
  return mul(mat.colour, texel);
}

Vec3 RenderScene::emission(const SurfacePoint& sp, double distance, const PixelFootprint& footprint) const {
  const Material& mat = *sp.material;
  Vec3 texel;
  if (mat.emission_texture < 0 || sp.kind != PrimKind::triangle ||
      !texel_at(mat.emission_texture, sp, sp.u, sp.v, footprint.at(distance), texel))
    return mat.emission;
  return mul(mat.emission, texel);
}

bool RenderScene::texel_at(int texture, const SurfacePoint& sp, double u, double v, double width, Vec3& out) const {
  const TextureDesc& tex = textures_[static_cast<size_t>(texture)];
  if (tex.kind != TextureDesc::Kind::uv_image || tex.image < 0) return false;
  double tu_u, tu_v;
  const TriangleUv* tu = texture_uv(tex, group_base_[sp.group][0] + size_t{sp.prim}, u, v, tu_u, tu_v);
  if (!tu) return false;
  const MipMap& mip = mips_[static_cast<size_t>(tex.image)];
  // The footprint in level-0 texels: world width x texture units per world
  // unit (the transform scales them by the root of its determinant) x texels per unit.
  const auto& m = tex.uv_transform;
  const double texels = width * tu->uv_per_world * std::sqrt(std::fabs(m[0] * m[4] - m[1] * m[3])) *
                        std::sqrt(double(mip.width()) * mip.height());
  const double level = texels > 1 ? std::log2(texels) : 0.0;
  out = mip.sample_uv(tu_u, tu_v, level, tex.wrap_u, tex.wrap_v, tex.nearest, decode_table(tex.srgb));
  return true;
}

const RenderScene::TriangleUv* RenderScene::texture_uv(const TextureDesc& tex, size_t t, double u, double v,
                                                       double& tu_u, double& tu_v) const {
  if (t >= tri_uv_.size() || tri_uv_[t] < 0) return nullptr;
  const TriangleUv& tu = tri_uvs_[static_cast<size_t>(tri_uv_[t])];
  const double w0 = 1 - u - v;
  const double iu = tu.uv[0][0] * w0 + tu.uv[1][0] * u + tu.uv[2][0] * v;
  const double iv = tu.uv[0][1] * w0 + tu.uv[1][1] * u + tu.uv[2][1] * v;
  const auto& m = tex.uv_transform;
  tu_u = m[0] * iu + m[1] * iv + m[2];
  tu_v = m[3] * iu + m[4] * iv + m[5];
  return &tu;
}

bool RenderScene::AlphaCutout::cut(uint32_t group, uint32_t prim, float u, float v) const {
  const size_t t = s_.group_base_[group][0] + size_t{prim};
  const Material& mat = s_.materials_[s_.object_material_[s_.tri_object_[t]]];
  if (!mat.alpha_mask) return false;
  double alpha = mat.alpha;
  // MTL's map_d, else the colour texture's alpha (glTF's MASK).
  const int texture = mat.alpha_texture >= 0 ? mat.alpha_texture : mat.texture;
  if (texture >= 0) {
    const TextureDesc& tex = s_.textures_[static_cast<size_t>(texture)];
    double tu, tv;
    if (tex.kind == TextureDesc::Kind::uv_image && tex.image >= 0 && s_.texture_uv(tex, t, u, v, tu, tv)) {
      const MipMap& mip = s_.mips_[static_cast<size_t>(tex.image)];
      alpha *= mat.alpha_texture < 0 || mip.has_alpha()
                   ? mip.alpha_uv(tu, tv, tex.wrap_u, tex.wrap_v)
                   : mip.sample_uv(tu, tv, 0, tex.wrap_u, tex.wrap_v, tex.nearest, decode_table(false)).x;
    }
  }
  return alpha < mat.alpha_cutoff;
}

}  // namespace holoray
