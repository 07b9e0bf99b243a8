// holoray/scene: a mesh file's lights and the viewpoint's camera (mesh_import.hpp).
#include "scene/mesh_import.hpp"

#include <assimp/version.h>



namespace holoray::mesh_import {

void MeshReader::read_lights() {
  for (unsigned k = 0; k < s_.mNumLights; ++k) {
    const aiLight& l = *s_.mLights[k];
    const aiMatrix4x4 m = global(l.mName);
    Light light;
    light.position = to_vec(m * l.mPosition);
    light.colour = to_vec(l.mColorDiffuse);
    switch (l.mType) {
      case aiLightSource_POINT: light.kind = LightKind::point; break;
      case aiLightSource_SPOT: light.kind = LightKind::spot; break;
      case aiLightSource_DIRECTIONAL: light.kind = LightKind::directional; break;
      default:
        warn(fmt::format("light '{}': only point, spot and directional lights are rendered", l.mName.C_Str()));
        continue;
    }
    if (light.kind != LightKind::point) {
      const Vec3 d = to_vec(aiMatrix3x3(m) * l.mDirection);
      if (!(length(d) > 0) || !is_finite(d)) {
        warn(fmt::format("light '{}': its direction is zero or not finite; the light is dropped", l.mName.C_Str()));
        continue;
      }
      light.direction = normalize(d);
    }
    if (!is_finite(light.position) || !is_finite(light.colour)) {
      warn(fmt::format("light '{}': not finite; the light is dropped", l.mName.C_Str()));
      continue;
    }
    if (gltf_) {
      light.photometric = true;
      light.colour = light.colour * kGltfLightToRadiance;
      if (light.kind != LightKind::directional) light.kq = 1, light.kc = 0, light.kl = 0;
      if (light.kind == LightKind::spot) {
        // glTF's cone angles are measured from the axis.
        light.fall_end = std::clamp(static_cast<double>(l.mAngleOuterCone), 0.0, std::numbers::pi / 2);
        light.fall_start = std::clamp(static_cast<double>(l.mAngleInnerCone), 0.0, light.fall_end);
        light.smooth_cone = true;
      }
      light.range = light_range(l.mName);
    } else if (light.kind == LightKind::spot) {
      // aiLight's cone angles are full angles; falloff linear in the angle between them.
      light.fall_end = std::clamp(0.5 * l.mAngleOuterCone, 0.0, std::numbers::pi);
      light.fall_start = std::clamp(0.5 * l.mAngleInnerCone, 0.0, light.fall_end);
    }
    out_.lights.push_back(light);
  }
}

double MeshReader::light_range(const aiString& name) const {
  const aiNode* node = s_.mRootNode->FindNode(name);
  if (node == nullptr || node->mMetaData == nullptr) return 0;
  float f = 0;
  double d = 0;
  if (node->mMetaData->Get("PBR_LightRange", f)) d = f;
  else if (!node->mMetaData->Get("PBR_LightRange", d)) return 0;
  return d > 0 && std::isfinite(d) ? d : 0;
}

int MeshReader::chosen_camera() const {
  if (options_.camera_name.empty()) return s_.mNumCameras > 0 ? 0 : -1;
  std::string names;
  for (unsigned k = 0; k < s_.mNumCameras; ++k) {
    if (options_.camera_name == s_.mCameras[k]->mName.C_Str()) return static_cast<int>(k);
    names += fmt::format("{}'{}'", k ? ", " : "", s_.mCameras[k]->mName.C_Str());
  }
  throw std::invalid_argument(fmt::format("camera name: '{}' has no camera '{}' ({})", out_.source, options_.camera_name,
                                          names.empty() ? "it has none" : "its cameras: " + names));
}

void MeshReader::read_lens(const aiCamera& c, Viewpoint& vp) {
  const double aspect = c.mAspect > 0 && std::isfinite(c.mAspect) ? c.mAspect : 0;
  const double a = aspect > 0 ? aspect : 1;
  const double h = c.mHorizontalFOV;
  const auto assimp_at_least = [](unsigned minor) {
    return aiGetVersionMajor() > 5 || (aiGetVersionMajor() == 5 && aiGetVersionMinor() >= minor);
  };
  const auto degrees = [](double radians) { return radians * 180 / std::numbers::pi; };
  using Axis = Viewpoint::FovAxis;
  vp.fov_axis = Axis::horizontal;
  if (c.mOrthographicWidth > 0) {
    vp.ortho_size = 2 * c.mOrthographicWidth;
  } else if (gltf_) {
    vp.angle_deg = degrees(assimp_at_least(3) ? 2 * std::atan(std::tan(h / 2) / a) : h / a);
    vp.fov_axis = Axis::vertical;
  } else if (ext_ == ".irr") {
    vp.angle_deg = degrees(h / a);
    vp.fov_axis = Axis::vertical;
  } else if (ext_ == ".blend") {
    vp.angle_deg = degrees(h);
    vp.fov_axis = Axis::larger;
  } else if (ext_ == ".fbx") {
    vp.angle_deg = degrees(assimp_at_least(4) ? 2 * h : h);
  } else if (ext_ == ".3ds") {
    vp.angle_deg = 2400 / degrees(h);
  } else {
    vp.angle_deg = degrees(h);
  }
  if (!(vp.angle_deg > 0 && vp.angle_deg < 180)) {
    warn(fmt::format("camera '{}': a field of view of {:.4g} deg cannot be rendered; 45 deg instead", c.mName.C_Str(),
                     vp.angle_deg));
    vp.angle_deg = 45;
  }
  // The image the camera was made for, 512 px on its shorter side.
  if (aspect > 0 && aspect != 1) {
    vp.xres = aspect > 1 ? static_cast<int>(std::lround(512 * aspect)) : 512;
    vp.yres = aspect > 1 ? 512 : static_cast<int>(std::lround(512 / aspect));
  }
  vp.camera = c.mName.C_Str();
  if (c.mClipPlaneNear > 0 && std::isfinite(c.mClipPlaneNear)) vp.clip_near = c.mClipPlaneNear;
  // glTF's zfar is optional (an infinite projection, §5.12); assimp fills
  // in 100 where it is missing, keeping the file's camera order.
  const auto k = static_cast<size_t>(camera_index_);
  const bool infinite = gltf_ && k < gltf_infinite_far_.size() && gltf_infinite_far_[k];
  if (!infinite && c.mClipPlaneFar > vp.clip_near && std::isfinite(c.mClipPlaneFar)) vp.clip_far = c.mClipPlaneFar;
}

double MeshReader::centre_depth(const Vec3& eye, const Vec3& dir) const {
  const Vec3 to_centre = bounds_.centre() - eye;
  const double depth = dot(to_centre, dir);
  const double d = depth > 0 ? depth : length(to_centre);
  return d > 0 && std::isfinite(d) ? d : 1;
}

void MeshReader::read_camera() {
  Viewpoint vp;
  if (camera_ != nullptr) {
    const aiCamera& c = *camera_;
    const aiMatrix4x4 m = global(c.mName);
    // assimp's glTF importer copies the node's translation into mPosition
    // (which the node transform already holds).
    // A keyframed 3DS file's camera (assimp: mLookAt reset to +z) has its
    // first key in the node transform, and its target is lost: it is aimed
    // at the scene's centre instead, with a warning.
    const bool lost_target = ext_ == ".3ds" && c.mLookAt == aiVector3D(0, 0, 1);
    const aiVector3D local_from = gltf_ || lost_target ? aiVector3D(0, 0, 0) : c.mPosition;
    vp.from = to_vec(m * local_from);
    aiVector3D look = ext_ == ".irr" ? c.mLookAt - c.mPosition : c.mLookAt;
    if (lost_target) {
      const Vec3 to_centre = bounds_.centre() - vp.from;
      aiMatrix3x3 to_node(m);
      to_node.Inverse();
      look = to_node * aiVector3D(float(to_centre.x), float(to_centre.y), float(to_centre.z));
      warn(fmt::format("camera '{}': assimp does not keep a keyframed 3DS camera's target; it is aimed at the scene's "
                       "centre instead", c.mName.C_Str()));
    }
    const Vec3 dir = normalize(to_vec(aiMatrix3x3(m) * look));
    vp.up = to_vec(aiMatrix3x3(m) * c.mUp);
    read_lens(c, vp);
    const double focus = centre_depth(vp.from, dir);
    vp.at = vp.from + dir * focus;
    vp.focus = Viewpoint::Focus::scene_centre_depth;
    if (animation_ && animation_->camera) {
      MeshAnimation::Camera& moving = *animation_->camera;
      moving.from = to_vec(local_from);
      moving.look = to_vec(look);
      moving.up = to_vec(c.mUp);
      moving.optics = vp;
      moving.focus_distance = focus;
    }
  } else {
    // A three-quarter view from +z (raised toward +y, moved toward +x),
    // framing the bounding sphere: radius r at distance r / sin(angle / 2),
    // widened so it fills 90 % of the view.
    const Vec3 centre = bounds_.centre();
    const double r = std::fmax(0.5 * length(bounds_.diagonal()), 1e-6);
    vp.angle_deg = 40;
    const double distance = r / std::sin(vp.angle_deg / 2 * std::numbers::pi / 180) / 0.9;
    vp.from = centre + normalize(Vec3{0.5, 0.5, 1}) * distance;
    vp.at = centre;
    vp.up = {0, 1, 0};
  }
  out_.viewpoint = vp;
  if (out_.lights.empty()) {
    Light headlight;
    headlight.position = vp.from;
    headlight.headlight = true;
    out_.lights.push_back(headlight);
  }
}

}  // namespace holoray::mesh_import
