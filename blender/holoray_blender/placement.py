"""Where holoray's camera stands, from Blender's active camera (world frame,
Blender's Z up; `to_gltf` turns a point or direction into the exported
glTF's Y-up frame, as Blender's exporter writes it).

The lens array stands at the camera's focus distance (its depth-of-field
focus object or distance: the zero-parallax plane), faces the camera, and
spans the camera's field of view there, lens shift included; the render's
aspect is the array's (lenses x pixels per lens), so the sensor fit decides
which side the sensor's size spans (Blender's rule)."""

from dataclasses import dataclass

from mathutils import Vector


class PlacementError(Exception):
    """The scene cannot place the camera: the message says what to change."""


@dataclass
class ArrayPlacement:
    origin: Vector  # the array's centre, world
    normal: Vector  # unit, toward the viewer
    up: Vector      # unit, the camera's up
    width: float    # the array's width (its x extent), world units
    height: float


def focus_distance(camera_object):
    """The zero-parallax distance along the view: the focus object's depth, else the focus distance."""
    cam = camera_object.data
    forward = (camera_object.matrix_world.to_3x3() @ Vector((0, 0, -1))).normalized()
    if cam.dof.focus_object is not None:
        d = (cam.dof.focus_object.matrix_world.translation - camera_object.matrix_world.translation).dot(forward)
    else:
        d = cam.dof.focus_distance
    if not d > 0:
        raise PlacementError(f"the camera '{camera_object.name}' focuses at {d:.4g}: set a focus distance (or a focus "
                             "object in front of it) where the lens array should stand")
    return d


def frame_size(camera_object, distance, aspect):
    """(width, height) of the camera's view at `distance`, for an image of `aspect` = width / height."""
    cam = camera_object.data
    if cam.type == "ORTHO":
        span = cam.ortho_scale
    elif cam.type == "PERSP":
        fit = cam.sensor_fit
        if fit == "AUTO":
            fit = "HORIZONTAL" if aspect >= 1 else "VERTICAL"
            sensor = cam.sensor_width
        else:
            sensor = cam.sensor_width if fit == "HORIZONTAL" else cam.sensor_height
        span = distance * sensor / cam.lens
    else:
        raise PlacementError(f"the camera '{camera_object.name}' is panoramic: holoray places a lens array from a "
                             "perspective or orthographic camera")
    if cam.type == "ORTHO":
        fit = "HORIZONTAL" if aspect >= 1 else "VERTICAL"
    return (span, span / aspect) if fit == "HORIZONTAL" else (span * aspect, span)


def camera_axes(camera_object):
    """The camera's forward, up and right unit vectors (Blender world)."""
    m = camera_object.matrix_world.to_3x3().normalized()
    return tuple((m @ Vector(v)).normalized() for v in ((0, 0, -1), (0, 1, 0), (1, 0, 0)))


def array_placement(camera_object, aspect, pseudoscopic=False):
    """The lens array for `camera_object`, an image of `aspect` (width / height)."""
    forward, up, right = camera_axes(camera_object)
    d = focus_distance(camera_object)
    width, height = frame_size(camera_object, d, aspect)
    cam = camera_object.data
    # Lens shift moves the frame by shift times its larger side (Blender's rule).
    larger = max(width, height)
    centre = camera_object.matrix_world.translation + forward * d + right * (cam.shift_x * larger) + up * (cam.shift_y * larger)
    if pseudoscopic:  # a direct pickup: the array at the camera, looking where it looks
        return ArrayPlacement(camera_object.matrix_world.translation.copy(), forward, up, width, height)
    return ArrayPlacement(centre, -forward, up, width, height)


def to_gltf(v):
    """A Blender world vector in the exported glTF's frame (Y up: x, z, -y)."""
    return Vector((v.x, v.z, -v.y))
