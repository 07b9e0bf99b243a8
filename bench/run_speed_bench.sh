#!/usr/bin/env bash
# Where holoray's time goes, against the commit before a change and against
# Tachyon, all in one run (writes bench/speed_results.md):
#   1. start-up: `holoray --help` and a 4x4-lens render against `true`;
#   2. the four SPD scenes as 2048x2048 EIAs (128x128 lenses x 16 px) against
#      `tachyon SCENE.nff -res 2048 2048 -raydepth 5 -aasamples 0`, both
#      reading the same NFF file, whole commands, runs alternated (at least
#      5 rounds), ratios taken round by round, medians;
#   3. the images of the two holoray builds compared (four SPD scenes and
#      Tachyon's Room), PSNR over float EXRs (inf: identical);
#   4. the cycle shares of each SPD render (perf record: Embree, holoray,
#      the dynamic loader, the kernel, libc, zlib, the rest);
#   5. the packet styles by array: trace seconds of `--style packet` and
#      `--style subaperture` at three lens pitches, and what `auto` picks;
#   6. the floor under each Tachyon ratio: Embree's own CPU seconds in the
#      EIA and in a 2048x2048 pinhole view of the same scene (the same rays,
#      coherent), and the whole command's time if holoray's own code took
#      none: what the targets of section 2 would leave that code;
#   7. peak memory (the largest resident set, from the kernel's rusage of
#      each command) of the 2048x2048 EIAs in both builds, and an 8192x8192
#      EIA of teapot_s6 rendered by this build.
# The baseline is built from BASE (a commit; default: the commit before
# the image-library change) into a scratch folder, or taken from BASE_BIN.
# Needs ../shared, tachyon and perf (linux-perf).
# Usage: bash bench/run_speed_bench.sh   (ROUNDS=3, BASE=<commit>, BASE_BIN=<binary>)
set -euo pipefail
cd "$(dirname "$0")/.."
source bench/lib.sh
shared=${HOLORAY_SHARED:-../shared}
[[ -d $shared/scenes/nff ]] || { echo "run_speed_bench.sh: needs $shared/scenes" >&2; exit 1; }
for tool in tachyon perf python3; do
  command -v "$tool" >/dev/null || { echo "run_speed_bench.sh: '$tool' is missing" >&2; exit 1; }
done
base_commit=${BASE:-e5b5ca3}
build_baseline "$base_commit"
python3 - "$bin" "$BASE_BIN" "$base_commit" "$shared" "$tmp" "$ROUNDS" "$(machine)" "$(git rev-parse --short HEAD)" \
  > "$tmp/speed_results.md" <<'PY'
import os, re, statistics, subprocess, sys, time
new, base, base_commit, shared, tmp, rounds, machine, head = sys.argv[1:9]
rounds = int(rounds)
nff = f"{shared}/scenes/nff"
scenes = ("teapot_s6", "gears_s4", "balls_s4", "tree_s11")
eia = ["--lenses", "128x128", "--pixels-per-lens", "16"]

def wall(cmd, cwd=None):
    t0 = time.perf_counter()
    r = subprocess.run(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    t = time.perf_counter() - t0
    if r.returncode != 0:
        sys.exit(f"failed: {' '.join(cmd)}\n{r.stdout}")
    return t, r.stdout

def alternated(cmds, n, outputs=None):
    """Runs the commands alternated n times; each one's wall times, round by
    round (and, into `outputs` when given, each one's printed outputs).
    Round r starts at command r mod len(cmds): in a fixed order holoray
    always ran right after Tachyon's 18 s on tree_s11, and measured 0.94x
    its baseline there against 0.98x in pairs without Tachyon between."""
    times = [[] for _ in cmds]
    for r in range(n):
        for j in range(len(cmds)):
            k = (r + j) % len(cmds)
            c = cmds[k]
            t, out = wall(c)
            times[k].append(t)
            if outputs is not None:
                outputs.setdefault(k, []).append(out)
    return times
def medians(cmds, n):
    """The median wall time of each command, run alternated n times."""
    return [statistics.median(t) for t in alternated(cmds, n)]
def ratio(num, den):
    """num/den round by round (each round's runs sat side by side): the
    median, and the spread as min-max; a ratio of medians would mix rounds
    taken in different moods of the machine."""
    r = sorted(a / b for a, b in zip(num, den))
    return f"{statistics.median(r):.2f}x ({r[0]:.2f}-{r[-1]:.2f})"

print(f"# Speed: holoray {head} against {base_commit} and Tachyon\n")
print(f"`BASE={base_commit} ROUNDS={rounds} bash bench/run_speed_bench.sh` on {machine}; every figure from this one run.\n")

# 1. start-up
small = ["render", "examples/primitives.nff", "--lenses", "4x4", "-o", f"{tmp}/small.png", "-q"]
t_true, t_help, t_bhelp, t_small, t_bsmall = medians(
    [["true"], [new, "--help"], [base, "--help"], [new] + small, [base] + small], 10)
print("## Start-up (median of 10 runs, ms)\n")
print("| command | this build | baseline | baseline / this |\n|---|---:|---:|---:|")
print(f"| `holoray --help` | {t_help*1e3:.1f} | {t_bhelp*1e3:.1f} | {t_bhelp/t_help:.1f}x |")
print(f"| `holoray render examples/primitives.nff --lenses 4x4` | {t_small*1e3:.1f} | {t_bsmall*1e3:.1f} | {t_bsmall/t_small:.1f}x |")
print(f"| `true` (do-nothing baseline) | {t_true*1e3:.1f} | | |\n")

# 2. against Tachyon
tachyon_rounds = max(rounds, 5)
against_tachyon = {}  # scene: (holoray s, tachyon s, trace s), medians over section 2's runs
print(f"## 2048x2048 against Tachyon (whole commands, 2 threads, alternated, {tachyon_rounds} rounds)\n")
print("Seconds are medians; each ratio is the median of the rounds' own ratios, "
      "with their range in brackets.\n")
print("| scene | holoray s | baseline holoray s | tachyon s | Tachyon / holoray | Tachyon / baseline | this / baseline speed-up | trace s | Mrays/s | baseline Mrays/s |")
print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
for s in scenes:
    f = f"{nff}/{s}.nff"
    outs = {}
    hs, bs, ts = alternated([[new, "render", f] + eia + ["-o", f"{tmp}/n.png"],
                             [base, "render", f] + eia + ["-o", f"{tmp}/b.png"],
                             ["tachyon", f, "-res", "2048", "2048", "-raydepth", "5", "-aasamples", "0", "-o", f"{tmp}/t.tga"]],
                            tachyon_rounds, outs)
    h, b, t = (statistics.median(x) for x in (hs, bs, ts))
    # Trace seconds and Mrays/s: medians over the same runs as the wall times.
    def printed(k, pattern):
        return statistics.median(float(re.search(pattern, o).group(1)) for o in outs[k])
    tr = printed(0, r"trace\s+([\d.]+) s")
    mr, bmr = printed(0, r"([\d.]+) Mrays/s"), printed(1, r"([\d.]+) Mrays/s")
    print(f"| {s} | {h:.3f} | {b:.3f} | {t:.3f} | {ratio(ts, hs)} | {ratio(ts, bs)} | {ratio(bs, hs)} | {tr:.3f} | {mr:.1f} | {bmr:.1f} |")
    against_tachyon[s] = (h, t, tr)
print()

# 3. same images
print("## Images of this build against the baseline (PSNR dB over float EXR; inf: identical)\n")
print("| scene | PSNR |\n|---|---:|")
room = f"{shared}/scenes/tachyon/room.dat"
for s, f, extra in [(s, f"{nff}/{s}.nff", eia) for s in scenes] + [("room (Tachyon)", room, [])]:
    wall([new, "render", f] + extra + ["-o", f"{tmp}/n.exr", "-q"])
    wall([base, "render", f] + extra + ["-o", f"{tmp}/b.exr", "-q"])
    cmp = wall([new, "compare", f"{tmp}/b.exr", f"{tmp}/n.exr"])[1]
    print(f"| {s} | {cmp.strip().splitlines()[-1].split()[-1]} |")
print()

# 4. cycle shares
PERF_HZ = 2000  # perf's samples per second of one thread's CPU time

# The executables' own names (a BASE_BIN may be called anything) and the
# library the front ends link (libholoray.so since issue 54): their samples
# are holoray's.
own = {os.path.basename(new), os.path.basename(base)}
def is_own(dso):
    return dso in own or dso.startswith("libholoray.so")
def shares(binary, f, view=None, seconds=False):
    """The whole command's cycles by component: % of perf's samples, or
    CPU seconds (`seconds`). `view`: the camera options (default: the EIA)."""
    data = f"{tmp}/perf.data"
    subprocess.run(["perf", "record", "-q", "-F", str(PERF_HZ), "-o", data, binary, "render", f] + (view or eia) +
                   ["-o", f"{tmp}/p.png", "-q"], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=True)
    rep = subprocess.run(["perf", "report", "-i", data, "--no-children", "--sort", "dso", "-n", "--stdio"],
                         stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True).stdout
    got = {"embree": 0.0, "holoray": 0.0, "loader": 0.0, "kernel": 0.0, "libc": 0.0, "zlib": 0.0, "other": 0.0}
    for line in rep.splitlines():
        m = re.match(r"\s+([\d.]+)%\s+(\d+)\s+(\S+)", line)
        if not m:
            continue
        pct, dso = (int(m.group(2)) / PERF_HZ if seconds else float(m.group(1))), m.group(3)
        key = ("embree" if "embree" in dso else "holoray" if is_own(dso) else "loader" if dso.startswith("ld-linux")
               else "kernel" if "kernel" in dso else "libc" if dso.startswith("libc.") else "zlib" if dso.startswith("libz") else "other")
        got[key] += pct
    return got
print("## Cycle shares of the whole `holoray render` (perf record, % of samples)\n")
print("| scene | build | Embree | holoray | loader | kernel | libc | zlib | other |\n|---|---|---:|---:|---:|---:|---:|---:|---:|")
for s in scenes:
    for name, binary in (("this", new), ("baseline", base)):
        g = shares(binary, f"{nff}/{s}.nff")
        print(f"| {s} | {name} | " + " | ".join(f"{g[k]:.1f}" for k in ("embree", "holoray", "loader", "kernel", "libc", "zlib", "other")) + " |")
print()

# 5. packet styles by array
print(f"## Packet styles by lens pitch (trace s, median of {rounds}; 2048x2048 EIAs, lens field of view 20 deg)\n")
print("| scene | lenses x px | packet | subaperture | subaperture speed-up | auto picks |\n|---|---|---:|---:|---:|---|")
def trace_s(cmd):
    return float(re.search(r"trace\s+([\d.]+) s", wall(cmd)[1]).group(1))
for s in scenes:
    for lenses, p in (("128x128", "16"), ("256x256", "8"), ("512x512", "4")):
        cmd = [new, "render", f"{nff}/{s}.nff", "--lenses", lenses, "--pixels-per-lens", p, "-o", f"{tmp}/s.png"]
        runs = {st: [] for st in ("packet", "subaperture")}
        for _ in range(rounds):
            for st in runs:
                runs[st].append(trace_s(cmd + ["--style", st]))
        pk, sa = (statistics.median(runs[st]) for st in ("packet", "subaperture"))
        picked = re.search(r"(\w+) style", wall(cmd)[1]).group(1)
        print(f"| {s} | {lenses} x {p} | {pk:.3f} | {sa:.3f} | {pk/sa:.2f}x | {picked} |")
print()

# 6. the floor under the Tachyon ratios
targets = {"teapot_s6": 3.0, "gears_s4": 1.2}  # issue 43's
pinhole = ["--camera", "pinhole", "--resolution", "2048x2048"]
def total_rays(view, f):
    return int(re.search(r"total (\d+)", wall([new, "render", f] + view + ["-o", f"{tmp}/r.png"])[1]).group(1))
print("## The floor under the Tachyon ratios (perf record, CPU seconds of one run each)\n")
print("Embree's CPU seconds in the EIA and in a 2048x2048 pinhole view of the same scene "
      "(about the same rays, but neighbouring pixels' rays are coherent); the floor is the "
      "whole command with holoray's own code taking no time: Embree's seconds spread over "
      "2 cores, plus the phases around the trace (start-up, parse, BVH build, PNG), "
      "from section 2's medians. Where there is a target, the last column is the wall time "
      "it leaves holoray's own code, against what that code takes today (its CPU seconds "
      "over 2 cores).\n")
print("| scene | rays EIA / pinhole (M) | Embree CPU s EIA | Embree CPU s pinhole | holoray CPU s EIA | "
      "floor s | Tachyon s | Tachyon / floor | target | own code: allowed s / today s |")
print("|---|---|---:|---:|---:|---:|---:|---:|---:|---|")
for s in scenes:
    f = f"{nff}/{s}.nff"
    h, t, tr = against_tachyon[s]
    e, p = shares(new, f, seconds=True), shares(new, f, pinhole, seconds=True)
    floor = e["embree"] / 2 + (h - tr)
    target = targets.get(s)
    allowed = (f"{t / target - floor:.3f} / {e['holoray'] / 2:.3f}" if target else "")
    print(f"| {s} | {total_rays(eia, f) / 1e6:.1f} / {total_rays(pinhole, f) / 1e6:.1f} | {e['embree']:.2f} | "
          f"{p['embree']:.2f} | {e['holoray']:.2f} | {floor:.3f} | {t:.3f} | {t / floor:.2f}x | "
          f"{f'{target:g}x' if target else ''} | {allowed} |")
print()

# 7. peak memory
def peak(cmd):
    """The command's largest resident set in MiB (the kernel's own count,
    ru_maxrss of the child) and its wall seconds."""
    t0 = time.perf_counter()
    p = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    _, status, ru = os.wait4(p.pid, 0)
    if status != 0:
        sys.exit(f"failed: {' '.join(cmd)}")
    return ru.ru_maxrss / 1024, time.perf_counter() - t0
print("## Peak memory (largest resident set, MiB; one run each)\n")
print("| scene | EIA | this build | baseline | this / baseline |\n|---|---|---:|---:|---:|")
for s in scenes:
    f = f"{nff}/{s}.nff"
    n, _ = peak([new, "render", f] + eia + ["-o", f"{tmp}/n.png", "-q"])
    b, _ = peak([base, "render", f] + eia + ["-o", f"{tmp}/b.png", "-q"])
    print(f"| {s} | 2048x2048 | {n:.1f} | {b:.1f} | {n / b:.3f}x |")
n, secs = peak([new, "render", f"{nff}/teapot_s6.nff", "--lenses", "512x512", "--pixels-per-lens", "16",
                "-o", f"{tmp}/big.png", "-q"])
os.remove(f"{tmp}/big.png")
print(f"| teapot_s6 | 8192x8192 | {n:.1f} ({secs:.1f} s) | | |")
PY
cp "$tmp/speed_results.md" bench/speed_results.md
cat bench/speed_results.md
