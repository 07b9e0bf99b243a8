// holoray/gpu: the built scene and one frame's camera laid out as the
// compute shaders read them (shaders/layout.h): flat arrays of triangles,
// spheres, cones, materials and lights in world space at the scene's
// current transforms, and the hierarchy Embree's builder made over them
// (accel/bvh_builder.hpp). Plain data, no Vulkan: built and checked on any
// machine.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "camera/lens_array.hpp"
#include "camera/pinhole.hpp"
#include "accel/bvh_builder.hpp"
#include "camera/display_camera.hpp"
#include "camera/quilt_camera.hpp"
#include "display/looking_glass.hpp"
#include "render/frame_camera.hpp"
#include "render/render_context.hpp"
#include "render/renderer.hpp"

#include "gpu/shaders/layout.h"

namespace holoray::gpu {

/// The scene's arrays; `bvh_depth` the hierarchy's levels (its stack need).
struct SceneArrays {
  std::vector<GpuNode> nodes;
  std::vector<uint32_t> refs;  ///< leaves' primitive references (HR_PRIM_* << HR_PRIM_SHIFT | index)
  std::vector<GpuTriangle> triangles;
  std::vector<GpuPatch> patches;
  std::vector<GpuPatch> colours;  ///< vertex colours (GpuTriangle::e2.w)
  std::vector<GpuUv> uvs;         ///< texture coordinates (GpuTriangle::v0.w)
  std::vector<GpuSphere> spheres;
  std::vector<GpuCone> cones;
  std::vector<uint32_t> object_material;
  std::vector<GpuMaterial> materials;
  std::vector<GpuLight> lights;
  std::vector<GpuTexture> textures;  ///< Tachyon's texfuncs and meshes' images
  std::vector<GpuLevel> levels;      ///< the image maps' MIP levels
  std::vector<uint32_t> texels;      ///< the levels' texels, RGB8 in a uint each
  /// The path integrator's (lay_out_path; one zero record each until then).
  std::vector<GpuAreaLight> area_lights;
  std::vector<GpuEnvTexel> environment;
  std::vector<GpuEmitter> emitters;
  /// Each group's first triangle in `triangles` (host only: where the
  /// emitters' triangles are).
  std::vector<uint32_t> group_first_triangle;
  int bvh_depth = 0;
  /// What the materials need of the kernel (HR_FEATURE_* bits): its
  /// pipeline is specialised to them (shaders/trace.comp).
  uint32_t features = 0;
  /// Some material's hit may send two rays on under Whitted's light (a
  /// mirror and a transmitted ray), so a pixel's ray tree may hold up to
  /// 2^max_depth - 1 rays, not max_depth (the wavefront's steps,
  /// gpu/wavefront.cpp).
  bool whitted_branches = false;
  /// Bytes the arrays take on the device.
  uint64_t bytes() const;
};

/// Where each group of a scene stood when it was laid out (its transform
/// and pose): a frame of an animation whose groups moved or deformed is
/// laid out again.
struct ScenePose {
  std::vector<Affine> to_world;
  std::vector<uint64_t> pose;

  explicit ScenePose(const AccelScene& accel) {
    for (uint32_t g = 0; g < accel.group_count(); ++g) to_world.push_back(accel.transform(g)), pose.push_back(accel.pose(g));
  }
  bool operator==(const ScenePose&) const = default;
};

/// Throws std::length_error naming both depths when a hierarchy `depth`
/// levels deep with nodes `width` wide could need more of the traversal's
/// stack than it holds (HR_STACK entries; a depth-first walk needs
/// (width - 1) (depth - 1) + 1): the build's depth bound (bvh_builder.hpp)
/// keeps every hierarchy within it, and lay_out checks each.
void check_stack(int depth, int width);

/// An animation's hierarchy, kept from frame to frame by the one who lays
/// its frames out (GpuExecutor, live): the tree built at some frame, and
/// its cost then (bvh_cost). A frame whose groups moved refits it while its
/// cost stays within kRefitGrowth of the built one, and builds it again
/// past that (objects that parted make a refit tree's boxes overlap).
struct KeptBvh {
  Bvh bvh;
  size_t primitives = 0;  // the boxes it was built over
  double built_cost = 0;
  int builds = 0, refits = 0;
};
inline constexpr double kRefitGrowth = 1.5;

/// The scene laid out for the device, its hierarchy built at `quality` with
/// nodes `bvh_width` (4 or 8) wide, or `kept`'s refitted (KeptBvh; null:
/// built, not kept). Throws std::length_error when a count passes the 2^30
/// a reference holds (or the texels 2^31), std::runtime_error when Embree's
/// builder fails.
SceneArrays lay_out(const RenderScene& scene, BvhQuality quality = BvhQuality::high, int bvh_width = 4,
                    KeptBvh* kept = nullptr);

/// The path integrator's light added to `arrays` (laid out from the same
/// scene): the area lights, the environment image and its alias table
/// (RenderSettings::environment), the emissive triangles by power
/// (RenderSettings::emitters), and the kernel's path feature. Throws
/// std::length_error past the 2^31 texels or triangles an index holds.
void lay_out_path(const RenderContext& context, SceneArrays& arrays);

/// lay_out of `context`'s scene, with lay_out_path where its settings ask
/// for the path integrator: what a render uploads.
SceneArrays lay_out(const RenderContext& context, BvhQuality quality, int bvh_width, KeptBvh* kept = nullptr);

/// One frame's constants: the lens array (any grid, either recording
/// mode), the scene's box grown by its epsilon, depth limit, background,
/// ambient, spp, the AOVs wanted and the rows [row0, row1) rendered.
GpuFrame frame_constants(const RenderContext& context, const LensArray& camera, const AovSet& aovs, int spp, int row0,
                         int row1);
/// A quilt's views (camera/quilt_camera.hpp), each a pinhole view with its
/// tile of the whole quilt image (GpuFrame::tile).
std::vector<GpuFrame> quilt_frames(const RenderContext& context, const QuiltCamera& camera, const AovSet& aovs, int spp);
/// The same for a pinhole view (camera/pinhole.hpp: shift, orthographic,
/// clipping, the sample's place in its pixel).
GpuFrame frame_constants(const RenderContext& context, const PinholeCamera& camera, const AovSet& aovs, int spp, int row0,
                         int row1);
/// A display's panel (camera/display_camera.hpp): one sample per subpixel
/// (or pixel), each written into its channel of the W x H pixel image as
/// render/display_renderer.cpp packs them (`red_first`: RGB, else BGR).
/// Colour only, as on the CPU path.
GpuFrame frame_constants(const RenderContext& context, const DisplayCamera& camera, bool red_first, int spp, int row0,
                         int row1);
/// A Looking Glass's native panel (display/looking_glass.hpp): each
/// subpixel's view from the calibration, computed on the device. Colour only.
GpuFrame frame_constants(const RenderContext& context, const LookingGlassCamera& camera, int spp, int row0, int row1);

/// Any placed camera's frames (one, or a quilt's views), rows [row0, row1)
/// of it (a quilt: whole only): the one place the GPU path dispatches on
/// the camera's kind.
std::vector<GpuFrame> camera_frames(const RenderContext& context, const FrameCamera& camera, const AovSet& aovs, int spp,
                                    int row0, int row1);
/// Whether camera_frames() of `camera` are panel images (a display's
/// panel, a Looking Glass's native panel), which the kernel renders in a
/// pipeline of their own (GpuRenderer::load's `panel`).
bool renders_panel(const FrameCamera& camera);

}  // namespace holoray::gpu
