"""What holoray is asked to render, said once for both ways of running it:
`spec()` turns the settings and the camera into a plain description (the
camera kind and its parameters in the glTF frame, the tracing options),
which `cli_args()` writes as `holoray render` options and `inprocess`
builds as the Python module's camera objects."""

import bpy

from . import devices, lighting, placement

# The AOVs holoray writes, by the name the settings use.
AOVS = ("albedo", "depth", "normal")


def path_tracing(settings):
    """Whether the render path traces (Integrator Path tracing, on either device)."""
    return settings.integrator == "PATH"


def spec(scene, settings, camera_object, width, height, lights_file=None):
    """The render as a dict: 'camera' ('integral', 'pinhole', 'quilt',
    'display', 'looking_glass') with that camera's parameters (world
    positions and directions in the exported glTF's frame, lengths in scene
    units, angles in degrees), and 'max_depth', 'threads' (0: holoray's
    defaults), 'device' ('cpu', 'gpu' or 'gpu:N'), 'aovs' (the AOVs the camera gives:
    none for panels), 'integrator' ('whitted' or 'path'), 'samples', and
    for path tracing 'world' (lighting.world()'s), 'lights' (the lights
    file written for it, `lights_file`), 'blender_principled',
    'share_views' (a quilt's, on the CPU; else 0) and 'seed' (the
    samples' seed, plus the frame's number with an animated seed, as
    Cycles' Seed and Use Animated Seed)."""
    s = settings
    out = {"max_depth": s.max_depth, "threads": s.threads, "device": devices.device_argument(s),
           "integrator": "path" if path_tracing(s) else "whitted", "samples": s.samples, "world": None, "lights": None}
    if path_tracing(s):
        out["world"] = lighting.world(scene)[0]
        out["lights"] = lights_file
        # glTF materials as Blender 3.x's Principled BSDF shades them (what
        # Cycles renders of the .blend); Blender 4's Principled BSDF layers
        # its diffuse under the specular energy-conservingly, nearer glTF's
        # own BRDF, which holoray then keeps.
        out["blender_principled"] = bpy.app.version < (4, 0, 0)
        # A quilt's views share their samples on the CPU only.
        out["share_views"] = s.share_views if s.camera == "QUILT" and out["device"] == "cpu" else 0
        out["seed"] = (s.seed + (scene.frame_current if s.use_animated_seed else 0)) % 2**32
    if s.camera == "INTEGRAL":
        place = placement.array_placement(camera_object, width / height, s.mode == "PSEUDOSCOPIC")
        out.update(camera="integral", grid=s.grid.lower(), lenses=(s.lenses_x, s.lenses_y if s.grid != "LENTICULAR" else 1),
                   pixels_per_lens=s.pixels_per_lens, mode=s.mode.lower(),
                   origin=tuple(placement.to_gltf(place.origin)), normal=tuple(placement.to_gltf(place.normal)),
                   up=tuple(placement.to_gltf(place.up)), pitch=place.width / s.lenses_x,
                   rows=s.lenticular_rows if s.grid == "LENTICULAR" else None,
                   gap=s.gap if s.use_gap else None, fov_lens=None if s.use_gap else s.fov_lens)
    elif s.camera == "PINHOLE":
        cam = camera_object.data
        out.update(camera="pinhole", resolution=(width, height), shift=(cam.shift_x, cam.shift_y))
    elif s.camera == "QUILT":
        out.update(camera="quilt", columns=s.quilt_columns, rows=s.quilt_rows,
                   view_resolution=(s.view_width, s.view_height), view_cone=s.view_cone,
                   focus_distance=placement.focus_distance(camera_object))
    elif s.camera == "DISPLAY":
        out.update(camera="display", path=bpy.path.abspath(s.display_file))
    elif s.camera == "LOOKING_GLASS":
        out.update(camera="looking_glass", path=bpy.path.abspath(s.calibration_file),
                   focus_distance=placement.focus_distance(camera_object))
    panel = out["camera"] in ("display", "looking_glass")
    out["aovs"] = [] if panel else [a for a in AOVS if getattr(s, f"aov_{a}")]
    return out


def _fmt(v):
    return ",".join(f"{x:.9g}" for x in v)


def cli_args(job):
    """The `holoray render` options that say `job` (scene and output not included)."""
    kind = job["camera"]
    if kind == "integral":
        args = ["--grid", job["grid"], "--lenses", "{}x{}".format(*job["lenses"]),
                "--pixels-per-lens", str(job["pixels_per_lens"]), "--mode", job["mode"],
                "--origin", _fmt(job["origin"]), "--normal", _fmt(job["normal"]), "--up", _fmt(job["up"]),
                "--pitch", f"{job['pitch']:.9g}"]
        if job["rows"] is not None:
            args += ["--rows", str(job["rows"])]
        args += ["--gap", f"{job['gap']:.9g}"] if job["gap"] is not None else ["--fov-lens", f"{job['fov_lens']:.9g}"]
    elif kind == "pinhole":
        args = ["--camera", "pinhole", "--resolution", "{}x{}".format(*job["resolution"]), "--shift", _fmt(job["shift"])]
    elif kind == "quilt":
        args = ["--quilt", f"{job['columns']}x{job['rows']}", "--resolution", "{}x{}".format(*job["view_resolution"]),
                "--view-cone", f"{job['view_cone']:.9g}", "--focus-distance", f"{job['focus_distance']:.9g}"]
    elif kind == "display":
        args = ["--display", job["path"]]
    else:
        args = ["--looking-glass", job["path"], "--focus-distance", f"{job['focus_distance']:.9g}"]
    if job["max_depth"]:
        args += ["--max-depth", str(job["max_depth"])]
    if job["threads"]:
        args += ["--threads", str(job["threads"])]
    if job["device"] != "cpu":
        args += ["--device", job["device"]]
    if job["aovs"]:
        args += ["--aov", ",".join(job["aovs"])]
    args += ["--spp", str(job["samples"])]
    if job["integrator"] == "path":
        args += ["--integrator", "path"] + (["--blender-principled"] if job["blender_principled"] else [])
        if job["share_views"]:
            args += ["--share-views", str(job["share_views"])]
        if job["seed"]:
            args += ["--seed", str(job["seed"])]
        if job["lights"]:
            args += ["--lights", job["lights"]]
        w = job["world"]
        if w["environment"]:
            args += ["--environment", w["environment"], "--environment-rotation", f"{w['rotation']:.9g}"]
        elif w["colour"] is not None:
            args += ["--environment-colour", _fmt(w["colour"])]
        if w["environment"] or w["colour"] is not None:
            args += ["--environment-strength", f"{w['strength']:.9g}"]
    return args
