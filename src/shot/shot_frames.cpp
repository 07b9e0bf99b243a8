#include "shot/shot_frames.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

#include "camera/placement.hpp"
#include "scene/mesh_reader.hpp"

namespace holoray {

ShotFrames::ShotFrames(Shot shot) : shot_(std::move(shot)) {
  // A mesh file's animated nodes become parts of their own, after the file's
  // still part; descs_ must not reallocate once parts point into it.
  animations_.resize(shot_.objects.size());
  for (size_t k = 0; k < shot_.objects.size(); ++k) {
    MeshAnimation& anim = animations_[k];
    descs_.push_back(read_scene_file(shot_.objects[k].scene, &anim, shot_.read));
    entries_.push_back({k, -1});
    for (size_t p = 0; p < anim.parts.size(); ++p) {
      descs_.push_back(std::move(anim.parts[p].scene));
      anim.parts[p].scene = SceneDesc{};
      entries_.push_back({k, static_cast<int>(p)});
    }
  }
  std::vector<ScenePart> parts;
  for (size_t e = 0; e < entries_.size(); ++e) {
    const Entry& en = entries_[e];
    const auto& meshes = animations_[en.object].deforming;
    for (size_t m = 0; m < meshes.size(); ++m)
      if (en.part >= 0 && meshes[m].part == static_cast<size_t>(en.part)) deforming_.push_back({e, en.object, m});
    const bool deformable = !deforming_.empty() && deforming_.back().entry == e;
    parts.push_back({&descs_[e], en.part >= 0 || !shot_.objects[en.object].motion.is_static(), deformable});
  }
  scene_ = std::make_unique<RenderScene>(parts);

  const auto nff_view = std::find_if(descs_.begin(), descs_.end(), [](const SceneDesc& d) { return d.viewpoint.has_value(); });
  if (nff_view != descs_.end()) default_angle_ = nff_view->viewpoint->angle_deg;
  // A Tachyon scene's camera path and keys are seen on Tachyon's (mirrored) screen.
  if (nff_view != descs_.end()) mirrored_ = nff_view->viewpoint->mirrored;
  if (shot_.camera.angle_deg) default_angle_ = *shot_.camera.angle_deg;

  if (!shot_.camera.path.empty()) {
    if (shot_.camera.distance) {
      path_distance_ = *shot_.camera.distance;
    } else {
      // The scene's centre depth at the first frame, held for the whole shot
      // so the array keeps its size.
      scene_->set_transforms(transforms(0));
      const CameraPathFrame& f = shot_.camera.path[static_cast<size_t>(shot_.camera.path_start)];
      path_distance_ = dot(scene_->bounds().centre() - f.centre, normalize(f.view));
      if (!(path_distance_ > 0))
        throw std::invalid_argument(fmt::format(
            "{}: the camera path's first frame looks away from the scene (its centre is {:.4g} behind the camera); "
            "set [camera] distance",
            shot_.source, -path_distance_));
    }
  } else if (shot_.camera.keys.empty() && nff_view == descs_.end()) {
    throw std::invalid_argument(fmt::format(
        "{}: no camera: give [camera] keys or a path, or use a scene file with a viewpoint ('v')", shot_.source));
  }
  seek(0);
}

std::vector<Affine> ShotFrames::transforms(double frame) const {
  std::vector<Affine> out;
  for (const Entry& e : entries_) {
    const Affine placed = shot_.objects[e.object].motion.matrix(frame);
    // The file's own animation runs on the shot's clock: frame f is f / fps seconds.
    out.push_back(e.part < 0 ? placed
                             : placed * animations_[e.object].transform(static_cast<size_t>(e.part), frame / shot_.fps));
  }
  return out;
}

Viewpoint ShotFrames::viewpoint(int frame) const {
  const ShotCamera& cam = shot_.camera;
  Viewpoint vp;
  vp.angle_deg = default_angle_;
  vp.mirrored = mirrored_;
  if (!cam.path.empty()) {
    const CameraPathFrame& f = cam.path[static_cast<size_t>(cam.path_start + frame)];
    vp.from = f.centre;
    vp.at = f.centre + normalize(f.view) * path_distance_;
    vp.up = f.up;
    return vp;
  }
  if (!cam.keys.empty()) {
    const auto& keys = cam.keys;
    const double fr = frame;
    size_t hi = 0;
    while (hi < keys.size() && keys[hi].frame <= fr) ++hi;
    const ViewKey& a = keys[hi == 0 ? 0 : hi - 1];
    const ViewKey& b = keys[std::min(hi, keys.size() - 1)];
    const double w = (hi == 0 || hi == keys.size()) ? 0.0 : key_weight(fr, a.frame, b.frame, cam.interpolation);
    auto mix = [w](const Vec3& x, const Vec3& y) { return x + (y - x) * w; };
    vp.from = mix(a.from, b.from);
    vp.at = mix(a.at, b.at);
    vp.up = mix(a.up, b.up);
    const double angle_a = a.angle_deg.value_or(default_angle_), angle_b = b.angle_deg.value_or(default_angle_);
    vp.angle_deg = angle_a + (angle_b - angle_a) * w;
    return vp;
  }
  for (size_t e = 0; e < descs_.size(); ++e)
    if (const SceneDesc& d = descs_[e]; d.viewpoint) {
      vp = *d.viewpoint;
      // A mesh file whose animation moves its camera: the camera at the
      // frame's time (in the file's frame, as its still viewpoint: the
      // object's keys do not carry it).
      if (const MeshAnimation& anim = animations_[entries_[e].object]; anim.camera) {
        const Viewpoint moving = anim.camera_at(frame / shot_.fps);
        vp.from = moving.from, vp.at = moving.at, vp.up = moving.up;
      }
      if (shot_.camera.angle_deg) vp.angle_deg = *shot_.camera.angle_deg;
      return vp;
    }
  return vp;  // unreachable: the constructor refused shots without a camera
}

LensArrayDesc ShotFrames::camera(int frame) const {
  if (frame < 0 || frame >= shot_.frames)
    throw std::out_of_range(fmt::format("frame {} is outside the shot (0 to {})", frame, shot_.frames - 1));
  try {
    return place_array(shot_.array, viewpoint(frame));
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(fmt::format("{}: frame {}: {}", shot_.source, frame, e.what()));
  }
}

void ShotFrames::seek(int frame) {
  scene_->set_transforms(transforms(frame));
  // Tagged with the frame, so that two frames of one pose share it (reuse).
  const auto pose = static_cast<uint64_t>(frame) + 1;
  std::vector<Vec3> vertices, normals;
  for (const DeformingRef& d : deforming_) {
    const auto group = static_cast<uint32_t>(d.entry);
    if (scene_->accel().pose(group) == pose) continue;
    animations_[d.object].pose(d.mesh, frame / shot_.fps, vertices, normals);
    scene_->set_vertices(group, vertices, normals, pose);
  }
}

RenderSettings ShotFrames::settings() const {
  RenderSettings s = file_settings(*scene_);
  if (shot_.background) s.background = *shot_.background;
  return s;
}

}  // namespace holoray
