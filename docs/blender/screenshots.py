"""Inside Blender's interface: the Render properties with holoray's panel and
the camera's view, a screenshot; F12's render, shown in the image editor, a
second one; then quit. Steps run on timers, so the interface draws between them."""
import os

import bpy

out = os.environ["HOLORAY_SHOTS"]


def areas(kind):
    return [a for a in bpy.context.window_manager.windows[0].screen.areas if a.type == kind]


def screenshot(name):
    win = bpy.context.window_manager.windows[0]
    with bpy.context.temp_override(window=win, screen=win.screen, area=win.screen.areas[0]):
        bpy.ops.screen.screenshot(filepath=os.path.join(out, name))


def settings():
    for a in areas("PROPERTIES"):
        a.spaces[0].context = "RENDER"
    for a in areas("VIEW_3D"):
        a.spaces[0].region_3d.view_perspective = "CAMERA"
    bpy.app.timers.register(render, first_interval=1.0)


def render():
    screenshot("ui_settings.png")
    bpy.ops.render.render()
    for a in areas("VIEW_3D"):
        a.type = "IMAGE_EDITOR"
        a.spaces[0].image = bpy.data.images["Render Result"]
    bpy.app.timers.register(fit, first_interval=1.5)


def fit():
    win = bpy.context.window_manager.windows[0]
    for a in areas("IMAGE_EDITOR"):
        with bpy.context.temp_override(window=win, screen=win.screen, area=a, region=a.regions[-1]):
            bpy.ops.image.view_all(fit_view=True)
    bpy.app.timers.register(result, first_interval=1.0)


def result():
    screenshot("ui_result.png")
    bpy.ops.wm.quit_blender()


bpy.app.timers.register(settings, first_interval=2.0)
