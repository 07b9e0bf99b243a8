// holoray/scene: glTF 2.0 files checked before assimp reads them. Debian's
// assimp (5.2 on Debian 12, 5.4 on Debian 13) trusts parts of a glTF file
// that the specification requires but a damaged or hand-written file may
// lack, and dereferences or divides by them: the process crashes instead of
// failing. Every rule here was found by fuzz/ (target gltf) or by reading
// assimp's glTF2 importer, and each refuses the file with what it expected.
#pragma once

#include <fstream>
#include <string>
#include <vector>

namespace holoray {

/// What the glTF JSON says that assimp does not pass on.
struct GltfFacts {
  /// Per camera, in file order: true for a perspective camera without
  /// `zfar`, which sees to infinity (glTF 2.0 §5.12; assimp writes 100).
  std::vector<bool> infinite_far;
};

/// Checks the glTF (`binary`: GLB) file open in `in`, named `path` in
/// messages, and returns its facts. Errors: ParseError with line:col for
/// text that is not JSON; std::runtime_error ("cannot read 'PATH': ...")
/// naming the JSON place, e.g. "/accessors/3/count", and what glTF 2.0
/// requires there, for a structure assimp would crash on.
GltfFacts check_gltf(std::ifstream& in, const std::string& path, bool binary);

}  // namespace holoray
