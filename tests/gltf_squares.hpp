// Test helper: a glTF file of squares, written in the test (tests of the
// glTF materials on the Whitted path and of the path integrator on both
// devices).
#pragma once

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "test_util.hpp"

namespace holoray::test {

// A glTF scene: squares facing +z, square k with material k; the camera on
// the +z axis at z = 4 looking down -z; KHR_lights_punctual's `lights` and
// the one node that places them.
struct GltfSquares {
  std::string materials, lights, light_node;
  std::vector<std::pair<double, double>> squares;  // (half-size, z)
};

inline std::string gltf(const GltfSquares& s) {
  std::vector<uint8_t> buffer;
  std::vector<std::string> views, accessors, meshes, nodes;
  auto add = [&](const void* data, size_t bytes) {
    const size_t offset = buffer.size();
    buffer.resize(offset + bytes);
    std::memcpy(buffer.data() + offset, data, bytes);
    views.push_back(fmt::format(R"({{"buffer": 0, "byteOffset": {}, "byteLength": {}}})", offset, bytes));
    return views.size() - 1;
  };
  for (size_t k = 0; k < s.squares.size(); ++k) {
    const auto h = static_cast<float>(s.squares[k].first), z = static_cast<float>(s.squares[k].second);
    const float p[12] = {-h, -h, z, h, -h, z, h, h, z, -h, h, z};
    const uint16_t i[6] = {0, 1, 2, 0, 2, 3};
    const size_t pv = add(p, sizeof p), iv = add(i, sizeof i);
    accessors.push_back(fmt::format(
        R"({{"bufferView": {}, "componentType": 5126, "count": 4, "type": "VEC3", "min": [{}, {}, {}], "max": [{}, {}, {}]}})",
        pv, -h, -h, z, h, h, z));
    accessors.push_back(fmt::format(R"({{"bufferView": {}, "componentType": 5123, "count": 6, "type": "SCALAR"}})", iv));
    meshes.push_back(fmt::format(R"({{"primitives": [{{"attributes": {{"POSITION": {}}}, "indices": {}, "material": {}}}]}})",
                                 accessors.size() - 2, accessors.size() - 1, k));
    nodes.push_back(fmt::format(R"({{"mesh": {}}})", k));
  }
  nodes.push_back(R"({"camera": 0, "translation": [0, 0, 4]})");
  nodes.push_back(s.light_node);
  std::string scene_nodes;
  for (size_t k = 0; k < nodes.size(); ++k) scene_nodes += fmt::format("{}{}", k ? ", " : "", k);
  return fmt::format(R"({{"asset": {{"version": "2.0"}}, "scene": 0, "scenes": [{{"nodes": [{}]}}],
 "extensionsUsed": ["KHR_lights_punctual", "KHR_materials_transmission"], "extensions": {{"KHR_lights_punctual": {{"lights": [{}]}}}},
 "nodes": [{}],
 "cameras": [{{"type": "perspective", "perspective": {{"yfov": 0.6, "aspectRatio": 1.0, "znear": 0.1}}}}],
 "meshes": [{}], "materials": [{}],
 "buffers": [{{"byteLength": {}, "uri": "data:application/octet-stream;base64,{}"}}],
 "bufferViews": [{}], "accessors": [{}]}})",
                     scene_nodes, s.lights, fmt::join(nodes, ", "), fmt::join(meshes, ", "), s.materials, buffer.size(),
                     test::base64(buffer), fmt::join(views, ", "), fmt::join(accessors, ", "));
}

}  // namespace holoray::test
