#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "api/internal.hpp"
#include "scene/lights_file.hpp"
#include "scene/mesh_reader.hpp"

namespace holoray::api {

namespace {

bool finite3(const std::array<double, 3>& v) { return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]); }
Vec3 vec(const Vec3d& v) { return {v[0], v[1], v[2]}; }

// std::invalid_argument "what: row k has a coordinate that is NaN or infinite".
template <size_t N>
void check_finite(const char* what, const std::vector<std::array<double, N>>& rows) {
  for (size_t k = 0; k < rows.size(); ++k)
    for (double x : rows[k])
      if (!std::isfinite(x))
        throw std::invalid_argument(fmt::format("{}: row {} has a coordinate that is NaN or infinite ({})", what, k, x));
}

void check_colour(const char* what, const Vec3d& c) {
  if (!finite3(c) || c[0] < 0 || c[1] < 0 || c[2] < 0)
    throw std::invalid_argument(fmt::format("{}: expected three finite values >= 0, got ({}, {}, {})", what, c[0], c[1], c[2]));
}

}  // namespace

Scene::Scene() : data_(std::make_shared<SceneData>()) {}
Scene::~Scene() = default;
Scene::Scene(const Scene& o) = default;
Scene& Scene::operator=(const Scene& o) = default;
Scene::Scene(Scene&&) noexcept = default;
Scene& Scene::operator=(Scene&&) noexcept = default;

SceneData& Scene::mutable_data() {
  // Another Scene or a Renderer shares it: change a copy of its own.
  if (data_.use_count() > 1) data_ = std::make_shared<SceneData>(*data_);
  return *data_;
}

Scene Scene::load(const std::string& path, const LoadOptions& options) {
  Scene s;
  s.data_->desc = read_scene_file(path, nullptr, {options.camera_name, options.texture_paths});
  return s;
}

int Scene::add_mesh(const Mesh& m) {
  const size_t n = m.vertices.size();
  if (m.faces.empty()) throw std::invalid_argument("faces: expected at least one triangle, got none");
  check_finite("vertices", m.vertices);
  check_finite("normals", m.normals);
  check_finite("uv", m.uv);
  check_colour("colour", m.colour);
  if (!m.normals.empty() && m.normals.size() != n)
    throw std::invalid_argument(fmt::format("normals: expected one per vertex ({}), got {}", n, m.normals.size()));
  if (!m.uv.empty() && m.uv.size() != n)
    throw std::invalid_argument(fmt::format("uv: expected one per vertex ({}), got {}", n, m.uv.size()));
  for (size_t k = 0; k < m.faces.size(); ++k)
    for (uint32_t v : m.faces[k])
      if (v >= n)
        throw std::invalid_argument(fmt::format("faces: row {} refers to vertex {}, but there are {} vertices", k, v, n));
  for (size_t k = 0; k < m.normals.size(); ++k) {
    const auto& v = m.normals[k];
    if (v[0] == 0 && v[1] == 0 && v[2] == 0) throw std::invalid_argument(fmt::format("normals: row {} is zero", k));
  }
  SceneDesc& d = mutable_data().desc;
  Material mat;
  mat.colour = vec(m.colour);
  if (m.texture) {
    const Texture& t = *m.texture;
    if (m.uv.empty()) throw std::invalid_argument("texture: goes with uv (the texture coordinates it is read at)");
    if (t.width < 1 || t.height < 1 || (t.channels != 3 && t.channels != 4))
      throw std::invalid_argument(
          fmt::format("texture: expected (H, W, 3) or (H, W, 4), got {}x{} with {} channels", t.height, t.width, t.channels));
    if (t.codes.size() != static_cast<size_t>(t.width) * t.height * t.channels)
      throw std::invalid_argument("texture: the codes do not fill width x height x channels");
    ImageMap img;
    img.path = fmt::format("texture of mesh {}", d.objects.size());
    img.width = t.width;
    img.height = t.height;
    img.srgb = true;
    const size_t pixels = static_cast<size_t>(t.width) * t.height;
    img.rgb.resize(pixels * 3);
    if (t.channels == 4) img.alpha.resize(pixels);
    // A mesh's image maps hold their bottom row first (v up, as the mesh
    // reader stores them); the texture's row 0 is its top.
    for (int y = 0; y < t.height; ++y)
      for (int x = 0; x < t.width; ++x) {
        const size_t at = static_cast<size_t>(y) * t.width + x;
        const size_t from = static_cast<size_t>(t.height - 1 - y) * t.width + x;
        for (int c = 0; c < 3; ++c) img.rgb[at * 3 + c] = t.codes[from * t.channels + c];
        if (t.channels == 4) img.alpha[at] = t.codes[from * 4 + 3];
      }
    d.images.push_back(std::move(img));
    TextureDesc tex;
    tex.kind = TextureDesc::Kind::uv_image;
    tex.image = static_cast<int>(d.images.size()) - 1;
    tex.srgb = true;
    d.textures.push_back(tex);
    mat.texture = static_cast<int>(d.textures.size()) - 1;
  }
  d.materials.push_back(mat);
  TriangleMeshDesc mesh;
  mesh.vertices.reserve(n);
  for (const Vec3d& v : m.vertices) mesh.vertices.push_back(vec(v));
  for (const Vec3d& v : m.normals) mesh.normals.push_back(normalize(vec(v)));
  mesh.triangles = m.faces;
  mesh.uvs = m.uv;
  d.objects.push_back({std::move(mesh), static_cast<int>(d.materials.size()) - 1, {}});
  return static_cast<int>(d.objects.size()) - 1;
}

int Scene::add_sphere(const Vec3d& centre, double radius, const Vec3d& colour) {
  if (!finite3(centre)) throw std::invalid_argument("centre: a coordinate is NaN or infinite");
  if (!(radius > 0) || !std::isfinite(radius))
    throw std::invalid_argument(fmt::format("radius: expected a finite number > 0, got {}", radius));
  check_colour("colour", colour);
  SceneDesc& d = mutable_data().desc;
  Material mat;
  mat.colour = vec(colour);
  d.materials.push_back(mat);
  d.objects.push_back({SphereDesc{vec(centre), radius}, static_cast<int>(d.materials.size()) - 1, {}});
  return static_cast<int>(d.objects.size()) - 1;
}

void Scene::add_light(const Vec3d& position, const Vec3d& colour) {
  if (!finite3(position)) throw std::invalid_argument("position: a coordinate is NaN or infinite");
  check_colour("colour", colour);
  Light l;
  l.position = vec(position);
  l.colour = vec(colour);
  // Its radiance as given, not scaled by NFF's 1/sqrt(lights) (nff-notes §4).
  l.photometric = true;
  mutable_data().desc.lights.push_back(l);
}

void Scene::add_lights(const std::string& path) {
  LightsFile file = read_lights_file(path);
  SceneDesc& desc = mutable_data().desc;
  // A mesh file's stand-in headlight lit a scene without lights: the
  // file's lights are the scene's own now.
  if (!file.lights.empty() || !file.area_lights.empty())
    std::erase_if(desc.lights, [](const Light& l) { return l.headlight; });
  desc.lights.insert(desc.lights.end(), file.lights.begin(), file.lights.end());
  desc.area_lights.insert(desc.area_lights.end(), file.area_lights.begin(), file.area_lights.end());
}

void Scene::set_viewpoint(const Vec3d& eye, const Vec3d& at, const Vec3d& up, double fov_deg) {
  if (!finite3(eye)) throw std::invalid_argument("eye: a coordinate is NaN or infinite");
  if (!finite3(at)) throw std::invalid_argument("at: a coordinate is NaN or infinite");
  if (!finite3(up)) throw std::invalid_argument("up: a coordinate is NaN or infinite");
  if (!(fov_deg > 0 && fov_deg < 180)) throw std::invalid_argument(fmt::format("fov_deg: expected degrees in (0, 180), got {}", fov_deg));
  const Vec3 from = vec(eye), to = vec(at), u = vec(up);
  if (length(from - to) == 0) throw std::invalid_argument("at: the same point as eye");
  if (!up_orients(to - from, u)) throw std::invalid_argument("up: parallel to the line of sight (or zero)");
  SceneDesc& d = mutable_data().desc;
  Viewpoint vp = d.viewpoint.value_or(Viewpoint{});
  vp.from = from;
  vp.at = to;
  vp.up = u;
  vp.angle_deg = fov_deg;
  vp.mirrored = false;
  d.viewpoint = vp;
  // A mesh file's stand-in light sits at its viewpoint: it follows it.
  for (Light& l : d.lights)
    if (l.headlight) l.position = from;
}

const std::string& Scene::source() const { return data_->desc.source; }
int Scene::object_count() const { return static_cast<int>(data_->desc.objects.size()); }
int Scene::light_count() const { return static_cast<int>(data_->desc.lights.size() + data_->desc.area_lights.size()); }
bool Scene::has_viewpoint() const { return data_->desc.viewpoint.has_value(); }
const std::vector<std::string>& Scene::warnings() const { return data_->desc.warnings; }
size_t Scene::warning_count() const { return data_->desc.warning_count; }

}  // namespace holoray::api
