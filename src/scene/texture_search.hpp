// holoray/scene: where a texture a scene file names is found. Files carry the
// paths of the machine they were made on (absolute, Windows-style with drive
// letters and backslashes); other tools then look for the image by its base
// name beside the file and in folders the user names (Blender's "find missing
// files", assimp viewers, game engines' texture folders). holoray does the
// same, in a fixed order, and says everywhere it looked when it fails.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace holoray {

/// The places a texture was looked for, in order, and the first that exists.
struct TextureLookup {
  std::optional<std::string> found;  ///< the file's path; nullopt: none exists
  std::vector<std::string> tried;    ///< every path looked at, in order (for the warning)
};

/// Looks for the texture `named` (as the scene file writes it) for the scene
/// file `scene_file`:
///  1. the path as written, relative to the scene file's folder unless absolute;
///  2. the same with backslashes read as folder separators;
///  3. its base name (after the last '/' or '\') in the scene file's folder;
///  4. its base name in each folder of `search`, in order (--texture-path).
/// In steps 3 and 4 a name differing only in letter case also matches (the
/// file was named on a case-blind file system). Never throws for a missing
/// or unreadable folder: that place is simply not found.
TextureLookup find_texture(const std::string& named, const std::string& scene_file, const std::vector<std::string>& search);

/// The part of `path` after its last '/' or '\' (a Windows path's base name
/// on every system).
std::string texture_base_name(const std::string& path);

}  // namespace holoray
