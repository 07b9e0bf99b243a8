// holoray/scene: a mesh file's animation: node tracks, skins and morph
// targets read (mesh_import.hpp), and MeshAnimation played at a time.
#include "scene/mesh_import.hpp"

namespace holoray {

namespace mesh_import {

void MeshReader::read_animation(const aiAnimation& anim) {
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

MeshAnimation::DeformingMesh::Joint MeshReader::joint_at(const std::string& node) const {
  const NodePlace& at = place_.at(node);
  MeshAnimation::DeformingMesh::Joint j;
  if (at.part >= 0) j.chain = animation_->parts[static_cast<size_t>(at.part)].chain;
  j.fixed = at.rel;
  return j;
}

void MeshReader::add_deforming_mesh(const aiMesh& mesh, const std::string& node) {
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

void MeshReader::read_targets(const aiMesh& mesh, const std::string& node, MeshAnimation::DeformingMesh& d) const {
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

void MeshReader::read_skin(const aiMesh& mesh, const std::string& node, MeshAnimation::DeformingMesh& d) const {
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

}  // namespace mesh_import

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

}  // namespace holoray
