#!/usr/bin/env bash
# Embree 3 against Embree 4 on the EIA's rays (issue 52): the same commit
# built on Debian 12 (Embree 3.13, GCC 12) and on Debian 13 (Embree 4.3,
# GCC 14), on one machine, in one run (writes bench/embree_results.md):
#   1. the do-nothing baselines: `true` here and in the Debian 13 root
#      (chroot), and `holoray --help` of each build;
#   2. the four SPD scenes as 2048x2048 EIAs (128x128 lenses x 16 px), both
#      builds and each release's own tachyon (`-res 2048 2048 -raydepth 5
#      -aasamples 0`), whole commands, alternated, ratios taken round by
#      round, medians;
#   3. the images of the two builds compared: the four SPD scenes, Tachyon's
#      Room and the textured CesiumMilkTruck (glTF), PSNR over float EXRs;
#   4. each build's cycle shares (perf record, by library);
#   5. the floor: Embree's CPU seconds in the EIA and in a 2048x2048 pinhole
#      view of the same scene, for each build.
# Runs on Debian 12 as root, with this checkout's build/ and a Debian 13 root
# holding its own build of the same commit in /root/holoray/build (made by
# `KEEP_ROOT=DIR bash scripts/debian13_check.sh`). Debian 13's commands run
# in that root through chroot, inside a private mount namespace.
# Needs ../shared, tachyon and perf (linux-perf) here.
# Usage: DEBIAN13_ROOT=DIR bash bench/run_embree_bench.sh   (ROUNDS=5)
set -euo pipefail
cd "$(dirname "$0")/.."
source bench/lib.sh
ROUNDS=${ROUNDS:-5}
root=${DEBIAN13_ROOT:-}
[ -n "$root" ] || { echo "run_embree_bench.sh: set DEBIAN13_ROOT (KEEP_ROOT=DIR bash scripts/debian13_check.sh makes one)" >&2; exit 1; }
root=$(cd "$root" && pwd)
[ -x "$root/root/holoray/build/holoray" ] || { echo "run_embree_bench.sh: no $root/root/holoray/build/holoray" >&2; exit 1; }
[ -x "$root/usr/bin/tachyon" ] || { echo "run_embree_bench.sh: no tachyon in $root" >&2; exit 1; }
[ -x build/holoray ] || { echo "run_embree_bench.sh: no build/holoray (bash scripts/setup.sh)" >&2; exit 1; }
for tool in tachyon perf python3 unshare chroot; do
  command -v "$tool" >/dev/null || { echo "run_embree_bench.sh: '$tool' is missing" >&2; exit 1; }
done
shared=$(cd ../shared && pwd)
mkdir -p "$tmp/in13"

cat > "$tmp/bench.py" <<'PY'
import os, re, statistics, subprocess, sys, time
root, shared, tmp, rounds, machine, head = sys.argv[1:7]
rounds = int(rounds)
scenes = ("teapot_s6", "gears_s4", "balls_s4", "tree_s11")
eia = ["--lenses", "128x128", "--pixels-per-lens", "16"]
pinhole = ["--camera", "pinhole", "--resolution", "2048x2048"]
# Each build: how to run its holoray and its tachyon, where it reads the
# scenes and where it writes (the same folder: $tmp/in13 is the root's /tmp).
builds = {
    "Debian 12, Embree 3": dict(run=[], holoray="build/holoray", shared=shared, out=f"{tmp}/in13"),
    "Debian 13, Embree 4": dict(run=["chroot", root], holoray="/root/holoray/build/holoray", shared="/root/shared",
                                out="/tmp"),
}
names = list(builds)

def holoray(b, *args):
    return builds[b]["run"] + [builds[b]["holoray"], *args]
def tachyon(b, f):
    return builds[b]["run"] + ["tachyon", f, "-res", "2048", "2048", "-raydepth", "5", "-aasamples", "0",
                               "-o", builds[b]["out"] + "/t.tga"]
def scene(b, s):
    return f"{builds[b]['shared']}/scenes/nff/{s}.nff"

def wall(cmd):
    t0 = time.perf_counter()
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    t = time.perf_counter() - t0
    if r.returncode != 0:
        sys.exit(f"failed: {' '.join(cmd)}\n{r.stdout}")
    return t, r.stdout

def alternated(cmds, n, outputs):
    """Each command's wall times, run alternated n times, round r starting
    at command r mod len(cmds); their printed outputs into `outputs`."""
    times = [[] for _ in cmds]
    for r in range(n):
        for j in range(len(cmds)):
            k = (r + j) % len(cmds)
            t, out = wall(cmds[k])
            times[k].append(t)
            outputs.setdefault(k, []).append(out)
    return times
def ratio(num, den):
    r = sorted(a / b for a, b in zip(num, den))
    return f"{statistics.median(r):.2f}x ({r[0]:.2f}-{r[-1]:.2f})"

print(f"# Embree 3 (Debian 12) against Embree 4 (Debian 13): holoray {head}\n")
print(f"`DEBIAN13_ROOT=DIR bash bench/run_embree_bench.sh` on {machine}; every figure from this one run. "
      "Debian 12's build: Embree 3.13.5, GCC 12; Debian 13's: Embree 4.3.3, GCC 14, run in a Debian 13 root "
      "through chroot.\n")

# 1. do-nothing baselines
out = {}
cmds = [["true"], ["chroot", root, "true"], holoray(names[0], "--help"), holoray(names[1], "--help")]
t = [statistics.median(x) for x in alternated(cmds, 10, out)]
print("## Do-nothing baselines (median of 10 runs, ms)\n")
print("| command | ms |\n|---|---:|")
for label, v in zip(["`true`", "`chroot ROOT true` (what running in the root adds)", f"`holoray --help`, {names[0]}",
                     f"`holoray --help`, {names[1]}"], t):
    print(f"| {label} | {v * 1e3:.1f} |")
print()

# 2. the EIAs against each other and each release's tachyon
print(f"## 2048x2048 EIAs (whole commands, 2 threads, alternated, {rounds} rounds)\n")
print("Seconds are medians; each ratio is the median of the rounds' own ratios, with their range.\n")
print("| scene | holoray s, Embree 3 | holoray s, Embree 4 | Embree 4 build's speed-up | tachyon s, Debian 12 | "
      "tachyon s, Debian 13 | Tachyon / holoray, Debian 12 | Tachyon / holoray, Debian 13 | trace s, Embree 3 | "
      "trace s, Embree 4 | Mrays/s, Embree 3 | Mrays/s, Embree 4 |")
print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
for s in scenes:
    outs = {}
    cmds = [holoray(b, "render", scene(b, s), *eia, "-o", builds[b]["out"] + "/e.png") for b in names] + \
           [tachyon(b, scene(b, s)) for b in names]
    h3, h4, t12, t13 = alternated(cmds, rounds, outs)
    med = lambda x: statistics.median(x)
    printed = lambda k, pat: statistics.median(float(re.search(pat, o).group(1)) for o in outs[k])
    trace, mrays = r"trace\s+([\d.]+) s", r"([\d.]+) Mrays/s"
    print(f"| {s} | {med(h3):.3f} | {med(h4):.3f} | {ratio(h3, h4)} | {med(t12):.3f} | {med(t13):.3f} | "
          f"{ratio(t12, h3)} | {ratio(t13, h4)} | {printed(0, trace):.3f} | {printed(1, trace):.3f} | "
          f"{printed(0, mrays):.1f} | {printed(1, mrays):.1f} |")
print()

# 3. the same images?
print("## Images of the two builds (PSNR dB over float EXR; inf: identical)\n")
print("| scene | PSNR |\n|---|---:|")
others = [("room (Tachyon)", "scenes/tachyon/room.dat", [])]
truck = "glTF/CesiumMilkTruck/CesiumMilkTruck.gltf"
for label, rel, extra in [(s, f"scenes/nff/{s}.nff", eia) for s in scenes] + others + [("CesiumMilkTruck (glTF, textured)", None, eia)]:
    paths = []
    for k, b in enumerate(names):
        f = f"{builds[b]['shared']}/{rel}" if rel else f"/usr/share/assimp/models/{truck}"  # assimp-testmodels
        o = f"{builds[b]['out']}/c{k}.exr"
        wall(holoray(b, "render", f, *extra, "-o", o, "-q"))
        paths.append(f"{tmp}/in13/c{k}.exr")
    cmp = wall(holoray(names[0], "compare", *paths))[1]
    print(f"| {label} | {cmp.strip().splitlines()[-1].split()[-1]} |")
print()

# 4. cycle shares, and 5. the floor
PERF_HZ = 2000
def shares(b, f, view, seconds=False):
    data = f"{tmp}/perf.data"
    subprocess.run(["perf", "record", "-q", "-F", str(PERF_HZ), "-o", data] +
                   holoray(b, "render", f, *view, "-o", builds[b]["out"] + "/p.png", "-q"),
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=True)
    rep = subprocess.run(["perf", "report", "-i", data, "--no-children", "--sort", "dso", "-n", "--stdio"],
                         stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True).stdout
    got = dict.fromkeys(("embree", "holoray", "tbb", "loader", "kernel", "libc", "zlib", "other"), 0.0)
    for line in rep.splitlines():
        m = re.match(r"\s+([\d.]+)%\s+(\d+)\s+(\S+)", line)
        if not m:
            continue
        v, dso = (int(m.group(2)) / PERF_HZ if seconds else float(m.group(1))), os.path.basename(m.group(3))
        key = ("embree" if "embree" in dso else "holoray" if dso == "holoray" else "tbb" if "libtbb" in dso
               else "loader" if dso.startswith("ld-linux") else "kernel" if "kernel" in dso
               else "libc" if dso.startswith("libc.") else "zlib" if dso.startswith("libz") else "other")
        got[key] += v
    return got
cols = ("embree", "holoray", "tbb", "loader", "kernel", "libc", "zlib", "other")
print("## Cycle shares of the whole `holoray render` of each 2048x2048 EIA (perf record, % of samples)\n")
print("| scene | build | Embree | holoray | oneTBB | loader | kernel | libc | zlib | other |")
print("|---|---|" + "---:|" * len(cols))
for s in scenes:
    for b in names:
        g = shares(b, scene(b, s), eia)
        print(f"| {s} | {b} | " + " | ".join(f"{g[k]:.1f}" for k in cols) + " |")
print()
print("## The floor: Embree's CPU seconds on the EIA's rays and on a pinhole view's (perf record, one run each)\n")
print("The pinhole view (2048x2048) traces about as many rays as the EIA, but neighbouring pixels' rays are "
      "coherent there: EIA / pinhole is what the EIA's incoherence costs Embree (issue 43's floor).\n")
print("| scene | build | Embree CPU s, EIA | Embree CPU s, pinhole | EIA / pinhole | holoray CPU s, EIA | "
      "Embree 3 / Embree 4 on the EIA |")
print("|---|---|---:|---:|---:|---:|---:|")
for s in scenes:
    got = {b: (shares(b, scene(b, s), eia, True), shares(b, scene(b, s), pinhole, True)) for b in names}
    e3 = got[names[0]][0]["embree"]
    for b in names:
        e, p = got[b]
        print(f"| {s} | {b} | {e['embree']:.2f} | {p['embree']:.2f} | {e['embree'] / p['embree']:.2f}x | "
              f"{e['holoray']:.2f} | {e3 / e['embree']:.2f}x |")
PY
# In a private mount namespace, the Debian 13 root with the kernel's file
# systems, the scenes, and its /tmp on $tmp/in13 (both builds write there).
inside='
root=$1 shared=$2 tmp=$3
mount -t proc proc "$root/proc"
mount --rbind /dev "$root/dev"
mount --rbind /sys "$root/sys"
mount --bind "$tmp/in13" "$root/tmp"
mkdir -p "$root/root/shared"
mount --bind "$shared" "$root/root/shared"
python3 "$tmp/bench.py" "$@"
'
unshare -m --propagation private bash -euo pipefail -c "$inside" bench "$root" "$shared" "$tmp" "$ROUNDS" "$(machine)" \
  "$(git rev-parse --short HEAD)" < /dev/null > "$tmp/embree_results.md"
cp "$tmp/embree_results.md" bench/embree_results.md
cat bench/embree_results.md
