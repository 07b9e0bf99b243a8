#!/usr/bin/env bash
# The Blender add-on's own cost: what exporting the scene (Blender's glTF
# exporter) and loading the EXRs back into the render result add to
# holoray's own run, on the add-on tests' scene (tests/blender/scene.py) as a
# 64x64-lens x 16 px EIA (1024x1024), rendered as a user renders it:
#   - F12 in an open session: two renders (bpy.ops.render.render) in one
#     Blender, the first paying the Python modules' first use, each timed
#     whole as Blender runs it (its wall);
#   - a one-off `blender -b scene.blend -E HOLORAY -f 1`, the whole command
#     timed from outside, Blender's start included.
# Each way of running holoray (its Python module in Blender's process, the
# program) is timed; the engine prints its phases (export, holoray, result)
# and the way. Rounds alternate the
# two ways. Writes bench/blender_results.md.
# Usage: bash bench/run_blender_bench.sh   (ROUNDS=7)
set -euo pipefail
cd "$(dirname "$0")/.."
ROUNDS=${ROUNDS:-7}
source bench/lib.sh
command -v blender >/dev/null || { echo "run_blender_bench.sh: blender is not installed" >&2; exit 1; }
export BLENDER_USER_SCRIPTS=$PWD/build/blender PATH=$PWD/build:$PATH
blender -b --factory-startup --python tests/blender/case.py -- bench "$tmp" >/dev/null
/usr/bin/python3 - "$tmp" "$ROUNDS" "$(machine)" "$(git describe --always --dirty)" > bench/blender_results.md <<'PY'
import re, statistics, subprocess, sys, time
tmp, rounds, machine, head = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4]
WAYS = (("MODULE", "holoray's Python module in Blender's process (the default where it loads)"),
        ("PROGRAM", "the holoray program, through EXR files"))
def base(way):
    return ["blender", "-b", f"{tmp}/scene.blend", "--addons", "holoray_blender", "-E", "HOLORAY",
            "--python-expr", f"import bpy; bpy.context.scene.holoray.backend = '{way}'"]
f12 = ["--python-expr", "import bpy, time\nfor k in range(2):\n    t = time.perf_counter()\n"
       "    bpy.ops.render.render()\n    print(f'F12 wall {time.perf_counter() - t:.4f}', flush=True)"]
one_off = ["-o", f"{tmp}/frame_####", "-F", "OPEN_EXR", "-f", "1"]
phases = re.compile(r"holoray: (\d+)x(\d+): export ([\d.]+) s, holoray ([\d.]+) s, result ([\d.]+) s \((\w+)\)")
walls = re.compile(r"F12 wall ([\d.]+)")
rows = {way: ([], [], []) for way, _ in WAYS}  # first F12, later F12, one-off: (export, holoray, result, wall)
def found_in(out, way, n):
    found = [tuple(float(m.group(k)) for k in (3, 4, 5)) for m in phases.finditer(out) if m.group(6) == way.lower()]
    if len(found) != n:
        sys.exit(f"run_blender_bench.sh: the engine printed no {way.lower()} phase times:\n" + out[-2000:])
    return found
for _ in range(rounds):
    for way, _ in WAYS:
        first, later, command = rows[way]
        out = subprocess.run(base(way) + f12, capture_output=True, text=True, check=True).stdout
        found, wall = found_in(out, way, 2), [float(m.group(1)) for m in walls.finditer(out)]
        first.append(found[0] + (wall[0],))
        later.append(found[1] + (wall[1],))
        t = time.perf_counter()
        out = subprocess.run(base(way) + one_off, capture_output=True, text=True, check=True).stdout
        wall = time.perf_counter() - t
        command.append(found_in(out, way, 1)[0] + (wall,))
med = lambda rows, k: statistics.median(r[k] for r in rows)
print("# The Blender add-on's own cost\n")
print(f"`bash bench/run_blender_bench.sh` (ROUNDS={rounds}) on {machine}, commit {head}.\n")
print("The add-on tests' scene (a textured cube on a plane, a sun and a point light) as a 64x64-lens x 16 px EIA "
      "(1024x1024), rendered each way three times per round, the ways alternated: the first and the second F12 "
      "(`bpy.ops.render.render()`) in one Blender session, and a one-off "
      "`blender -b scene.blend --addons holoray_blender -E HOLORAY -f 1` timed whole from outside (Blender's start "
      "included). The engine's own phases and the wall time, medians of the rounds, in seconds. The add-on's own cost "
      "is export + result; holoray's, the trace with its set-up (and, for the program, its start and its files).")
for way, title in WAYS:
    cols = (("first F12 in a session", rows[way][0]), ("later F12", rows[way][1]), ("one-off `-f 1` command", rows[way][2]))
    print(f"\n## {title}\n")
    print("| | " + " | ".join(name for name, _ in cols) + " |\n|---|---:|---:|---:|")
    for k, name in enumerate(("export (Blender's glTF exporter)", "holoray", "result (into the render result)",
                              "wall time of the render")):
        print(f"| {name} | " + " | ".join(f"{med(r, k):.3f}" for _, r in cols) + " |")
    for name, r in cols:
        s = [100 * (x[0] + x[2]) / x[3] for x in r]
        print(f"\n{name}: the add-on's own share of the wall time {statistics.median(s):.1f} % "
              f"(range {min(s):.1f} to {max(s):.1f} %)", end="")
    print()
PY
cat bench/blender_results.md
