"""The tests' scene, built in a fresh Blender (`--factory-startup`): a
textured cube on a plane, a sun and a point light, a camera whose depth of
field focuses at the cube, and holoray as the render engine. Run inside
Blender; `build(addon=True)` enables the add-on (found through
BLENDER_USER_SCRIPTS)."""

import os

import addon_utils
import bpy


def checker_image(name="checker", size=64):
    img = bpy.data.images.new(name, size, size)
    px = []
    for y in range(size):
        for x in range(size):
            on = ((x // 8) + (y // 8)) % 2 == 0
            px += [0.9, 0.2, 0.1, 1.0] if on else [0.1, 0.3, 0.8, 1.0]
    img.pixels.foreach_set(px)
    img.pack()
    return img


def material(name, colour=None, image=None):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    bsdf = mat.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Roughness"].default_value = 1.0
    # Blender 4 renamed the Principled BSDF's "Specular" to "Specular IOR Level".
    bsdf.inputs["Specular" if "Specular" in bsdf.inputs else "Specular IOR Level"].default_value = 0.0
    if colour is not None:
        bsdf.inputs["Base Color"].default_value = (*colour, 1.0)
    if image is not None:
        tex = mat.node_tree.nodes.new("ShaderNodeTexImage")
        tex.image = image
        tex.interpolation = "Closest"
        mat.node_tree.links.new(tex.outputs["Color"], bsdf.inputs["Base Color"])
    return mat


def build(addon=True, fresh=True):
    """The test scene, from an empty one (`fresh`: Blender's factory
    settings; else the open file, emptied); returns it."""
    if fresh:
        bpy.ops.wm.read_factory_settings(use_empty=True)
    else:
        for obj in list(bpy.data.objects):
            bpy.data.objects.remove(obj)
    if addon:  # the add-on's module: HOLORAY_BLENDER_ADDON names an installed extension's
        addon_utils.enable(os.environ.get("HOLORAY_BLENDER_ADDON", "holoray_blender"), default_set=True,
                           handle_error=None)
    scene = bpy.context.scene
    bpy.ops.mesh.primitive_cube_add(size=1.0, location=(0, 0, 0.5))
    cube = bpy.context.view_layer.objects.active
    cube.rotation_euler = (0, 0, 0.5)
    cube.data.materials.append(material("cube", image=checker_image()))
    bpy.ops.mesh.primitive_plane_add(size=6.0, location=(0, 0, 0))
    bpy.context.view_layer.objects.active.data.materials.append(material("floor", colour=(0.6, 0.6, 0.55)))
    bpy.ops.object.light_add(type="SUN", location=(3, -2, 5), rotation=(0.6, 0.2, 0.4))
    bpy.context.view_layer.objects.active.data.energy = 3.0
    bpy.ops.object.light_add(type="POINT", location=(-2, -3, 3))
    bpy.context.view_layer.objects.active.data.energy = 400.0
    bpy.ops.object.camera_add(location=(0, -5, 2.5), rotation=(1.18, 0, 0))
    cam = bpy.context.view_layer.objects.active
    cam.data.lens = 50
    cam.data.dof.focus_distance = 5.0
    scene.camera = cam
    scene.world = None
    if addon:
        scene.render.engine = "HOLORAY"
    return scene
