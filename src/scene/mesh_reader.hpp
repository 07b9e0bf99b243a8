// holoray/scene: meshes through assimp (issue 13, item 4): OBJ+MTL, PLY,
// STL, glTF 2.0 (.gltf, .glb), 3DS, COLLADA and AC3D, read into the same
// SceneDesc as NFF, so every renderer path takes them unchanged.
//
// What becomes what (docs/mesh-import.md has the whole table):
// - every mesh one object (TriangleMeshDesc: shared vertices, the file's
//   per-vertex normals when it has them, flat otherwise); node transforms are
//   applied;
// - materials mapped to NFF's Whitted model: colour = diffuse colour, Kd 1,
//   Ks = reflectivity (NFF ties the highlight to the mirror weight, so a
//   highlight without reflection is dropped), Phong exponent = shininess,
//   T = 1 - opacity, ior = the refraction index;
//   a material the importer made up (unnamed, or assimp's "DefaultMaterial":
//   OBJ without MTL, PLY, STL) is holoray's default, grey 0.8 as in NFF;
// - point lights as NFF lights; the first camera as the viewpoint;
// - a file with no camera is viewed from +z of its bounds toward their
//   centre, along (0.5, 0.5, 1) (y up, 40 degrees, the bounding sphere
//   filling 90 % of the view);
//   a file with no point light gets one at that eye, so nothing renders black.
// - node animation (the file's first animation; glTF's translation,
//   rotation and scale channels), when the caller asks for it: every
//   animated node becomes a moving part, its meshes and those of its
//   descendants without animation of their own, in the node's frame, with
//   the chain of transforms that places it (MeshAnimation). Without the
//   request, or for a still, nodes stand at their rest transforms. A camera
//   the animation moves is kept as MeshAnimation::camera.
// - skinned and morphed meshes posed by their joints and morph weights: a
//   still at the joints' rest transforms and the default weights; in a shot
//   each becomes a part of its own whose vertices follow the animation
//   (MeshAnimation::DeformingMesh).
// What it cannot map yet it keeps as a warning, never silently: texture
// maps other than the base colour and emission, area and ambient lights,
// points and lines.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "math/node_track.hpp"
#include "scene/scene_desc.hpp"

namespace holoray {

/// Limits checked before anything is stored (absurd files are refused).
struct MeshLimits {
  long max_triangles = 20'000'000;  ///< as NffLimits::max_objects
  long max_warnings_kept = 100;
};

/// What the user says about reading a scene file (all formats; NFF and
/// Tachyon files take no camera name).
struct SceneReadOptions {
  /// The file camera the viewpoint is; "": the file's first (assimp keeps
  /// no "active" mark). Throws std::invalid_argument naming the file's
  /// cameras when none has this name.
  std::string camera_name;
  /// Folders a texture is looked for in, by its base name, when the path the
  /// file gives does not exist (texture_search.hpp).
  std::vector<std::string> texture_paths;
};

/// What a mesh file's first animation moves. Part k sits in the file's
/// frame at time t (seconds) by transform(k, t): the product, outermost
/// first, of each chain link's fixed matrix times its track's TRS at t.
struct MeshAnimation {
  struct Link {
    Affine fixed;    ///< rest transforms from the previous link's node to this node's parent
    int track = -1;  ///< index into tracks: the animated node's own TRS
  };
  struct Part {
    std::string node;  ///< the animated node's name (messages)
    SceneDesc scene;   ///< its meshes in its own frame; the file's materials, no lights or camera
    std::vector<Link> chain;
  };
  /// The file's first camera when the animation moves it (its node or an
  /// ancestor has a track): the chain to its moving ancestor, then `fixed`
  /// from there to the camera's node frame, where it sits at `from` looking
  /// along `look` with `up` (the still scene's viewpoint is its rest pose).
  struct Camera {
    std::vector<Link> chain;
    Affine fixed;
    Vec3 from, look, up;
    Viewpoint optics;           ///< angle, axis, orthographic size, name: those of every pose
    double focus_distance = 1;  ///< `at` this far along `look`: the rest pose's (read_camera)
  };
  /// A mesh whose vertices move: morph targets (glTF 2.0 §3.7.2.2), then a
  /// skin (§3.7.3; assimp's aiBone). Morphing blends the targets into the
  /// base, v + sum_i w_i (t_i - v), with the weights at time t. Skinning
  /// carries each vertex by a weighted blend of its joints' matrices,
  /// J(t) = (the joint node's frame -> file frame at t) x (its inverse bind
  /// matrix), the mesh node's own transform ignored (the joints place it):
  /// linear blend skinning, v(t) = (sum_k w_k J_k(t)) v, normals by the
  /// blend's inverse transpose. Skin weights are normalised to sum to 1; a
  /// vertex with none stays with the mesh's node. A morphed mesh without a
  /// skin has its node as its one joint.
  struct DeformingMesh {
    size_t part = 0;   ///< parts index: a part of this mesh alone, in the file frame (empty chain)
    std::string mesh;  ///< the mesh's name (messages)
    std::vector<Vec3> vertices, normals;  ///< base pose, the mesh's own space, as the file has them
    struct Target {
      std::vector<Vec3> vertices, normals;  ///< absolute (the base plus the displacement), as assimp gives them
    };
    std::vector<Target> targets;
    std::vector<double> weights;  ///< the targets' default weights (no keys, or a still)
    std::vector<std::pair<double, std::vector<double>>> weight_keys;  ///< (seconds, a weight per target), by time
    struct Joint {
      std::vector<Link> chain;  ///< the joint node's moving ancestors (empty: it stands still)
      Affine fixed;             ///< from the last link's node (or the file) to the joint's frame
      Affine inverse_bind;      ///< mesh space -> the joint's frame at bind time
    };
    std::vector<Joint> joints;
    std::vector<uint32_t> first;  ///< per vertex, plus one: where its influences start
    std::vector<std::pair<uint32_t, double>> influences;  ///< (joint, weight), weights summing to 1

    /// The morph weights at `seconds`: linear between keys, held outside them.
    std::vector<double> weights_at(double seconds) const;
  };
  std::vector<NodeTrack> tracks;
  std::vector<Part> parts;
  std::vector<DeformingMesh> deforming;
  std::optional<Camera> camera;
  double duration_s = 0;  ///< the animation's length (assimp's mDuration in seconds)

  Affine transform(size_t part, double seconds) const;
  /// The moving camera's viewpoint at `seconds` (file frame; needs `camera`).
  Viewpoint camera_at(double seconds) const;
  /// Deforming mesh `k`'s vertices and unit normals (file frame; normals
  /// empty when the mesh has none) at `seconds`.
  void pose(size_t k, double seconds, std::vector<Vec3>& vertices, std::vector<Vec3>& normals) const;
};

/// `mesh` morphed with `weights` (one per target), then skinned with the
/// joints' frames at `seconds` (`tracks` empty: every joint at its rest
/// transform): MeshAnimation::DeformingMesh.
void pose_mesh(const MeshAnimation::DeformingMesh& mesh, const std::vector<double>& weights,
               const std::vector<NodeTrack>& tracks, double seconds, std::vector<Vec3>& vertices,
               std::vector<Vec3>& normals);

/// Reads a mesh file. Throws std::runtime_error "cannot read 'FILE': REASON"
/// (assimp's reason) when it cannot be read or parsed, and when it holds no
/// triangles or more than limits.max_triangles. With `animation`, the nodes
/// the file's first animation moves go there as parts and the returned
/// scene keeps only what stands still (lights and camera at rest).
SceneDesc read_mesh_file(const std::string& path, const MeshLimits& limits = {}, MeshAnimation* animation = nullptr,
                         const SceneReadOptions& options = {});

/// The scene file's reader by its extension: `.nff` (read_nff_file), `.dat`
/// (read_tachyon_file), else read_mesh_file (with `animation`: NFF and
/// Tachyon files have none, it is left empty). Throws as they do.
SceneDesc read_scene_file(const std::string& path, MeshAnimation* animation = nullptr,
                          const SceneReadOptions& options = {});

}  // namespace holoray
