#include "scene/mesh_reader.hpp"

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <fmt/format.h>

#include <charconv>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "scene/file_text.hpp"
#include "scene/gltf_check.hpp"
#include "scene/mesh_import.hpp"
#include "scene/nff_reader.hpp"
#include "scene/tachyon_reader.hpp"

namespace holoray {

namespace mesh_import {

MeshReader::MeshReader(const aiScene& s, std::string source, std::string ext, const MeshLimits& limits, MeshAnimation* animation,
           const SceneReadOptions& options, std::vector<bool> gltf_infinite_far)
    : s_(s), limits_(limits), options_(options), ext_(std::move(ext)), gltf_(ext_ == ".gltf" || ext_ == ".glb"),
      gltf_infinite_far_(std::move(gltf_infinite_far)), animation_(animation) {
  out_.source = std::move(source);
  camera_index_ = chosen_camera();
  camera_ = camera_index_ >= 0 ? s_.mCameras[camera_index_] : nullptr;
  if (animation_ && s_.mNumAnimations > 0) read_animation(*s_.mAnimations[0]);
  if (!animation_ && s_.mNumAnimations > 0)
    warn("its node animation is not played in a still (nodes stand at rest); a shot plays it (holoray animate)");
  if (animation_ && s_.mNumAnimations > 1)
    warn(fmt::format("{} animations: only the first is played", s_.mNumAnimations));
}

SceneDesc MeshReader::read() {
  read_materials();
  long triangles = 0;
  count(s_.mRootNode, triangles);
  if (triangles == 0) throw malformed_file(out_.source, "it holds no triangles");
  if (triangles > limits_.max_triangles)
    throw malformed_file(out_.source, fmt::format("{} triangles, over the limit of {}",
                                                  triangles, limits_.max_triangles));
  out_.objects.reserve(static_cast<size_t>(triangles));
  walk(s_.mRootNode, aiMatrix4x4(), aiMatrix4x4(), -1);
  for (const auto& [mesh, node] : deforming_) add_deforming_mesh(*mesh, node);
  read_lights();
  read_camera();
  return std::move(out_);
}

void MeshReader::warn(const std::string& message) {
  if (static_cast<long>(out_.warning_count++) >= limits_.max_warnings_kept) return;
  out_.warnings.push_back(fmt::format("{}: warning: {}", out_.source, message));
}

}  // namespace mesh_import

namespace {

// A PLY header declares its element counts and assimp's reader trusts them:
// one declaring 10^12 vertices keeps it busy for hours. Every element takes
// at least one byte (ASCII: a digit and a separator; binary: a property), so
// counts beyond the file's size are refused before assimp sees the file.
void check_ply_header(std::ifstream& in, const std::string& path, uintmax_t size) {
  std::string line;
  if (!std::getline(in, line) || (line.rfind("ply", 0) != 0 && line.rfind("PLY", 0) != 0)) return;  // assimp reports it
  uintmax_t declared = 0;
  for (int lines = 0; lines < 10000 && std::getline(in, line); ++lines) {
    if (line.rfind("end_header", 0) == 0) break;
    std::istringstream words(line);
    std::string keyword, name, count;
    if (!(words >> keyword >> name >> count) || keyword != "element") continue;
    uintmax_t n = 0;
    const auto [end, ec] = std::from_chars(count.data(), count.data() + count.size(), n);
    if (ec != std::errc() || end != count.data() + count.size() || n > size || declared + n > size)
      throw malformed_file(path, fmt::format("its header declares {} {} elements, more than a file of {} bytes holds",
                                             count, name, size));
    declared += n;
  }
}

// An OFF file's counts, "nv nf ne" after its OFF keyword (on that line or
// the next that is not a comment), as check_ply_header checks a PLY's:
// assimp 5.2 allocates what they say and asserts (an abort) when the faces
// are not there.
void check_off_header(std::ifstream& in, const std::string& path, uintmax_t size) {
  std::string line;
  if (!std::getline(in, line)) return;
  std::istringstream first(line);
  std::string keyword;
  if (!(first >> keyword) || keyword.size() < 3 || keyword.compare(keyword.size() - 3, 3, "OFF") != 0) return;
  std::string counts;
  std::getline(first, counts);
  for (int lines = 0; lines < 1000 && counts.find_first_not_of(" \t\r") == std::string::npos; ++lines) {
    if (!std::getline(in, counts)) return;
    if (const auto hash = counts.find('#'); hash != std::string::npos) counts.resize(hash);
  }
  std::istringstream words(counts);
  uintmax_t vertices = 0, faces = 0;
  if (!(words >> vertices >> faces)) return;  // assimp reports it
  if (vertices > size || faces > size || vertices + faces > size)
    throw malformed_file(path, fmt::format("its header declares {} vertices and {} faces, more than a file of {} bytes holds",
                                           vertices, faces, size));
}

}  // namespace

SceneDesc read_mesh_file(const std::string& path, const MeshLimits& limits, MeshAnimation* animation,
                         const SceneReadOptions& options) {
  std::ifstream in = open_for_reading(path);
  const std::string ext = lower_extension(path);
  std::error_code ec;
  if (ext == ".ply") check_ply_header(in, path, std::filesystem::file_size(path, ec));
  if (ext == ".off") check_off_header(in, path, std::filesystem::file_size(path, ec));
  GltfFacts gltf;
  if (ext == ".gltf" || ext == ".glb") gltf = check_gltf(in, path, ext == ".glb");
  Assimp::Importer importer;
  // Points and lines are dropped by SortByPType; triangulated polygons keep
  // their file order. Node transforms are applied by the reader itself, so
  // that cameras and lights move with their nodes.
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const aiScene* scene = importer.ReadFile(path, aiProcess_Triangulate | aiProcess_SortByPType);
  if (!scene || !scene->mRootNode || (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE))
    throw malformed_file(path, importer.GetErrorString());
  if (animation) *animation = MeshAnimation{};
  return mesh_import::MeshReader(*scene, path, ext, limits, animation, options, std::move(gltf.infinite_far)).read();
}

SceneDesc read_scene_file(const std::string& path, MeshAnimation* animation, const SceneReadOptions& options) {
  const std::string ext = lower_extension(path);
  if (animation) *animation = MeshAnimation{};
  if ((ext == ".nff" || ext == ".dat") && !options.camera_name.empty())
    throw std::invalid_argument(fmt::format("camera name: '{}' has one viewpoint and no named cameras", path));
  if (ext == ".nff") return read_nff_file(path);
  if (ext == ".dat") return read_tachyon_file(path);
  return read_mesh_file(path, {}, animation, options);
}

}  // namespace holoray
