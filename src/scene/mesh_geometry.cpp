// holoray/scene: a mesh file's node hierarchy walked into triangle meshes (mesh_import.hpp).
#include "scene/mesh_import.hpp"



namespace holoray::mesh_import {

void MeshReader::count(const aiNode* node, long& triangles) const {
  for (unsigned k = 0; k < node->mNumMeshes; ++k) {
    const aiMesh& mesh = *s_.mMeshes[node->mMeshes[k]];
    if (mesh.mPrimitiveTypes & aiPrimitiveType_TRIANGLE) triangles += mesh.mNumFaces;
  }
  for (unsigned k = 0; k < node->mNumChildren; ++k) count(node->mChildren[k], triangles);
}

void MeshReader::walk(const aiNode* node, const aiMatrix4x4& parent_world, const aiMatrix4x4& parent_rel, int part) {
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

void MeshReader::add_mesh(const aiMesh& mesh, const Xform& xf, const aiMatrix4x4& world, SceneDesc& target,
              const std::vector<Vec3>* posed, const std::vector<Vec3>* posed_normals) {
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

aiMatrix4x4 MeshReader::global(const aiString& name) const {
  const auto it = global_.find(name.C_Str());
  return it == global_.end() ? aiMatrix4x4() : it->second;
}

}  // namespace holoray::mesh_import
