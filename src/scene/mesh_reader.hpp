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
// What it cannot map yet it keeps as a warning, never silently: texture
// maps, directional and spot lights, points and lines.
#pragma once

#include <string>

#include "scene/scene_desc.hpp"

namespace holoray {

/// Limits checked before anything is stored (absurd files are refused).
struct MeshLimits {
  long max_triangles = 20'000'000;  ///< as NffLimits::max_objects
  long max_warnings_kept = 100;
};

/// Reads a mesh file. Throws std::runtime_error "cannot read 'FILE': REASON"
/// (assimp's reason) when it cannot be read or parsed, and when it holds no
/// triangles or more than limits.max_triangles.
SceneDesc read_mesh_file(const std::string& path, const MeshLimits& limits = {});

/// The scene file's reader by its extension: `.nff` (read_nff_file), `.dat`
/// (read_tachyon_file), else read_mesh_file. Throws as they do.
SceneDesc read_scene_file(const std::string& path);

}  // namespace holoray
