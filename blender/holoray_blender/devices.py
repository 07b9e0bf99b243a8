"""The Device settings' values: `device` is the CPU or the GPU path, and
`gpu_device` which Vulkan device the GPU path takes: holoray's first GPU
(`--device gpu`: the first GPU, else lavapipe) or one by name, as `gpu:N`
counts them. The devices are listed the first time `gpu_device` is read or
drawn in a Blender session (so a CPU render lists none), by holoray's module
where it loads in Blender, else by `holoray devices`."""

import re
import subprocess

from . import inprocess

# (identifier, name, description, number): a .blend stores the number, so
# device N is 100 + N whatever else the machine lists.
_FIRST = ("FIRST", "First GPU", "holoray's --device gpu: the first Vulkan GPU, else the first device (lavapipe)", 0)
_listed = None  # Blender keeps no copy of a dynamic enum's strings: they must outlive the call


def _device_lines(binary):
    """'N: name, GPU|CPU, Vulkan x.y, memory' lines, or [] where holoray
    lists none (no loader, no device, or no holoray at all)."""
    module = inprocess.find_module(binary)
    try:
        if module is not None:
            return list(module.gpu_devices())
        if binary:
            run = subprocess.run([binary, "devices"], capture_output=True, text=True, timeout=30)
            return run.stdout.splitlines() if run.returncode == 0 else []
    except (RuntimeError, OSError, subprocess.TimeoutExpired):
        pass
    return []


def choices(binary):
    """`gpu_device`'s items: the first GPU, then one per device holoray
    lists ('0', '0: llvmpipe (...)')."""
    global _listed
    if _listed is None:
        items = [_FIRST]
        for line in _device_lines(binary):
            m = re.match(r"(\d+): (.*), (?:GPU|CPU), .*$", line)  # the name may hold commas
            if m:
                n, name = int(m.group(1)), m.group(2)
                items.append((str(n), f"{n}: {name}", f"holoray's --device gpu:{n}: {line.split(': ', 1)[1]}", 100 + n))
        _listed = items
    return _listed


def device_argument(settings):
    """holoray's --device for the settings: 'cpu', 'gpu' or 'gpu:N'."""
    if settings.device == "CPU":
        return "cpu"
    return "gpu" if settings.gpu_device in ("FIRST", "") else f"gpu:{settings.gpu_device}"


def missing_gpu(settings):
    """What to tell the user when the file chose a GPU device this machine
    lacks (the menu reads it as no item, and holoray takes the first GPU),
    else None."""
    if settings.device == "GPU" and settings.gpu_device == "":
        return (f"the GPU device chosen in this file (number {settings.get('gpu_device', 0) - 100}) is not on this "
                "machine: rendering on the first GPU (holoray devices lists this machine's)")
    return None
