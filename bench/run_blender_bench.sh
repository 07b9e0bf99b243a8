#!/usr/bin/env bash
# The Blender add-on's own cost: what exporting the scene (Blender's glTF
# exporter) and loading the EXRs back into the render result add to
# holoray's own run, on the add-on tests' scene (tests/blender/scene.py) as a
# 64x64-lens x 16 px EIA (1024x1024), rendered as a user renders it:
# `blender -b scene.blend --addons holoray_blender -E HOLORAY -s 1 -e 2 -a`:
# two frames in one Blender, the first as a one-off `-f 1` render pays it
# (Python modules imported on first use), the second as a later F12 in an
# open session does. The engine prints its phases (export, holoray, result).
# Writes bench/blender_results.md.
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
cmd = ["blender", "-b", f"{tmp}/scene.blend", "--addons", "holoray_blender", "-E", "HOLORAY",
       "-o", f"{tmp}/frame_####", "-F", "OPEN_EXR", "-s", "1", "-e", "2", "-a"]
phases = re.compile(r"holoray: (\d+)x(\d+): export ([\d.]+) s, holoray ([\d.]+) s, result ([\d.]+) s")
first, later = [], []
for _ in range(rounds):
    out = subprocess.run(cmd, capture_output=True, text=True, check=True).stdout
    found = [tuple(float(m.group(k)) for k in (3, 4, 5)) for m in phases.finditer(out)]
    if len(found) != 2:
        sys.exit("run_blender_bench.sh: the engine printed no phase times:\n" + out[-2000:])
    first.append(found[0])
    later.append(found[1])
print("# The Blender add-on's own cost\n")
print(f"`bash bench/run_blender_bench.sh` (ROUNDS={rounds}) on {machine}, commit {head}.\n")
print("The add-on tests' scene (a textured cube on a plane, a sun and a point light) as a 64x64-lens x 16 px EIA "
      "(1024x1024), two frames rendered in one `blender -b scene.blend --addons holoray_blender -E HOLORAY -s 1 -e 2 -a`: "
      "the first as a one-off `-f 1` render, the second as a later F12 in an open session. The engine's own phase "
      "times, medians of the rounds:\n")
print("| phase | first render, s | later renders, s |\n|---|---:|---:|")
med = lambda rows, k: statistics.median(r[k] for r in rows)
for k, name in enumerate(("export (Blender's glTF exporter)", "holoray (`holoray render`, start to exit)",
                          "result (the EXR into the render result)")):
    print(f"| {name} | {med(first, k):.3f} | {med(later, k):.3f} |")
share = lambda rows: [100 * (r[0] + r[2]) / sum(r) for r in rows]
for name, rows in (("first render", first), ("later renders", later)):
    s = share(rows)
    print(f"\nThe add-on's own share, (export + result) / (export + holoray + result), {name}: median "
          f"{statistics.median(s):.1f} % (range {min(s):.1f} to {max(s):.1f} %).")
PY
cat bench/blender_results.md
