// holoray/gpu: the records the host writes and the compute shaders read,
// declared once for both (std430: every member a 16-byte vector, or, last
// in GpuFrame, a record of 4-byte scalars, so C++ and GLSL agree on every
// offset). Included by gpu_scene.hpp (C++) and by
// trace.comp (GLSL, through glslc's #include). World frame, scene units,
// float; the CPU path keeps doubles, and the tests hold the two together.
#ifndef HOLORAY_GPU_LAYOUT_H
#define HOLORAY_GPU_LAYOUT_H

#ifdef __cplusplus
#include <cstdint>
namespace holoray::gpu {
struct vec4 { float x = 0, y = 0, z = 0, w = 0; };
struct ivec4 { int32_t x = 0, y = 0, z = 0, w = 0; };
struct uvec4 { uint32_t x = 0, y = 0, z = 0, w = 0; };
#define HR_STRUCT struct alignas(16)
// The cameras' constants in float, as the kernel reads them (GpuFrame).
using hr_real = float;
#include "camera/line_constants.h"
#else
#define HR_STRUCT struct
#include "camera/pixel_lines.h"
#endif

// Primitive references in a leaf: the kind in the top two bits.
#define HR_PRIM_TRIANGLE 0u
#define HR_PRIM_SPHERE 1u
#define HR_PRIM_CONE 2u
#define HR_PRIM_SHIFT 30

// Grid and recording mode (camera/lens_array.hpp's enums).
#define HR_GRID_SQUARE 0
#define HR_GRID_HEX 1
#define HR_GRID_LENTICULAR 2
#define HR_PINHOLE 3  // not a grid: the scene's pinhole view (camera/pinhole.hpp)
#define HR_DISPLAY 4  // a display's panel (camera/display_camera.hpp): its grid in GpuFrame::panel_grid
#define HR_LOOKING_GLASS 5  // a Looking Glass's native panel (display/looking_glass.hpp)
#define HR_ORTHOSCOPIC 0
#define HR_PSEUDOSCOPIC 1

// Material models the GPU path shades (scene_desc.hpp, ShadingModel).
#define HR_MODEL_NFF 0
#define HR_MODEL_BLINN_PHONG 1
#define HR_MODEL_TACHYON 2
#define HR_MODEL_GLTF 3

// Tachyon's texfuncs (scene_desc.hpp, TextureDesc::Kind).
#define HR_TEX_CHECKER3D 1
#define HR_TEX_WOOD 4
#define HR_TEX_CYLINDER_CHECKER 6
#define HR_TEX_CYLINDRICAL_IMAGE 7
#define HR_TEX_SPHERICAL_IMAGE 8
#define HR_TEX_PLANAR_IMAGE 9
#define HR_TEX_VOLUME_IMAGE 10
#define HR_TEX_UV_IMAGE 100  // a mesh's image, read at the hit's texture coordinates

// A mesh texture's wrap modes (scene_desc.hpp, TextureWrap).
#define HR_WRAP_REPEAT 0
#define HR_WRAP_CLAMP 1
#define HR_WRAP_MIRROR 2

// What a scene needs of the kernel (SceneArrays::features): its materials'
// models and maps, its hierarchy's width.
#define HR_FEATURE_TACHYON 1u
#define HR_FEATURE_GLTF 2u
#define HR_FEATURE_MESH_TEXTURES 4u
#define HR_FEATURE_ALPHA_MASKS 8u
#define HR_FEATURE_WIDE_BVH 16u
// The path integrator (RenderSettings::integrator path): its kernel, and
// the area lights, environment and emitters it samples.
#define HR_FEATURE_PATH 32u

// Fog modes (scene_desc.hpp, FogDesc), 0 for none.
#define HR_FOG_LINEAR 1
#define HR_FOG_EXP 2
#define HR_FOG_EXP2 3

// Light kinds (scene_desc.hpp, LightKind).
#define HR_LIGHT_POINT 0
#define HR_LIGHT_DIRECTIONAL 1
#define HR_LIGHT_SPOT 2

// AOV bits of GpuFrame::aovs.
#define HR_AOV_ALBEDO 1
#define HR_AOV_DEPTH 2
#define HR_AOV_NORMAL 4
#define HR_AOV_ID 8

// The deepest ray tree (render.hpp kMaxDepth) and the traversal stack.
#define HR_MAX_DEPTH 16
#define HR_STACK 64

// Subpixel cells of a Looking Glass calibration (looking_glass.hpp, kMaxSubpixelCells).
#define HR_MAX_CELLS 10

// Pairs of work counters per band of rows (gpu_renderer.cpp sums them).
#define HR_COUNT_SLOTS 64

// The shadow pass's invocations each cover this many queued shadow rays
// (their subgroup's share; gpu_renderer.cpp sizes the dispatch by it), few
// enough that lavapipe's 65535 loop iterations hold them.
#define HR_SHADOW_RAYS_PER_LANE 8

// The wavefront of both integrators (trace.comp's kWaveStage,
// wavefront.glsl, whitted_wavefront.glsl): its kernels, each a pipeline.
// Shade is the whole module's, told the vertex it works on (push constant
// `depth`: a vertex 1 to max_depth + 1, or Whitted's step); the others are
// a small module's (HR_TRAVERSAL_KERNELS), quick to compile and to run.
#define HR_WAVE_OFF 0
#define HR_WAVE_SHADING 1  // shade (each hit: light added, shadow rays written, the next ray queued)
#define HR_WAVE_EXTEND 2   // the queued paths' rays to their nearest hits (lanes fetch rays)
#define HR_WAVE_SHADOW 3   // the shadow rays traced, any hit (lanes fetch rays); blocked terms zeroed
#define HR_WAVE_ARGS 4     // one invocation: the next dispatches' sizes from the queues' counts
#define HR_WAVE_START 5    // eye rays: each pixel's path (or ray tree) begun, queued
#define HR_WAVE_FINISH 6   // the last shadow terms added, the sample written
// The rays a Whitted pixel's stack holds in the wavefront
// (whitted_wavefront.glsl): walked depth first, a tree never holds more
// waiting than one sibling a depth and two at the deepest hit.
#define HR_WAVE_STACK_RAYS(max_depth) ((max_depth) + 1)
// The wavefront's queue heads: the paths' for each vertex (1 to
// HR_MAX_DEPTH + 1, and the one after, never filled), then the shadow
// rays' made at each (wavefront.glsl); Whitted's steps, which may be more,
// take them in turn.
#define HR_WAVE_VERTICES (HR_MAX_DEPTH + 3)
#define HR_WAVE_HEADS (2 * HR_WAVE_VERTICES)

/// One 4-wide BVH node, or half of an 8-wide one (HR_FEATURE_WIDE_BVH:
/// children 0 to 3, then 4 to 7 in the next record), from
/// accel/bvh_builder.hpp's BvhNode: the children's boxes axis by axis, then
/// per child an index (inner node, or first reference of a leaf) and a
/// count (0 inner, > 0 leaf, -1 empty).
HR_STRUCT GpuNode {
  vec4 lo_x, hi_x, lo_y, hi_y, lo_z, hi_z;
  ivec4 index, count;
};

/// A triangle: its three vertices, each rounded to float once, so that
/// triangles sharing a vertex hold the same bits of it (the watertight
/// test needs them, trace.comp), the winding normal (w: the object id's
/// bits), and in v1.w the index of its three vertex normals in the patch
/// buffer (-1: flat), in v2.w that of its vertex colours in the colour
/// buffer (-1: none), in v0.w that of its texture coordinates (GpuUv, -1:
/// none), as float bits.
HR_STRUCT GpuTriangle {
  vec4 v0, v1, v2, ng;
};

/// Vertex normals of a smooth triangle (NFF `pp`, a mesh's normals), or the
/// vertex colours of a coloured one (Tachyon's vcstri; its own buffer).
HR_STRUCT GpuPatch {
  vec4 n0, n1, n2;
};

/// A triangle's texture coordinates: its vertices' (u, v), and its texture
/// units per world unit (RenderScene, TriangleUv).
HR_STRUCT GpuUv {
  vec4 uv01;      // u0, v0, u1, v1
  vec4 uv2_scale; // u2, v2, units per world unit
};

/// A sphere: centre and signed radius (negative: inside only); x of
/// `info`: object id, y: 1 when it casts shadows.
HR_STRUCT GpuSphere {
  vec4 centre_radius;
  ivec4 info;
};

/// An open cone prepared as accel/shapes.hpp's PreparedCone: base and |base
/// radius|, unit axis and length, x: k (radius change per height), y: sign
/// of the base radius (negative: inside only), z: the object id's bits.
HR_STRUCT GpuCone {
  vec4 base_rb, axis_len, k_sign;
};

/// A material: colour and kd; ks, shine, transmittance, ior; emission and
/// model; Blinn-Phong's specular colour; Tachyon's ambient, highlight
/// weight, 1 for a metal's highlight and 1 for a light's own sphere;
/// glTF's metallic, roughness, transmission and dielectric F0; alpha,
/// alpha cutoff and normal scale. Textures (GpuTexture, -1 none): in
/// `maps` the colour texture (a Tachyon texfunc or a mesh's base colour),
/// metallic-roughness, normal and emission maps; in `maps2` MTL's specular
/// map and alpha map, and 1 when the material is alpha-masked.
HR_STRUCT GpuMaterial {
  vec4 colour_kd, ks_shine_t_ior, emission_model, specular, tachyon, pbr, alpha;
  ivec4 maps, maps2;
};

/// A texture (render/textures.hpp): kind, its image map's first level
/// (GpuLevel) and level count. A Tachyon texfunc: centre, rotate, scale and
/// the u, v, w axes. A mesh's image (HR_TEX_UV_IMAGE): wrap modes in u and
/// v, 1 for nearest magnification, 1 when its codes are sRGB; 1 when the
/// image has alpha, its level 0 size; the texture transform's rows (m0 to
/// m5) and the root of its determinant.
HR_STRUCT GpuTexture {
  ivec4 kind_level_count;
  vec4 centre, rotate, scale, uaxis, vaxis, waxis;
  ivec4 wrap_filter, alpha_size;
  vec4 uv_m0, uv_m1;
};

/// One MIP level of an image map: width, height, depth (slices) and its
/// first texel in the texel buffer (one uint a texel: R | G << 8 | B << 16
/// | A << 24, A 255 where the image has no alpha and past level 0).
HR_STRUCT GpuLevel {
  ivec4 size_offset;
};

/// A light (render_scene.hpp, PointLight): position and kind, intensity and
/// whether it reaches every point whole, direction, attenuation kc, kl, kq
/// and range, the spot cone (start, end, cos start, cos end) and whether
/// its edge is glTF's smooth one (x of `flags`). For the path integrator:
/// in direction.w a point or spot light's radius, a directional light's
/// cosine of half its angular diameter; y of `flags` 1 for the readers'
/// stand-in headlight.
HR_STRUCT GpuLight {
  vec4 position_kind, intensity_unit, direction, attenuation, cone;
  ivec4 flags;
};

/// An area light (render_scene.hpp, AreaLight): centre and 1 for an
/// ellipse, the half-extent axes u (w: the light's area) and v, the unit
/// normal of its lit side, and its radiance.
HR_STRUCT GpuAreaLight {
  vec4 centre_ellipse, axis_u_area, axis_v, normal, radiance;
};

/// A texel of the environment image (render/environment.hpp): its RGB
/// radiance (strength applied) and its share of the light; the alias
/// table's probability of keeping it and its alias (uint bits).
HR_STRUCT GpuEnvTexel {
  vec4 radiance_share, keep_alias;
};

/// An emissive triangle for next-event estimation (render/emitters.hpp):
/// its power's running sum up to and including it (normalised), its
/// GpuTriangle index (uint bits), the probability of picking it and its area.
HR_STRUCT GpuEmitter {
  vec4 cdf_tri_pick_area;
};

/// A shadow ray waiting in the shadow queue (trace.comp, kShadowQueue):
/// origin (world) and how far it runs, unit direction, and w 1 once the
/// shadow pass finds that nothing blocks it (0 as queued). Its term and
/// link are in a vec4 of their own (the shadow pass does not read them):
/// the light's term at its pixel, already divided by the samples per
/// pixel, and in w (uint bits) of a run's first ray the start of the
/// pixel's run before << 4 | this run's length (trace.comp, shadow_resolve).
HR_STRUCT GpuShadowRay {
  vec4 origin_tmax, dir_lit;
};

/// A path of the wavefront between its stages (HrPathState, with what the
/// device keeps beside it): the ray it traces next (world), the light it
/// has gathered and the last bounce's density, its throughput and next
/// vertex (w: int bits), the throughput its shadow rays in flight take and
/// its flags (w, uint bits: 1 the last bounce was a delta lobe, 2 the eye
/// ray met something, its shadow rays in flight << 8), its sampler (`rng`: seed,
/// sample, dimension; w the eye ray's optical offset, float bits), and the
/// eye ray's line and depth sign (its AOVs).
HR_STRUCT GpuWavePath {
  vec4 o_tmin, dir_tmax, radiance_pdf, throughput_depth, shadow_flags;
  uvec4 rng;
  vec4 line_sign;
};

/// A path's shadow ray (wavefront.glsl): origin (world) and how far it
/// runs, unit direction, and the light's term it brings where nothing
/// blocks it (zeroed by the shadow stage when something does).
HR_STRUCT GpuWaveShadow {
  vec4 origin_tmax, dir, term;
};

/// What one frame's dispatches share: the camera (its frame, its kind and,
/// last, its constants), the scene's box and constants, and the output's
/// size and AOVs.
HR_STRUCT GpuFrame {
  vec4 origin, axis_x, axis_y, axis_z;  // the camera's frame (world)
  // A pinhole view's clipping range along its axis: near, far (0 and
  // infinity: none); z: the scene's epsilon.
  vec4 clip;
  ivec4 size;      // W, H (a panel's: its samples across, its rows); z, w unused
  ivec4 mode;      // x unused; the camera's kind (HR_GRID_*, HR_PINHOLE, HR_DISPLAY, HR_LOOKING_GLASS), recording mode, spp
  ivec4 counts;    // lights, AOV bits, max depth, objects
  ivec4 rows;      // the rows rendered: first, end (the image's buffers hold these alone)
  vec4 box_lo, box_hi;  // the scene's bounds (world) grown by the margin; w: margin
  vec4 background, ambient;
  // Tachyon's fog (render/models/tachyon_model.cpp): colour and HR_FOG_* (0
  // none); start, end, density. x of `flags`: 1 when a Tachyon surface is
  // transparent, so that shadow rays filter through it (tachyon_shadow).
  vec4 fog, fog_range;
  ivec4 flags;
  // A mesh texture's footprint (RenderSettings::footprint): a pixel's width
  // at distance d is x + y d, world units.
  vec4 footprint;
  // Where the camera's pixels go in the image: pixel (i, j) is image pixel
  // (x + i, y + j), rows `z` pixels apart (a quilt's view in its tile;
  // 0, 0, width for the others).
  ivec4 tile;
  // The panels, whose samples are subpixels (HR_DISPLAY, HR_LOOKING_GLASS;
  // size.x counts samples, tile.z pixels). panel_kind: samples per pixel
  // (1 or 3), 1 when red is the leftmost subpixel; z, w unused.
  // HR_LOOKING_GLASS: the view phase a = i A + j B + cells[cell][s] (mod 1)
  // of subpixel s of pixel (i, j), with panel = A and B each split in two
  // (hi, lo; i A_hi and j B_hi exact in float, so that the phase keeps its
  // fraction across a whole panel); cell_kind = cell pattern, cells (0:
  // none, cells[0] serves).
  vec4 panel;
  ivec4 panel_kind;
  ivec4 cell_kind;
  vec4 cells[HR_MAX_CELLS];
  // The path integrator (HR_FEATURE_PATH): area lights, emitters, the
  // environment image's width and height (0, 0: the constant env_constant);
  // flags: 1 when the environment's up is +y, 1 for Blender's Principled
  // BSDF, 1 when the headlight is left out, 1 when the environment lights
  // (not black); env_constant's w: 1 / the emitters' total power
  // (luminance x area); env_turn: cosine and sine of the environment's turn.
  ivec4 path_counts;
  ivec4 path_flags;
  vec4 env_constant, env_turn;
  // The camera's constants as camera/pixel_lines.h's line functions take
  // them: the CPU camera's own record (camera/line_constants.h) in float.
  // The kind mode.y names reads its own (HR_GRID_*: lens_grid; HR_DISPLAY:
  // panel_grid; HR_PINHOLE: pinhole; HR_LOOKING_GLASS: looking_glass); the
  // others are zero. Scalars: last, after every 16-byte vector.
  HrLensGrid lens_grid;
  HrPanelGrid panel_grid;
  HrPinhole pinhole;
  HrLookingGlass looking_glass;
};

#ifdef __cplusplus
}  // namespace holoray::gpu
#endif

#endif
