"""Light the glTF export cannot carry, said to holoray's path integrator:
Blender's lights with their radii, sun angles and area shapes as a lights
file (docs/lights.md, "Lights file"; Blender's own units, the glTF's
frame), and the World as environment options (its colour, or its
Environment Texture with the Background's strength and a Mapping node's Z
rotation). What cannot be said is returned as one sentence each."""

import math

import bpy
from mathutils import Vector

from . import placement


def _vec(v):
    return "[{:.9g}, {:.9g}, {:.9g}]".format(*v)


def _renders(obj):
    return not obj.hide_render and obj.visible_get()


def write_lights(scene, path):
    """Writes every light that renders to `path` (TOML) and returns how many.
    Positions and directions in the glTF's frame (y up), as the export's."""
    out = ["# holoray lights file, written by the Blender add-on: Blender's lights in its units\n"]
    count = 0
    for obj in scene.objects:
        if obj.type != "LIGHT" or not _renders(obj):
            continue
        light = obj.data
        m = obj.matrix_world
        pos = placement.to_gltf(m.translation)
        # Blender's lights shine down their local -Z; an area light's local X is its `size` side.
        down = placement.to_gltf((m.to_3x3() @ Vector((0, 0, -1))).normalized())
        colour = _vec(light.color)
        lines = [f"[[light]]  # {obj.name}"]
        if light.type == "POINT":
            lines += ['type = "point"', f"position = {_vec(pos)}", f"power = {light.energy:.9g}",
                      f"radius = {light.shadow_soft_size:.9g}"]
        elif light.type == "SPOT":
            lines += ['type = "spot"', f"position = {_vec(pos)}", f"direction = {_vec(down)}",
                      f"power = {light.energy:.9g}", f"radius = {light.shadow_soft_size:.9g}",
                      f"spot_size = {math.degrees(light.spot_size):.9g}", f"spot_blend = {light.spot_blend:.9g}"]
        elif light.type == "SUN":
            lines += ['type = "sun"', f"direction = {_vec(down)}", f"strength = {light.energy:.9g}",
                      f"angle = {math.degrees(light.angle):.9g}"]
        elif light.type == "AREA":
            scale = m.to_scale()
            right = placement.to_gltf((m.to_3x3() @ Vector((1, 0, 0))).normalized())
            shape = light.shape.lower()
            sx, sy = light.size * scale.x, (light.size_y if shape in ("rectangle", "ellipse") else light.size) * scale.y
            size = f"[{sx:.9g}, {sy:.9g}]" if shape in ("rectangle", "ellipse") else f"{sx:.9g}"
            # The file takes watts as Cycles 4 does (radiance P / (pi A));
            # Cycles 3 gave an area light P / (4 A), the same light as
            # pi / 4 of its power in Cycles 4 (lights.md, "Lights file").
            power = light.energy * (math.pi / 4 if bpy.app.version < (4, 0, 0) else 1)
            lines += ['type = "area"', f"position = {_vec(pos)}", f"direction = {_vec(down)}", f"right = {_vec(right)}",
                      f'shape = "{shape}"', f"size = {size}", f"power = {power:.9g}"]
        else:
            continue
        lines.append(f"colour = {colour}")
        out.append("\n".join(lines) + "\n")
        count += 1
    with open(path, "w", encoding="utf-8") as f:
        f.write("\n".join(out))
    return count


def world(scene):
    """({'environment': image path or None, 'colour': (r, g, b) or None,
    'strength': S, 'rotation': degrees}, [what is left out]) of the scene's
    World: a Background node's colour, or the Environment Texture feeding it
    (through a Mapping node, whose Z rotation is kept)."""
    out = {"environment": None, "colour": None, "strength": 1.0, "rotation": 0.0}
    w = scene.world
    if w is None:
        return out, []
    if not w.use_nodes:
        out["colour"] = tuple(w.color)
        return out, []
    bg = next((n for n in w.node_tree.nodes if n.type == "BACKGROUND"), None)
    if bg is None:
        return out, ["the world has no Background node: holoray's environment is black"]
    out["strength"] = bg.inputs["Strength"].default_value
    colour = bg.inputs["Color"]
    if not colour.is_linked:
        out["colour"] = tuple(colour.default_value[:3])
        return out, []
    node = colour.links[0].from_node
    if node.type != "TEX_ENVIRONMENT" or node.image is None:
        return out, [f"the world's colour comes from '{node.name}' ({node.bl_label}): holoray takes a colour or an "
                     "Environment Texture; its environment is black"]
    left_out = []
    if node.projection != "EQUIRECTANGULAR":
        left_out.append(f"the world's Environment Texture is {node.projection.lower()}: holoray reads it as equirectangular")
    vector = node.inputs["Vector"]
    if vector.is_linked:
        mapping = vector.links[0].from_node
        if mapping.type == "MAPPING":
            rotation = mapping.inputs["Rotation"].default_value
            out["rotation"] = math.degrees(rotation[2])
            if abs(rotation[0]) > 1e-6 or abs(rotation[1]) > 1e-6:
                left_out.append("the world's Mapping node turns about X or Y: holoray keeps its Z rotation only")
        else:
            left_out.append(f"the world's Environment Texture reads its vector from '{mapping.name}': holoray maps it "
                            "as the default")
    out["environment"] = bpy.path.abspath(node.image.filepath, library=node.image.library)
    return out, left_out
