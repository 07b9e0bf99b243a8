#include "scene/gltf_check.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <functional>
#include <iterator>
#include <stdexcept>
#include <string_view>

#include "scene/parse_error.hpp"

namespace holoray {
namespace {

using nlohmann::json;

// The JSON of a .gltf file, or of a .glb file's first chunk (12-byte header,
// then the chunk's length, its type "JSON" and its text). A file that is not
// JSON is refused with its place: assimp's format detection would otherwise
// fall back on its other readers, and one of Debian's 5.2 reads past the end
// of a 15-byte file doing so.
json parse_gltf_json(std::ifstream& in, const std::string& path, bool binary) {
  std::string text;
  if (binary) {
    char head[20];
    if (!in.read(head, sizeof head) || std::string_view(head, 4) != "glTF" || std::string_view(head + 16, 4) != "JSON")
      throw malformed_file(path, "not a binary glTF file (expected the 'glTF' magic and a JSON chunk first)");
    uint32_t length = 0;
    std::memcpy(&length, head + 12, sizeof length);
    std::error_code ec;
    if (length > std::filesystem::file_size(path, ec) || ec)
      throw malformed_file(path, fmt::format("its JSON chunk claims {} bytes, more than the file holds", length));
    text.resize(length);
    if (!in.read(text.data(), length))
      throw malformed_file(path, "its JSON chunk is cut short");
  } else {
    text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  try {
    return json::parse(text);
  } catch (const json::parse_error& e) {
    // nlohmann's byte is one past the character it stopped at (1-based).
    const size_t at = std::min(text.size(), e.byte > 0 ? static_cast<size_t>(e.byte - 1) : size_t{0});
    std::string reason = e.what();
    if (const size_t colon = reason.find(": ", reason.find("column")); colon != std::string::npos)
      reason = reason.substr(colon + 2);
    if (binary) throw malformed_file(path, fmt::format("its JSON chunk is not JSON ({})", reason));
    const size_t newline = at == 0 ? std::string::npos : text.rfind('\n', at - 1);
    const size_t line_start = newline == std::string::npos ? 0 : newline + 1;
    const size_t line_end = std::min(text.find('\n', at), text.size());
    const int line = 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(line_start), '\n'));
    // The offending line under the message, unless it is long (a one-line file of megabytes).
    const bool show = line_end - line_start <= 200;
    throw ParseError(path, SourceLoc{line, static_cast<int>(at - line_start) + 1}, "expected glTF's JSON: " + reason,
                     show ? text.substr(line_start, line_end - line_start) : std::string());
  } catch (const json::exception& e) {  // a number out of range: no place given
    std::string reason = e.what();
    if (const size_t close = reason.find("] "); close != std::string::npos) reason = reason.substr(close + 2);
    throw malformed_file(path, fmt::format("its JSON is not glTF's ({})", reason));
  }
}

// The rules, each naming its place as a JSON pointer ("/accessors/3/count").
class GltfRules {
 public:
  GltfRules(const json& j, const std::string& path) : j_(j), path_(path) {}

  void check() {
    texture_transforms();
    morph_weights();
    accessors();
    animations();
    skins();
    data_uris();
  }

 private:
  [[noreturn]] void fail(const std::string& where, const std::string& expected) const {
    throw malformed_file(path_, fmt::format("{} {}", where, expected));
  }

  const json& top(const char* name) const {
    static const json empty = json::array();
    return j_.contains(name) && j_[name].is_array() ? j_[name] : empty;
  }

  // An index into the top-level array `into`, required at obj[key].
  size_t index(const json& obj, const char* key, const char* into, const std::string& where) const {
    const std::string at = where + "/" + key;
    if (!obj.contains(key)) fail(at, fmt::format("is missing (expected the index of one of the file's {})", into));
    const json& v = obj[key];
    const size_t n = top(into).size();
    if (!v.is_number_unsigned() || v.get<uint64_t>() >= n)
      fail(at, fmt::format("must be the index of one of the file's {} {} (0 to {})", n, into, n == 0 ? 0 : n - 1));
    return v.get<size_t>();
  }

  void one_of(const json& obj, const char* key, std::initializer_list<std::string_view> allowed, const std::string& where,
              bool required) const {
    if (!obj.contains(key)) {
      if (required) fail(where + "/" + key, fmt::format("is missing (expected one of {})", quoted(allowed)));
      return;
    }
    const json& v = obj[key];
    const bool ok = v.is_string() && std::find(allowed.begin(), allowed.end(), v.get<std::string>()) != allowed.end();
    if (!ok) fail(where + "/" + key, fmt::format("must be one of {}", quoted(allowed)));
  }

  void one_of(const json& obj, const char* key, std::initializer_list<int> allowed, const std::string& where) const {
    const bool ok = obj.contains(key) && obj[key].is_number_integer() &&
                    std::find(allowed.begin(), allowed.end(), obj[key].get<int64_t>()) != allowed.end();
    if (!ok) fail(where + "/" + key, fmt::format("must be one of {}", fmt::join(allowed, ", ")));
  }

  static std::string quoted(std::initializer_list<std::string_view> words) {
    std::string s;
    for (std::string_view w : words) s += (s.empty() ? "'" : ", '") + std::string(w) + "'";
    return s;
  }

  const json& object(const json& parent, const char* key, const std::string& where) const {
    if (!parent.contains(key) || !parent[key].is_object()) fail(where + "/" + key, "must be an object");
    return parent[key];
  }

  const json& array(const json& parent, const char* key, const std::string& where) const {
    if (!parent.contains(key) || !parent[key].is_array()) fail(where + "/" + key, "must be an array");
    return parent[key];
  }

  uint64_t accessor_count(size_t a) const { return top("accessors")[a]["count"].get<uint64_t>(); }

  // Values assimp 5.2 reads as numbers without checking that they are (its
  // rapidjson asserts, and the process aborts): KHR_texture_transform's
  // offset and scale, anywhere in a material, and a mesh's morph weights.
  void numbers(const json& v, size_t at_least, const std::string& where) const {
    bool ok = v.is_array() && v.size() >= at_least;
    for (size_t k = 0; ok && k < v.size(); ++k) ok = v[k].is_number();
    if (!ok)
      fail(where, fmt::format("must be an array of {}numbers",
                              at_least > 0 ? fmt::format("at least {} ", at_least) : std::string()));
  }

  void texture_transforms() const {
    std::function<void(const json&, const std::string&)> walk = [&](const json& v, const std::string& where) {
      if (v.is_object()) {
        for (const auto& [key, value] : v.items()) {
          const std::string at = where + "/" + key;
          if (key == "KHR_texture_transform" && value.is_object())
            for (const char* field : {"offset", "scale"})
              if (value.contains(field)) numbers(value[field], 2, at + "/" + field);
          walk(value, at);
        }
      } else if (v.is_array()) {
        for (size_t k = 0; k < v.size(); ++k) walk(v[k], where + "/" + std::to_string(k));
      }
    };
    walk(top("materials"), "/materials");
  }

  void morph_weights() const {
    const json& meshes = top("meshes");
    for (size_t m = 0; m < meshes.size(); ++m)
      if (meshes[m].is_object() && meshes[m].contains("weights"))
        numbers(meshes[m]["weights"], 0, fmt::format("/meshes/{}/weights", m));
  }

  // glTF 2.0 §5.10 and §5.21: an image's media type is type/subtype
  // (image/png, image/jpeg), in its mimeType and in a data URI's header.
  // assimp 5.2 takes the subtype as what follows the '/' unchecked (a type
  // without one crashed it, found by fuzz_gltf), and keeps a data URI's
  // offsets in single chars: a header (up to its ',') of 128 characters or
  // more sends it reading outside the string.
  void data_uris() const {
    for (const char* what : {"images", "buffers"}) {
      const json& all = top(what);
      for (size_t k = 0; k < all.size(); ++k) {
        if (!all[k].is_object()) continue;
        const std::string where = fmt::format("/{}/{}", what, k);
        if (std::string_view(what) == "images" && all[k].contains("mimeType") &&
            !(all[k]["mimeType"].is_string() && all[k]["mimeType"].get<std::string>().find('/') != std::string::npos))
          fail(where + "/mimeType", "must be a media type, type/subtype (image/png or image/jpeg)");
        if (!all[k].contains("uri") || !all[k]["uri"].is_string()) continue;
        const std::string& uri = all[k]["uri"].get_ref<const std::string&>();
        if (uri.rfind("data:", 0) != 0) continue;
        const size_t comma = uri.find(',');
        if (comma == std::string::npos || comma >= 100)
          fail(where + "/uri", "is a data URI whose header (up to its ',') must be under 100 characters");
        const std::string media = uri.substr(5, uri.find_first_of(";,", 5) - 5);
        if (!media.empty() && media.find('/') == std::string::npos)
          fail(where + "/uri", fmt::format("is a data URI whose media type '{}' must be type/subtype (as image/png)", media));
      }
    }
  }

  // glTF 2.0 §5.1-5.4: count ≥ 1, componentType and type from fixed lists, and a
  // sparse part with both its views. assimp divides by a count of 0, and
  // dereferences a sparse part's missing view.
  void accessors() const {
    const json& all = top("accessors");
    for (size_t a = 0; a < all.size(); ++a) {
      const std::string where = fmt::format("/accessors/{}", a);
      const json& acc = all[a];
      if (!acc.is_object()) fail(where, "must be an object");
      if (!acc.contains("count") || !acc["count"].is_number_unsigned() || acc["count"].get<uint64_t>() < 1)
        fail(where + "/count", "must be an integer of at least 1");
      one_of(acc, "componentType", {5120, 5121, 5122, 5123, 5125, 5126}, where);
      one_of(acc, "type", {"SCALAR", "VEC2", "VEC3", "VEC4", "MAT2", "MAT3", "MAT4"}, where, true);
      if (acc.contains("bufferView")) index(acc, "bufferView", "bufferViews", where);
      if (!acc.contains("sparse")) continue;
      const json& sparse = object(acc, "sparse", where);
      if (!sparse.contains("count") || !sparse["count"].is_number_unsigned() || sparse["count"].get<uint64_t>() < 1)
        fail(where + "/sparse/count", "must be an integer of at least 1");
      const json& indices = object(sparse, "indices", where + "/sparse");
      index(indices, "bufferView", "bufferViews", where + "/sparse/indices");
      one_of(indices, "componentType", {5121, 5123, 5125}, where + "/sparse/indices");
      index(object(sparse, "values", where + "/sparse"), "bufferView", "bufferViews", where + "/sparse/values");
    }
  }

  // glTF 2.0 §5.5-5.8: every channel names a sampler of its animation and a
  // target path (and here a node); every sampler an input and an output
  // accessor, the output holding one value (three for a cubic spline:
  // in-tangent, value, out-tangent) per input time, times the morph targets
  // for weights. assimp 5.2 indexes the file's nodes with a channel's missing
  // node, and reads past the output (or divides by zero) where the counts
  // disagree.
  void animations() const {
    const json& all = top("animations");
    for (size_t a = 0; a < all.size(); ++a) {
      const std::string where = fmt::format("/animations/{}", a);
      if (!all[a].is_object()) fail(where, "must be an object");
      const json& samplers = array(all[a], "samplers", where);
      const json& channels = array(all[a], "channels", where);
      for (size_t s = 0; s < samplers.size(); ++s) {
        const std::string at = fmt::format("{}/samplers/{}", where, s);
        if (!samplers[s].is_object()) fail(at, "must be an object");
        index(samplers[s], "input", "accessors", at);
        index(samplers[s], "output", "accessors", at);
        one_of(samplers[s], "interpolation", {"LINEAR", "STEP", "CUBICSPLINE"}, at, false);
      }
      for (size_t c = 0; c < channels.size(); ++c) {
        const std::string at = fmt::format("{}/channels/{}", where, c);
        if (!channels[c].is_object()) fail(at, "must be an object");
        const json& channel = channels[c];
        if (!channel.contains("sampler") || !channel["sampler"].is_number_unsigned() ||
            channel["sampler"].get<uint64_t>() >= samplers.size())
          fail(at + "/sampler", fmt::format("must be the index of one of the animation's {} samplers", samplers.size()));
        const json& target = object(channel, "target", at);
        if (!target.contains("node"))  // optional in glTF 2.0, for extensions that animate other things
          fail(at + "/target/node", "is missing: holoray animates nodes only (assimp crashes on a channel without one)");
        index(target, "node", "nodes", at + "/target");
        one_of(target, "path", {"translation", "rotation", "scale", "weights"}, at + "/target", true);
        const json& sampler = samplers[channel["sampler"].get<size_t>()];
        const uint64_t times = accessor_count(sampler["input"].get<size_t>());
        const uint64_t values = accessor_count(sampler["output"].get<size_t>());
        const uint64_t per_time = sampler.value("interpolation", "") == "CUBICSPLINE" ? 3 : 1;
        const bool weights = target["path"] == "weights";
        if (weights ? values % (per_time * times) != 0 || values < per_time * times : values != per_time * times)
          fail(fmt::format("{}/samplers/{}/output", where, channel["sampler"].get<size_t>()),
               fmt::format("holds {} values for {} times: expected {}{}", values, times, per_time * times,
                           weights ? " times the number of morph targets" : ""));
      }
    }
  }

  // assimp 5.2 dereferences a skin's inverse bind matrices without checking
  // that it has them (the specification lets it leave them out: identity).
  void skins() const {
    const json& all = top("skins");
    for (size_t k = 0; k < all.size(); ++k)
      if (all[k].is_object() && !all[k].contains("inverseBindMatrices"))
        throw malformed_file(path_, fmt::format("skin {} has no inverseBindMatrices, which assimp cannot read; export "
                                                "the skin with its inverse bind matrices",
                                                k));
  }

  const json& j_;
  const std::string& path_;
};

}  // namespace

GltfFacts check_gltf(std::ifstream& in, const std::string& path, bool binary) {
  const json j = parse_gltf_json(in, path, binary);
  GltfFacts facts;
  if (!j.is_object()) return facts;  // assimp says what it expected
  GltfRules(j, path).check();
  if (j.contains("cameras") && j["cameras"].is_array())
    for (const json& c : j["cameras"])
      facts.infinite_far.push_back(c.is_object() && c.contains("perspective") && c["perspective"].is_object() &&
                                   !c["perspective"].contains("zfar"));
  return facts;
}

}  // namespace holoray
