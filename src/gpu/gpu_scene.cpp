#include "gpu/gpu_scene.hpp"

#include <fmt/format.h>

#include <bit>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "accel/bvh_builder.hpp"
#include "render/emitters.hpp"
#include "render/environment.hpp"
#include "render/gltf_brdf.hpp"

namespace holoray::gpu {

namespace {

vec4 v4(const Vec3& v, float w = 0) { return {float(v.x), float(v.y), float(v.z), w}; }
float bits(int32_t i) { return std::bit_cast<float>(i); }

void extend(PrimitiveBox& b, const Vec3& p) {
  const float q[3] = {float(p.x), float(p.y), float(p.z)};
  for (int a = 0; a < 3; ++a) b.lo[a] = std::fmin(b.lo[a], q[a]), b.hi[a] = std::fmax(b.hi[a], q[a]);
}

PrimitiveBox box_of(const Bounds3& b) {
  // Rounded outward: the float box holds the double one.
  PrimitiveBox out;
  const double lo[3] = {b.lo.x, b.lo.y, b.lo.z}, hi[3] = {b.hi.x, b.hi.y, b.hi.z};
  for (int a = 0; a < 3; ++a) {
    out.lo[a] = std::nextafter(float(lo[a]), -INFINITY);
    out.hi[a] = std::nextafter(float(hi[a]), INFINITY);
  }
  return out;
}

GpuMaterial material_of(const Material& m) {
  GpuMaterial g;
  g.colour_kd = v4(m.colour, float(m.kd));
  g.ks_shine_t_ior = {float(m.ks), float(m.shine), float(m.transmittance), float(m.ior)};
  const int model = m.model == ShadingModel::blinn_phong ? HR_MODEL_BLINN_PHONG
                    : m.model == ShadingModel::tachyon   ? HR_MODEL_TACHYON
                    : m.model == ShadingModel::gltf      ? HR_MODEL_GLTF
                                                         : HR_MODEL_NFF;
  g.emission_model = v4(m.emission, float(model));
  g.specular = v4(m.specular);
  g.tachyon = {float(m.ambient), float(m.phong), m.phong_metal ? 1.0f : 0.0f, m.emitter ? 1.0f : 0.0f};
  g.pbr = {float(m.metallic), float(m.roughness), float(m.transmission), float(dielectric_f0(m.ior))};
  g.alpha = {float(m.alpha), float(m.alpha_cutoff), float(m.normal_scale), 0};
  g.maps = {m.texture, m.metal_rough_texture, m.normal_texture, m.emission_texture};
  g.maps2 = {m.specular_texture, m.alpha_texture, m.alpha_mask ? 1 : 0, 0};
  return g;
}

// Whether a hit on `m` may send both a mirror and a transmitted ray on
// under Whitted's light (trace.comp: push_secondary_rays, shade_tachyon):
// NFF's and Blinn-Phong's with Ks and T, Tachyon's with both over its
// contribution floor, glTF's where it can be a mirror (roughness under
// 0.1, or a roughness map) and lets light through.
bool sends_two_rays(const Material& m) {
  switch (m.model) {
    case ShadingModel::tachyon: {
      constexpr double kMinContrib = 0.5 / 255.0;
      return m.ks > kMinContrib && m.transmittance > kMinContrib;
    }
    case ShadingModel::gltf:
      return (m.roughness < kMirrorRoughness || m.metal_rough_texture >= 0) && (m.transmittance > 0 || m.transmission > 0);
    default:
      return m.ks > 0 && m.transmittance > 0;
  }
}

// Tachyon's texfuncs, and their image maps' levels as uints of RGB8.
void lay_out_textures(const RenderScene& scene, SceneArrays& out) {
  std::vector<int> first_level;  // per image map
  for (const MipMap& mip : scene.mips()) {
    first_level.push_back(static_cast<int>(out.levels.size()));
    for (int k = 0; k < mip.levels(); ++k) {
      const MipMap::Level& l = mip.level(k);
      out.levels.push_back({{l.width, l.height, l.depth, static_cast<int32_t>(out.texels.size())}});
      if (out.texels.size() + l.rgb.size() / 3 > uint64_t{INT32_MAX})
        throw std::length_error("the GPU path holds at most 2^31 texels, the scene's image maps have more");
      const bool alpha = k == 0 && mip.alpha().size() == l.rgb.size() / 3;
      for (size_t t = 0; t + 2 < l.rgb.size(); t += 3)
        out.texels.push_back(uint32_t{l.rgb[t]} | uint32_t{l.rgb[t + 1]} << 8 | uint32_t{l.rgb[t + 2]} << 16 |
                             uint32_t{alpha ? mip.alpha()[t / 3] : uint8_t{255}} << 24);
    }
  }
  for (const TextureDesc& t : scene.textures()) {
    GpuTexture g;
    const bool mapped = t.image >= 0;
    g.kind_level_count = {static_cast<int>(t.kind), mapped ? first_level[size_t(t.image)] : -1,
                          mapped ? scene.mips()[size_t(t.image)].levels() : 0, 0};
    g.centre = v4(t.centre), g.rotate = v4(t.rotate), g.scale = v4(t.scale);
    g.uaxis = v4(t.uaxis), g.vaxis = v4(t.vaxis), g.waxis = v4(t.waxis);
    auto wrap = [](TextureWrap w) { return w == TextureWrap::clamp ? HR_WRAP_CLAMP : w == TextureWrap::mirror ? HR_WRAP_MIRROR : HR_WRAP_REPEAT; };
    g.wrap_filter = {wrap(t.wrap_u), wrap(t.wrap_v), t.nearest ? 1 : 0, t.srgb ? 1 : 0};
    if (mapped) {
      const MipMap& mip = scene.mips()[size_t(t.image)];
      g.alpha_size = {mip.has_alpha() ? 1 : 0, mip.width(), mip.height(), 0};
    }
    const auto& m = t.uv_transform;
    g.uv_m0 = {float(m[0]), float(m[1]), float(m[2]), float(m[3])};
    g.uv_m1 = {float(m[4]), float(m[5]), float(std::sqrt(std::fabs(m[0] * m[4] - m[1] * m[3]))), 0};
    out.textures.push_back(g);
  }
}

GpuLight light_of(const PointLight& l) {
  GpuLight g;
  const int kind = l.kind == LightKind::directional ? HR_LIGHT_DIRECTIONAL : l.kind == LightKind::spot ? HR_LIGHT_SPOT : HR_LIGHT_POINT;
  g.position_kind = v4(l.position, float(kind));
  g.intensity_unit = v4(l.intensity, l.unit_falloff ? 1.0f : 0.0f);
  g.direction = v4(l.direction);
  g.attenuation = {float(l.kc), float(l.kl), float(l.kq), float(l.range)};
  g.cone = {float(l.fall_start), float(l.fall_end), float(l.cos_fall_start), float(l.cos_fall_end)};
  g.direction.w = float(l.kind == LightKind::directional ? l.cos_half_angle : l.radius);
  g.flags = {l.smooth_cone ? 1 : 0, l.headlight ? 1 : 0, 0, 0};
  return g;
}

}  // namespace

uint64_t SceneArrays::bytes() const {
  return nodes.size() * sizeof(GpuNode) + refs.size() * 4 + triangles.size() * sizeof(GpuTriangle) +
         (patches.size() + colours.size()) * sizeof(GpuPatch) + uvs.size() * sizeof(GpuUv) + spheres.size() * sizeof(GpuSphere) + cones.size() * sizeof(GpuCone) +
         object_material.size() * 4 + materials.size() * sizeof(GpuMaterial) + lights.size() * sizeof(GpuLight) +
         textures.size() * sizeof(GpuTexture) + levels.size() * sizeof(GpuLevel) + texels.size() * 4 +
         area_lights.size() * sizeof(GpuAreaLight) + environment.size() * sizeof(GpuEnvTexel) + emitters.size() * sizeof(GpuEmitter);
}

void check_stack(int depth, int width) {
  // A node pushes at most width - 1 more children than it pops: the
  // traversal's stack (HR_STACK entries) must hold (width - 1) (depth - 1) + 1.
  if ((width - 1) * (depth - 1) + 1 > HR_STACK)
    throw std::length_error(fmt::format("the scene's hierarchy is {} levels deep, more than the GPU path's stack holds ({})",
                                        depth, (HR_STACK - 1) / (width - 1) + 1));
}

namespace {

// The hierarchy over `boxes`: `kept`'s refitted while its cost stays within
// kRefitGrowth of its build's, else built at `quality` (and kept).
Bvh hierarchy(const std::vector<PrimitiveBox>& boxes, BvhQuality quality, int bvh_width, KeptBvh* kept) {
  if (kept && kept->bvh.width == bvh_width && kept->primitives == boxes.size() && !kept->bvh.nodes.empty()) {
    Bvh refitted = kept->bvh;
    refit_bvh(refitted, boxes);
    if (bvh_cost(refitted, boxes) <= kRefitGrowth * kept->built_cost) {
      ++kept->refits;
      return refitted;
    }
  }
  Bvh built = build_bvh(boxes, 4, quality, bvh_width);
  if (kept) {
    kept->bvh = built;
    kept->primitives = boxes.size();
    kept->built_cost = bvh_cost(built, boxes);
    ++kept->builds;
  }
  return built;
}

}  // namespace

SceneArrays lay_out(const RenderScene& scene, BvhQuality quality, int bvh_width, KeptBvh* kept) {
  const AccelScene& accel = scene.accel();
  SceneArrays out;
  std::vector<PrimitiveBox> boxes;
  auto add_ref = [&](uint32_t kind, size_t index, const PrimitiveBox& box) {
    if (index >= (size_t{1} << HR_PRIM_SHIFT))
      throw std::length_error(fmt::format("the GPU path holds at most {} primitives of a kind, the scene has more",
                                          size_t{1} << HR_PRIM_SHIFT));
    out.refs.push_back(kind << HR_PRIM_SHIFT | static_cast<uint32_t>(index));
    boxes.push_back(box);
  };
  for (uint32_t g = 0; g < accel.group_count(); ++g) {
    const GeometryGroup& geo = accel.geometry(g);
    const Affine& xf = accel.transform(g);
    const bool moved = !accel.is_identity(g);
    out.group_first_triangle.push_back(static_cast<uint32_t>(out.triangles.size()));
    const auto& pos = geo.triangles.positions;
    const auto& idx = geo.triangles.indices;
    for (uint32_t t = 0; t * 3 < idx.size(); ++t) {
      Vec3 v[3];
      for (int c = 0; c < 3; ++c) {
        const size_t at = size_t{idx[t * 3 + c]} * 3;
        const Vec3 p{pos[at], pos[at + 1], pos[at + 2]};
        v[c] = moved ? xf.point(p) : p;
      }
      GpuTriangle tri;
      int32_t mapped = -1;
      std::array<std::array<float, 2>, 3> uv;
      float uv_per_world = 0;
      if (scene.triangle_uv(g, t, uv, uv_per_world)) {
        mapped = static_cast<int32_t>(out.uvs.size());
        out.uvs.push_back({{uv[0][0], uv[0][1], uv[1][0], uv[1][1]}, {uv[2][0], uv[2][1], uv_per_world, 0}});
      }
      tri.v0 = v4(v[0], bits(mapped));
      int32_t patch = -1;
      if (const auto* n = scene.vertex_normals(g, t)) {
        patch = static_cast<int32_t>(out.patches.size());
        GpuPatch pn;
        const Vec3 nn[3] = {moved ? xf.normal((*n)[0]) : (*n)[0], moved ? xf.normal((*n)[1]) : (*n)[1],
                            moved ? xf.normal((*n)[2]) : (*n)[2]};
        pn.n0 = v4(nn[0]), pn.n1 = v4(nn[1]), pn.n2 = v4(nn[2]);
        out.patches.push_back(pn);
      }
      tri.v1 = v4(v[1], bits(patch));
      int32_t coloured = -1;
      if (const auto* c = scene.vertex_colours(g, t)) {
        coloured = static_cast<int32_t>(out.colours.size());
        out.colours.push_back({v4((*c)[0]), v4((*c)[1]), v4((*c)[2])});
      }
      tri.v2 = v4(v[2], bits(coloured));
      const Vec3& wn = scene.winding_normal(g, t);
      tri.ng = v4(moved ? xf.normal(wn) : wn, bits(scene.object_of(g, PrimKind::triangle, t)));
      PrimitiveBox b{{INFINITY, INFINITY, INFINITY}, {-INFINITY, -INFINITY, -INFINITY}};
      for (const Vec3& p : v) extend(b, p);
      add_ref(HR_PRIM_TRIANGLE, out.triangles.size(), b);
      out.triangles.push_back(tri);
    }
    for (uint32_t s = 0; s < geo.spheres.size(); ++s) {
      Sphere sp = geo.spheres[s];
      if (moved) {  // a rigid motion with uniform scale keeps a sphere one
        const Vec3 c = xf.point(sp.centre);
        const double scale = length(xf.dir(Vec3{1, 0, 0}));
        sp.centre = c, sp.radius *= scale;
      }
      GpuSphere gs;
      gs.centre_radius = v4(sp.centre, float(sp.radius));
      gs.info = {scene.object_of(g, PrimKind::sphere, s), sp.casts_shadow ? 1 : 0, 0, 0};
      add_ref(HR_PRIM_SPHERE, out.spheres.size(), box_of(bounds_of(sp)));
      out.spheres.push_back(gs);
    }
    for (uint32_t c = 0; c < geo.cones.size(); ++c) {
      Cone cone = geo.cones[c];
      if (moved) {
        const double scale = length(xf.dir(Vec3{1, 0, 0}));
        cone.base = xf.point(cone.base), cone.apex = xf.point(cone.apex);
        cone.base_radius *= scale, cone.apex_radius *= scale;
      }
      const PreparedCone pc = prepare_cone(cone);
      GpuCone gc;
      gc.base_rb = v4(pc.cone.base, float(pc.rb));
      gc.axis_len = v4(pc.a, float(pc.len));
      gc.k_sign = {float(pc.k), cone.base_radius < 0 ? -1.0f : 1.0f, bits(scene.object_of(g, PrimKind::cone, c)), 0};
      add_ref(HR_PRIM_CONE, out.cones.size(), box_of(bounds_of(cone)));
      out.cones.push_back(gc);
    }
  }
  // Embree's builder over the primitives' boxes; the leaves' references
  // in its order.
  // Leaves of up to 4 primitives: 2 and 8 measured the same (within 0.5 %
  // on balls_s4 and gears_s4, 3840x2160, H200).
  const Bvh bvh = hierarchy(boxes, quality, bvh_width, kept);
  out.bvh_depth = bvh.depth;
  check_stack(bvh.depth, bvh.width);
  if (bvh.width == 8) out.features |= HR_FEATURE_WIDE_BVH;
  std::vector<uint32_t> refs;
  refs.reserve(bvh.order.size());
  for (uint32_t k : bvh.order) refs.push_back(out.refs[k]);
  out.refs = std::move(refs);
  // An 8-wide node is two records in a row, children 0 to 3 and 4 to 7; a
  // child's index counts nodes, not records.
  out.nodes.reserve(bvh.nodes.size() * size_t(bvh.width / 4));
  for (const BvhNode& n : bvh.nodes)
    for (int half = 0; half < bvh.width / 4; ++half) {
      GpuNode g;
      float* lo[3] = {&g.lo_x.x, &g.lo_y.x, &g.lo_z.x};
      float* hi[3] = {&g.hi_x.x, &g.hi_y.x, &g.hi_z.x};
      const int c0 = 4 * half;
      for (int a = 0; a < 3; ++a)
        for (int c = 0; c < 4; ++c) lo[a][c] = n.lo[a][c0 + c], hi[a][c] = n.hi[a][c0 + c];
      g.index = {n.index[c0], n.index[c0 + 1], n.index[c0 + 2], n.index[c0 + 3]};
      g.count = {n.count[c0], n.count[c0 + 1], n.count[c0 + 2], n.count[c0 + 3]};
      out.nodes.push_back(g);
    }
  for (size_t o = 0; o < scene.object_count(); ++o) out.object_material.push_back(scene.material_of_object(int(o)));
  for (const Material& m : scene.materials()) {
    out.materials.push_back(material_of(m));
    if (m.model == ShadingModel::tachyon) out.features |= HR_FEATURE_TACHYON;
    if (m.model == ShadingModel::gltf) out.features |= HR_FEATURE_GLTF;
    if (m.model != ShadingModel::tachyon && (m.texture >= 0 || m.metal_rough_texture >= 0 || m.normal_texture >= 0 ||
                                            m.emission_texture >= 0 || m.specular_texture >= 0))
      out.features |= HR_FEATURE_MESH_TEXTURES;
    if (m.alpha_mask) out.features |= HR_FEATURE_ALPHA_MASKS;
    out.whitted_branches = out.whitted_branches || sends_two_rays(m);
  }
  for (const PointLight& l : scene.lights()) out.lights.push_back(light_of(l));
  lay_out_textures(scene, out);
  // Empty arrays still bind a buffer: one zero record each.
  if (out.refs.empty()) out.refs.push_back(0);
  if (out.triangles.empty()) out.triangles.emplace_back();
  if (out.patches.empty()) out.patches.emplace_back();
  if (out.colours.empty()) out.colours.emplace_back();
  if (out.uvs.empty()) out.uvs.emplace_back();
  if (out.spheres.empty()) out.spheres.emplace_back();
  if (out.cones.empty()) out.cones.emplace_back();
  if (out.object_material.empty()) out.object_material.push_back(0);
  if (out.materials.empty()) out.materials.emplace_back();
  if (out.lights.empty()) out.lights.emplace_back();
  if (out.textures.empty()) out.textures.emplace_back();
  if (out.levels.empty()) out.levels.emplace_back();
  if (out.texels.empty()) out.texels.push_back(0);
  out.area_lights.emplace_back();
  out.environment.emplace_back();
  out.emitters.emplace_back();
  return out;
}

SceneArrays lay_out(const RenderContext& context, BvhQuality quality, int bvh_width, KeptBvh* kept) {
  SceneArrays out = lay_out(context.scene(), quality, bvh_width, kept);
  if (context.settings().integrator == Integrator::path) lay_out_path(context, out);
  return out;
}

void lay_out_path(const RenderContext& context, SceneArrays& out) {
  out.features |= HR_FEATURE_PATH;
  out.area_lights.clear();
  for (const AreaLight& a : context.scene().area_lights()) {
    GpuAreaLight g;
    g.centre_ellipse = v4(a.centre, a.ellipse ? 1.0f : 0.0f);
    g.axis_u_area = v4(a.axis_u, float(a.area));
    g.axis_v = v4(a.axis_v);
    g.normal = v4(a.normal);
    g.radiance = v4(a.radiance);
    out.area_lights.push_back(g);
  }
  out.environment.clear();
  if (const EnvironmentMap* env = context.settings().environment; env && !env->constant() && !env->black()) {
    const size_t n = env->keep().size();
    if (n >= (size_t{1} << 31)) throw std::length_error("the environment image has more texels than the GPU path indexes (2^31)");
    out.environment.resize(n);
    for (size_t t = 0; t < n; ++t) {
      const float* rgb = &env->texels()[t * 3];
      out.environment[t].radiance_share = {rgb[0], rgb[1], rgb[2], env->share()[t]};
      out.environment[t].keep_alias = {env->keep()[t], std::bit_cast<float>(env->alias()[t]), 0, 0};
    }
  }
  out.emitters.clear();
  if (const EmissiveTriangles* e = context.settings().emitters) {
    for (size_t k = 0; k < e->size(); ++k) {
      const EmissiveTriangles::Entry t = e->entry(k);
      const uint32_t tri = out.group_first_triangle.at(t.group) + t.prim;
      out.emitters.push_back({{float(t.cdf), std::bit_cast<float>(tri), float(t.pick), float(t.area)}});
    }
  }
  if (out.area_lights.empty()) out.area_lights.emplace_back();
  if (out.environment.empty()) out.environment.emplace_back();
  if (out.emitters.empty()) out.emitters.emplace_back();
}

namespace {

// What every camera's frame holds: the scene's constants, the AOVs wanted,
// the rows rendered, and the renderer's box (the scene's bounds grown
// by epsilon: renderer.cpp, grown()) that lens arrays and panels clip to.
GpuFrame scene_frame(const RenderContext& context, const AovSet& aovs, int row0, int row1) {
  GpuFrame f{};
  const double eps = context.epsilon();
  f.clip = {0, INFINITY, float(eps), 0};
  const int bits_ = (aovs.albedo ? HR_AOV_ALBEDO : 0) | (aovs.depth ? HR_AOV_DEPTH : 0) | (aovs.normal ? HR_AOV_NORMAL : 0) |
                    (aovs.id ? HR_AOV_ID : 0);
  f.counts = {int(context.lights().size()), bits_, context.max_depth(), int(context.object_count())};
  f.rows = {row0, row1, 0, 0};
  const Bounds3& b = context.bounds();
  if (b.empty()) {  // nothing to meet: a box no line crosses
    f.box_lo = {0, 0, 0, float(eps)}, f.box_hi = {0, 0, 0, 1};  // w = 1: the shader traces nothing
  } else {
    f.box_lo = v4(b.lo - Vec3{eps, eps, eps}, float(eps));
    f.box_hi = v4(b.hi + Vec3{eps, eps, eps});
  }
  f.background = v4(context.background());
  f.ambient = v4(context.ambient());
  if (const auto& fog = context.fog()) {
    const int mode = fog->mode == FogDesc::Mode::linear ? HR_FOG_LINEAR : fog->mode == FogDesc::Mode::exp ? HR_FOG_EXP : HR_FOG_EXP2;
    f.fog = v4(fog->colour, float(mode));
    f.fog_range = {float(fog->start), float(fog->end), float(fog->density), 0};
  }
  f.flags = {context.has_tachyon_transparency() ? 1 : 0, 0, 0, 0};
  f.footprint = {float(context.settings().footprint.base), float(context.settings().footprint.spread), 0, 0};
  const RenderSettings& rs = context.settings();
  if (rs.integrator == Integrator::path) {
    const EnvironmentMap* env = rs.environment;
    const bool image = env && !env->constant() && !env->black();
    const EmissiveTriangles* e = rs.emitters;
    f.path_counts = {int(context.scene().area_lights().size()), e ? int(e->size()) : 0, image ? env->width() : 0,
                     image ? env->height() : 0};
    f.path_flags = {env && env->up() == EnvironmentUp::y ? 1 : 0, rs.principled ? 1 : 0, rs.skip_headlights ? 1 : 0,
                    env && !env->black() ? 1 : 0};
    f.env_constant = v4(env ? env->constant_radiance() : context.background(), e && !e->empty() ? float(1 / e->total_power()) : 0.0f);
    f.env_turn = {env ? env->cos_rotation() : 1.0f, env ? env->sin_rotation() : 0.0f, std::bit_cast<float>(rs.sample_salt), 0};
  }
  return f;
}

void set_frame(GpuFrame& f, const Frame& fr) {
  f.origin = v4(fr.origin), f.axis_x = v4(fr.x), f.axis_y = v4(fr.y), f.axis_z = v4(fr.z);
}

// F.mode.y names a lens array's grid as the shared line functions do.
static_assert(HR_GRID_SQUARE == HR_LINE_GRID_SQUARE && HR_GRID_HEX == HR_LINE_GRID_HEX &&
              HR_GRID_LENTICULAR == HR_LINE_GRID_LENTICULAR);
int grid_of(Grid g) { return g == Grid::square ? HR_GRID_SQUARE : g == Grid::hex ? HR_GRID_HEX : HR_GRID_LENTICULAR; }

// x's leading 10 significant bits: i x_hi is exact in float for i < 2^14.
double high_part(double x) {
  if (x == 0 || !std::isfinite(x)) return 0;
  const double scale = std::ldexp(1.0, 9 - std::ilogb(x));
  return std::trunc(x * scale) / scale;
}
double fraction(double x) { return x - std::floor(x); }

// A CPU camera's constants in float, as the kernel reads them (GpuFrame).
// Each field is named, so that one added to camera/line_constants.h and not
// here is a compiler warning (missing initializer).
HrLensGrid narrowed(const camera_lines::HrLensGrid& g) {
  return {.grid = g.grid, .pixels_per_lens = g.pixels_per_lens, .lenses_x = g.lenses_x, .lenses_y = g.lenses_y,
          .converging = g.converging, .pitch = float(g.pitch), .gap = float(g.gap), .s = float(g.s), .half_w = float(g.half_w),
          .half_h = float(g.half_h), .row_step = float(g.row_step), .view_distance = float(g.view_distance)};
}
HrPanelGrid narrowed(const camera_lines::HrPanelGrid& g) {
  return {.grid = g.grid, .converging = g.converging, .pitch = float(g.pitch), .gap = float(g.gap),
          .sample_width = float(g.sample_width), .pixel_pitch = float(g.pixel_pitch), .half_w = float(g.half_w),
          .half_h = float(g.half_h), .left = float(g.left), .row_step = float(g.row_step), .sin_slant = float(g.sin_slant),
          .cos_slant = float(g.cos_slant), .view_distance = float(g.view_distance)};
}
HrPinhole narrowed(const camera_lines::HrPinhole& c) {
  return {.width = c.width, .height = c.height, .ortho = c.ortho, .pixel = float(c.pixel), .sample_u = float(c.sample_u),
          .sample_v = float(c.sample_v), .shift_x = float(c.shift_x), .shift_y = float(c.shift_y)};
}
HrLookingGlass narrowed(const camera_lines::HrLookingGlass& g) {
  return {.centre = narrowed(g.centre), .views = g.views, .view_cone_deg = float(g.view_cone_deg), .distance = float(g.distance)};
}

}  // namespace

GpuFrame frame_constants(const RenderContext& context, const LensArray& camera, const AovSet& aovs, int spp, int row0,
                         int row1) {
  const LensArrayDesc& d = camera.desc();
  GpuFrame f = scene_frame(context, aovs, row0, row1);
  set_frame(f, d.frame);
  f.lens_grid = narrowed(camera.line_constants());
  f.size = {camera.width(), camera.height(), 0, 0};
  f.mode = {0, grid_of(d.grid), d.mode == RecordingMode::orthoscopic ? HR_ORTHOSCOPIC : HR_PSEUDOSCOPIC, spp};
  f.tile = {0, 0, camera.width(), 0};
  return f;
}

GpuFrame frame_constants(const RenderContext& context, const PinholeCamera& camera, const AovSet& aovs, int spp, int row0,
                         int row1) {
  const PinholeDesc& d = camera.desc();
  GpuFrame f = scene_frame(context, aovs, row0, row1);
  set_frame(f, camera.frame());
  f.pinhole = narrowed(camera.line_constants());
  f.size = {camera.width(), camera.height(), 0, 0};
  // The normals face the eye, as a pseudoscopic array's face the lens.
  f.mode = {0, HR_PINHOLE, HR_PSEUDOSCOPIC, spp};
  f.tile = {0, 0, camera.width(), 0};
  // Not clipped to the box: w of box_hi alone says whether the scene is empty.
  f.box_lo = {0, 0, 0, 0}, f.box_hi = {0, 0, 0, context.bounds().empty() ? 1.0f : 0.0f};
  f.clip.x = float(d.clip_near), f.clip.y = float(d.clip_far);
  return f;
}

GpuFrame frame_constants(const RenderContext& context, const DisplayCamera& camera, bool red_first, int spp, int row0,
                         int row1) {
  const DisplayGeometry& g = camera.geometry();
  GpuFrame f = scene_frame(context, AovSet{}, row0, row1);
  set_frame(f, g.frame);
  f.panel_grid = narrowed(camera.line_constants());
  f.size = {camera.width(), camera.height(), 0, 0};
  f.mode = {0, HR_DISPLAY, g.mode == RecordingMode::orthoscopic ? HR_ORTHOSCOPIC : HR_PSEUDOSCOPIC, spp};
  f.tile = {0, 0, g.width, 0};
  f.panel_kind = {g.samples_per_pixel, red_first ? 1 : 0, 0, 0};
  return f;
}

GpuFrame frame_constants(const RenderContext& context, const LookingGlassCamera& camera, int spp, int row0, int row1) {
  const LookingGlassCalibration& c = camera.calibration();
  GpuFrame f = scene_frame(context, AovSet{}, row0, row1);
  set_frame(f, camera.frame());
  f.looking_glass = narrowed(camera.line_constants());
  f.size = {camera.width(), camera.height(), 0, 0};
  f.mode = {0, HR_LOOKING_GLASS, HR_PSEUDOSCOPIC, spp};
  f.tile = {0, 0, c.width, 0};
  f.box_lo = {0, 0, 0, 0}, f.box_hi = {0, 0, 0, context.bounds().empty() ? 1.0f : 0.0f};  // eye rays, unclipped
  // looking_glass_view()'s phase, a = (u + s subp + v tilt) L - center
  // with u = (i + 1/2) / W and v = (H - j - 1/2) / H, as i A + j B + K_s
  // with K_s (the cell's subpixel offsets and the constant) taken mod 1 here,
  // in double: the shader's float sees only fractions.
  const double W = c.width, H = c.height, flip = c.flip_x ? -1 : 1;
  const double tilt = H / (W * c.slope) * flip;
  const double L = c.pitch * W / c.dpi * std::cos(std::atan(1 / c.slope));
  const double A = L / W, B = -tilt * L / H, C = 0.5 * L / W + (H - 0.5) / H * tilt * L - c.center;
  f.panel = {float(high_part(A)), float(A - high_part(A)), float(high_part(B)), float(B - high_part(B))};
  f.panel_kind = {3, 1, 0, 0};
  f.cell_kind = {c.cell_pattern, int(c.cells.size()), 0, 0};
  if (c.cells.empty()) {
    for (int s = 0; s < 3; ++s) (&f.cells[0].x)[s] = float(fraction(s * (flip / (3 * W)) * L + C));
  } else {
    for (size_t k = 0; k < c.cells.size(); ++k)
      for (int s = 0; s < 3; ++s)
        (&f.cells[k].x)[s] = float(fraction((c.cells[k].dx[s] / W + c.cells[k].dy[s] / H * tilt) * L + C));
  }
  return f;
}

std::vector<GpuFrame> quilt_frames(const RenderContext& context, const QuiltCamera& camera, const AovSet& aovs, int spp) {
  const QuiltDesc& q = camera.desc();
  std::vector<GpuFrame> out;
  for (int k = 0; k < q.columns * q.rows; ++k) {
    GpuFrame f = frame_constants(context, camera.view(k), aovs, spp, 0, q.view_height);
    // View 0 is the bottom left tile (QuiltCamera::view_at).
    f.tile = {k % q.columns * q.view_width, (q.rows - 1 - k / q.columns) * q.view_height, camera.width(), 0};
    out.push_back(f);
  }
  return out;
}

std::vector<GpuFrame> camera_frames(const RenderContext& context, const FrameCamera& camera, const AovSet& aovs, int spp,
                                    int row0, int row1) {
  if (const auto* quilt = camera.get<QuiltCamera>()) return quilt_frames(context, *quilt, aovs, spp);
  if (const auto* view = camera.get<PinholeCamera>()) return {frame_constants(context, *view, aovs, spp, row0, row1)};
  if (const auto* panel = camera.get<PanelView>())
    return {frame_constants(context, panel->camera, panel->red_first, spp, row0, row1)};
  if (const auto* glass = camera.get<LookingGlassCamera>()) return {frame_constants(context, *glass, spp, row0, row1)};
  return {frame_constants(context, *camera.lens_array(), aovs, spp, row0, row1)};
}

bool renders_panel(const FrameCamera& camera) { return camera.get<PanelView>() || camera.get<LookingGlassCamera>(); }

}  // namespace holoray::gpu
