#!/usr/bin/env bash
# Mesh scenes, as the glTF and OBJ files of content makers reach holoray,
# against the commit before a change (writes bench/mesh_results.md):
#   1. whole commands, a 2048x2048 EIA (128x128 lenses x 16 px) of each
#      scene, this build and the baseline alternated (at least 5 rounds),
#      ratios taken round by round, medians; the preprocess (parse, textures'
#      MIP levels, BVH) and trace seconds each build prints, medians;
#   2. the images of the two builds compared: PSNR over float EXRs with the
#      albedo, depth and normal AOVs (inf: identical);
#   3. the cycle shares of this build's render (perf record: Embree,
#      holoray, libm, zlib, the kernel, the rest).
# Scenes: Debian's assimp-testmodels (CesiumMilkTruck: textured; BoxTextured)
# and the Blender tests' lit glTF (point, spot and sun lights, PBR metals),
# and examples/box_on_floor.obj.
# The baseline is built from BASE (a commit; default: the commit before the
# mesh steps of issue 43) into a scratch folder, or taken from BASE_BIN.
# Needs perf (linux-perf).
# Usage: bash bench/run_mesh_bench.sh   (ROUNDS=5, BASE=<commit>, BASE_BIN=<binary>)
set -euo pipefail
cd "$(dirname "$0")/.."
source bench/lib.sh
command -v perf >/dev/null || { echo "run_mesh_bench.sh: 'perf' is missing" >&2; exit 1; }
base_commit=${BASE:-2288f75}
build_baseline "$base_commit"
python3 - "$bin" "$BASE_BIN" "$base_commit" "$tmp" "$ROUNDS" "$(machine)" "$(git rev-parse --short HEAD)" \
  > "$tmp/mesh_results.md" <<'PY'
import os, re, statistics, subprocess, sys, time
new, base, base_commit, tmp, rounds, machine, head = sys.argv[1:8]
rounds = max(int(rounds), 5)
models = "/usr/share/assimp/models"
scenes = [("CesiumMilkTruck (glTF, textured)", f"{models}/glTF/CesiumMilkTruck/CesiumMilkTruck.gltf"),
          ("BoxTextured (glTF, textured)", f"{models}/glTF2/BoxTextured-glTF/BoxTextured.gltf"),
          ("lit_spheres (glTF: point, spot, sun; metals)", "tests/data/blender/lit_spheres.gltf"),
          ("box_on_floor (OBJ + MTL)", "examples/box_on_floor.obj")]
eia = ["--lenses", "128x128", "--pixels-per-lens", "16"]

def run(cmd):
    t0 = time.perf_counter()
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    t = time.perf_counter() - t0
    if r.returncode != 0:
        sys.exit(f"failed: {' '.join(cmd)}\n{r.stdout}")
    return t, r.stdout

def printed(outs, pattern):
    return statistics.median(float(re.search(pattern, o).group(1)) for o in outs)

print(f"# Mesh scenes: holoray {head} against {base_commit}\n")
print(f"`bash bench/run_mesh_bench.sh` on {machine}; every figure from this one run.\n")
nothing = statistics.median(run([new, "--help"])[0] for _ in range(5))
print(f"Do-nothing baseline: `holoray --help` {nothing * 1e3:.1f} ms (median of 5).\n")
print(f"## 2048x2048 EIAs, whole commands (2 threads, alternated, {rounds} rounds)\n")
print("Seconds are medians; the ratio is the median of the rounds' own ratios (this build's time over the "
      "baseline's), with their range in brackets.\n")
print("| scene | this build s | baseline s | this / baseline | preprocess s, this / baseline | trace s, this / baseline |")
print("|---|---:|---:|---:|---:|---:|")
for name, f in scenes:
    ts = {0: [], 1: []}
    outs = {0: [], 1: []}
    for _ in range(rounds):
        for k, b in enumerate((new, base)):
            t, o = run([b, "render", f] + eia + ["-o", f"{tmp}/{k}.png"])
            ts[k].append(t), outs[k].append(o)
    r = sorted(a / b for a, b in zip(ts[0], ts[1]))
    pre = [printed(outs[k], r"preprocess\s+([\d.]+) s") for k in (0, 1)]
    tr = [printed(outs[k], r"trace\s+([\d.]+) s") for k in (0, 1)]
    print(f"| {name} | {statistics.median(ts[0]):.3f} | {statistics.median(ts[1]):.3f} | "
          f"{statistics.median(r):.3f}x ({r[0]:.3f}-{r[-1]:.3f}) | {pre[0]:.3f} / {pre[1]:.3f} | {tr[0]:.3f} / {tr[1]:.3f} |")
print()

print("## Images of this build against the baseline (PSNR dB over float EXR with AOVs; inf: identical)\n")
print("| scene | PSNR |\n|---|---:|")
for name, f in scenes:
    for k, b in enumerate((new, base)):
        run([b, "render", f] + eia + ["--aov", "albedo,depth,normal", "-o", f"{tmp}/{k}.exr", "-q"])
    cmp = run([new, "compare", f"{tmp}/1.exr", f"{tmp}/0.exr"])[1]
    print(f"| {name} | {cmp.strip().splitlines()[-1].split()[-1]} |")
print()

print("## Cycle shares of this build's render (perf record, % of samples)\n")
print("| scene | Embree | holoray | libm | zlib | kernel | other |\n|---|---:|---:|---:|---:|---:|---:|")
for name, f in scenes:
    data = f"{tmp}/perf.data"
    subprocess.run(["perf", "record", "-q", "-o", data, new, "render", f] + eia + ["-o", f"{tmp}/p.png", "-q"],
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=True)
    rep = subprocess.run(["perf", "report", "-i", data, "--no-children", "--sort", "dso", "--stdio"],
                         stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True).stdout
    got = {"embree": 0.0, "holoray": 0.0, "libm": 0.0, "zlib": 0.0, "kernel": 0.0, "other": 0.0}
    for line in rep.splitlines():
        m = re.match(r"\s*([\d.]+)%\s+(\S+)", line)
        if not m:
            continue
        pct, dso = float(m.group(1)), m.group(2)
        key = ("embree" if "embree" in dso else "holoray" if dso == os.path.basename(new) or "libholoray" in dso
               else "libm" if dso.startswith("libm.") or "libmvec" in dso else "zlib" if dso.startswith("libz")
               else "kernel" if "kernel" in dso else "other")
        got[key] += pct
    print(f"| {name} | " + " | ".join(f"{got[k]:.1f}" for k in got) + " |")
PY
mv "$tmp/mesh_results.md" bench/mesh_results.md
echo "wrote bench/mesh_results.md"
