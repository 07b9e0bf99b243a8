"""holoray's Python module inside Blender's own process: where the module
loads (built for the Python that Blender embeds, as Debian's Blender and
Debian's python3 share 3.11), the engine renders through it and takes the
numpy arrays straight into the render result, with no holoray process to
start, no EXR to write and none for Blender to read back (Blender's EXR
reader took 47 ms of a 1024x1024 render: bench/blender_results.md)."""

import os
import sys

_NOT_TRIED = object()
_found = {}  # program path (or "") -> the module or None, tried once per process


def find_module(binary):
    """The holoray module: the one Python imports (the .deb puts it in
    /usr/lib/python3/dist-packages, on Blender's path), else the one beside
    the program (a build tree: build/holoray and build/python/holoray).
    None when neither imports (missing, or built for another Python)."""
    key = binary or ""
    module = _found.get(key, _NOT_TRIED)
    if module is _NOT_TRIED:
        module = _import(binary)
        _found[key] = module
    return module


def release_gpu_devices():
    """Hands back the GPU devices the module keeps between renders (the
    add-on disabled, Blender closing), so that their memory on the GPU goes
    to Blender's own engines."""
    for module in _found.values():
        if module is not None:
            module.release_gpu_devices()


def _import(binary):
    try:
        import holoray
        return holoray
    except ImportError:
        pass
    if not binary:
        return None
    folder = os.path.join(os.path.dirname(os.path.realpath(binary)), "python")
    if not os.path.isfile(os.path.join(folder, "holoray", "__init__.py")):
        return None
    sys.path.insert(0, folder)
    try:
        import holoray
        return holoray
    except ImportError:
        sys.path.remove(folder)
        sys.modules.pop("holoray", None)
        return None


def camera(hr, job):
    """job.spec()'s camera as the module's camera object."""
    kind = job["camera"]
    if kind == "integral":
        return hr.LensArray(job["lenses"], job["pixels_per_lens"], job["grid"], job["fov_lens"], job["mode"],
                            pitch=job["pitch"], gap=job["gap"], rows=job["rows"], origin=job["origin"],
                            normal=job["normal"], up=job["up"])
    if kind == "pinhole":
        return hr.Pinhole(job["resolution"], shift=job["shift"])
    if kind == "quilt":
        return hr.Quilt(job["columns"], job["rows"], job["view_resolution"], job["view_cone"],
                        focus_distance=job["focus_distance"])
    if kind == "display":
        return hr.Display(job["path"])
    return hr.LookingGlass(job["path"], focus_distance=job["focus_distance"])


def render(hr, gltf, job, progress):
    """(holoray.Result, the scene's warnings) of `job` (job.spec()) on the
    exported scene. The module's exceptions pass through; so does whatever
    `progress(fraction)` raises, after the render has stopped."""
    scene = hr.load_scene(gltf)
    light = {}
    if job["integrator"] == "path":
        if job["lights"]:
            scene.add_lights(job["lights"])
        w = job["world"]
        environment = w["environment"] or w["colour"]
        light = dict(integrator="path", blender_principled=job["blender_principled"], environment=environment,
                     environment_strength=w["strength"] if environment is not None else 1.0,
                     environment_rotation=w["rotation"], share_views=job["share_views"], seed=job["seed"])
    result = hr.render(scene, camera(hr, job), threads=job["threads"] or None, max_depth=job["max_depth"] or None,
                       aovs=job["aovs"], progress=progress, device=job["device"], spp=job["samples"], **light)
    return result, list(scene.warnings)
