// holoray public API: a scene, read from a file or built in code.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "holoray/export.hpp"

namespace holoray::api {

using Vec3d = std::array<double, 3>;

/// A texture for a mesh: sRGB-encoded 8-bit codes (glTF's and PNG's
/// convention), row 0 at the top, 3 (RGB) or 4 (RGBA) channels.
struct Texture {
  int width = 0, height = 0, channels = 3;
  std::vector<uint8_t> codes;  ///< width * height * channels
};

/// A triangle mesh in world units and frame.
struct Mesh {
  std::vector<Vec3d> vertices;                      ///< N
  std::vector<std::array<uint32_t, 3>> faces;       ///< M, counter-clockwise seen from the front
  std::vector<Vec3d> normals;                       ///< N (shading normals) or empty: flat
  std::vector<std::array<double, 2>> uv;            ///< N or empty; v up from the texture's bottom row
  Vec3d colour{0.8, 0.8, 0.8};                      ///< linear RGB, times the texture where there is one
  std::optional<Texture> texture;
};

/// How a scene file is read (Scene::load; docs/guide/scenes.md, "File
/// cameras" and "Textures").
struct LoadOptions {
  /// The mesh file's camera the viewpoint is, by its name in the file;
  /// "": the file's first. A name the file lacks throws
  /// std::invalid_argument listing its cameras; NFF and Tachyon files have
  /// no named cameras.
  std::string camera_name;
  /// Folders a mesh file's texture is looked for in, by its base name, when
  /// the path the file gives does not exist (after the file's own folder).
  std::vector<std::string> texture_paths;
};

struct SceneData;  // the scene description (internal)

/// A scene: everything a render needs but the camera. Copies share the
/// description until one of them is changed (copy on write): a Renderer
/// keeps the scene it was made from without copying a large mesh.
class HOLORAY_API Scene {
 public:
  Scene();
  ~Scene();
  Scene(const Scene&);
  Scene& operator=(const Scene&);
  Scene(Scene&&) noexcept;
  Scene& operator=(Scene&&) noexcept;

  /// NFF (.nff), Tachyon (.dat) or a mesh file through assimp (.obj, .ply,
  /// .stl, .gltf, .glb, .3ds, .dae, .ac). Throws SceneError (file:line:col)
  /// for malformed input, std::runtime_error for a file that cannot be read.
  static Scene load(const std::string& path, const LoadOptions& options = {});

  /// Adds a mesh; returns its object id (the `id` AOV). Throws
  /// std::invalid_argument naming the field: a coordinate that is NaN or
  /// infinite, a face index out of range, normals or uv of another count
  /// than the vertices, a texture without uv or of the wrong size.
  int add_mesh(const Mesh& mesh);
  /// An exact sphere (world units); radius > 0. Returns its object id.
  int add_sphere(const Vec3d& centre, double radius, const Vec3d& colour = {0.8, 0.8, 0.8});
  /// A point light without falloff; `colour` is the radiance it gives a white
  /// surface facing it (docs/lights.md). Without any, a render adds a
  /// headlight at the viewpoint, as mesh files do.
  void add_light(const Vec3d& position, const Vec3d& colour = {1, 1, 1});
  /// Adds the lights of a lights file (docs/lights.md, "Lights file"): point,
  /// spot, sun and area lights in Blender's words and units, in the scene's
  /// frame; area lights, light radii and sun angles light the path
  /// integrator. They replace a mesh file's stand-in headlight. Throws
  /// SceneError (file:line:col) for a malformed file, std::runtime_error
  /// for one that cannot be read.
  void add_lights(const std::string& path);
  /// The viewpoint every camera is placed by (NFF's `v`): eye, the point
  /// looked at, up, and the vertical field of view in degrees, in (0, 180).
  void set_viewpoint(const Vec3d& eye, const Vec3d& at, const Vec3d& up, double fov_deg);

  const std::string& source() const;  ///< the file it was read from ("" when built in code)
  int object_count() const;
  int light_count() const;  ///< point, spot, directional and area lights
  bool has_viewpoint() const;
  /// "file:line:col: warning: ..." for input accepted but suspect.
  const std::vector<std::string>& warnings() const;
  /// Every warning, also those past the ones kept as text.
  size_t warning_count() const;

  /// The description, shared (internal).
  std::shared_ptr<const SceneData> data() const { return data_; }

 private:
  SceneData& mutable_data();
  std::shared_ptr<SceneData> data_;
};

}  // namespace holoray::api
