// holoray/scene: MTL bump maps (`bump`, `map_Bump`) read as tangent-space
// normal maps, so that one normal-map path (RenderScene::apply_normal_map)
// shades them all.
#pragma once

#include "scene/scene_desc.hpp"

namespace holoray {

/// True when every texel's three codes are equal: a height (bump) map, not
/// a normal map. Files in the wild use `bump` for both; a normal map's
/// texels are bluish, never grey over the whole image.
bool is_grey(const ImageMap& image);

/// The normal map of a height map: heights h = code / 255, rows v up
/// (ImageMap's order), repeating at the edges; the normal of the surface
/// z = strength * h over a grid of unit texels, by central differences,
/// (-strength dh/dx, -strength dh/dy, 1) normalised and encoded as glTF's
/// normal maps are (code = 255 (n + 1) / 2, x along u, y along v). A rise
/// of the whole range across two texels tilts the normal by 27 degrees at
/// strength 1 (MTL's `-bm`). Linear codes (ImageMap::srgb false).
ImageMap normals_from_heights(const ImageMap& heights, double strength);

}  // namespace holoray
