#!/usr/bin/env bash
# The Python module against the CLI on one EIA: does rendering from Python
# cost anything? Each round renders the same 2048x2048 EIA (256x256 lenses x
# 8 px, the scene's viewpoint, all cores) twice, alternating which goes first:
#   CLI:    `build/holoray render SCENE --lenses 256x256 --pixels-per-lens 8 -o x.png`,
#           the `trace` seconds it prints;
#   Python: `holoray.render(holoray.load_scene(SCENE),
#           holoray.LensArray(lenses=(256, 256), pixels_per_lens=8))` in a fresh
#           /usr/bin/python3 (cold as the CLI is), result.stats['seconds']['trace'].
# Reports both medians, the ratio of the medians and the median and range of
# the rounds' own ratios. Checks, every round, that result.colour is the
# renderer's buffer and not a copy (flags['OWNDATA'] False, base not None),
# and once that both images are the same (PSNR of float EXRs: inf).
# Writes bench/python_results.md (also when a check failed; then exits 1).
# Usage: bash bench/run_python_bench.sh   (ROUNDS=9, SCENE=examples/primitives.nff,
#        LENSES=256, PIXELS_PER_LENS=8, PYTHON=/usr/bin/python3)
set -euo pipefail
cd "$(dirname "$0")/.."
ROUNDS=${ROUNDS:-9}
source bench/lib.sh
scene=${SCENE:-examples/primitives.nff}
lenses=${LENSES:-256}
ppl=${PIXELS_PER_LENS:-8}
py=${PYTHON:-/usr/bin/python3}   # Debian's: the module is built against it
export PYTHONPATH="$PWD/build/python${PYTHONPATH:+:$PYTHONPATH}"
[ -x "$bin" ] || { echo "run_python_bench.sh: $bin is missing: run scripts/setup.sh first" >&2; exit 1; }
[ -f "$scene" ] || { echo "run_python_bench.sh: no scene $scene" >&2; exit 1; }
"$py" -c 'import holoray' || { echo "run_python_bench.sh: $py cannot import holoray from build/python" >&2; exit 1; }
status=0
"$py" - "$bin" "$py" "$scene" "$lenses" "$ppl" "$tmp" "$ROUNDS" "$(machine)" "$(git describe --always --dirty)" \
  > "$tmp/python_results.md" <<'PY' || status=$?
import json, re, statistics, subprocess, sys, time
cli, py, scene, lenses, ppl, tmp, rounds, machine, head = sys.argv[1:10]
lenses, ppl, rounds = int(lenses), int(ppl), int(rounds)
size = lenses * ppl
cli_cmd = [cli, "render", scene, "--lenses", f"{lenses}x{lenses}", "--pixels-per-lens", str(ppl), "-o", f"{tmp}/x.png"]
# One Python render in a fresh interpreter; prints what the round needs as JSON.
child = """
import json, sys, holoray
scene, lenses, ppl, exr = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), sys.argv[4]
result = holoray.render(holoray.load_scene(scene), holoray.LensArray(lenses=(lenses, lenses), pixels_per_lens=ppl))
c = result.colour
if exr:
    holoray.write_image(exr, c)
print(json.dumps({"trace": result.stats["seconds"]["trace"], "shape": list(c.shape), "dtype": str(c.dtype),
                  "owndata": bool(c.flags["OWNDATA"]), "base": c.base is not None}))
"""

def run(cmd):
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if r.returncode != 0:
        sys.exit(f"failed: {' '.join(cmd)}\n{r.stdout}")
    return r.stdout

def cli_round():
    out = run(cli_cmd)
    return float(re.search(r"^trace\s+([\d.]+) s", out, re.M).group(1)), out

def py_round(exr=""):
    return json.loads(run([py, "-c", child, scene, str(lenses), str(ppl), exr]).strip().splitlines()[-1])

rows, seen = [], []
for r in range(rounds):
    first = "CLI" if r % 2 == 0 else "Python"
    if first == "CLI":
        (c, out), p = cli_round(), py_round()
    else:
        p = py_round(); c, out = cli_round()
    rows.append((first, c, p["trace"]))
    seen.append(p)
threads = re.search(r"(\d+) threads", out).group(1)
copies = [k + 1 for k, p in enumerate(seen) if p["owndata"] or not p["base"]]
shape_ok = all(p["shape"] == [size, size, 3] and p["dtype"] == "float32" for p in seen)
# The same image both ways: the CLI's EXR against the Python render's.
run(cli_cmd[:-1] + [f"{tmp}/cli.exr", "-q"])
py_round(f"{tmp}/py.exr")
same = run([cli, "compare", f"{tmp}/cli.exr", f"{tmp}/py.exr"]).strip().splitlines()[-1].split()[-1]

cs, ps = [c for _, c, _ in rows], [p for _, _, p in rows]
cm, pm = statistics.median(cs), statistics.median(ps)
ratios = sorted(p / c for _, c, p in rows)
print("# The Python module against the CLI: trace seconds\n")
print(f"`bash bench/run_python_bench.sh` (ROUNDS={rounds}, SCENE={scene}) on {machine}, "
      f"commit {head}, {time.strftime('%Y-%m-%d', time.gmtime())}; {threads} threads both ways.\n")
print(f"Each round renders the {size}x{size} EIA of `{scene}` ({lenses}x{lenses} lenses x {ppl} px, "
      f"placed by its viewpoint) once with\n`holoray render {scene} --lenses {lenses}x{lenses} "
      f"--pixels-per-lens {ppl} -o x.png` (the `trace` seconds it prints) and once with\n"
      f"`holoray.render(holoray.load_scene(\"{scene}\"), holoray.LensArray(lenses=({lenses}, {lenses}), "
      f"pixels_per_lens={ppl}))` in a fresh `{py}` (`result.stats['seconds']['trace']`); "
      f"which goes first alternates.\n")
print(f"| | trace s, median of {rounds} |\n|---|---:|")
print(f"| CLI | {cm:.3f} |\n| Python | {pm:.3f} |")
print(f"| Python / CLI, ratio of the medians | {pm / cm:.3f} |")
print(f"| Python / CLI, median of the rounds' ratios (range) | "
      f"{statistics.median(ratios):.3f} ({ratios[0]:.3f}-{ratios[-1]:.3f}) |\n")
print("| round | first | CLI s | Python s | Python / CLI |\n|---:|---|---:|---:|---:|")
for k, (first, c, p) in enumerate(rows):
    print(f"| {k + 1} | {first} | {c:.3f} | {p:.3f} | {p / c:.3f} |")
print("\nChecks:\n")
print(f"- `result.colour` is float32 ({size}, {size}, 3) in every round: {'yes' if shape_ok else 'NO'}.")
print("- `result.colour` is not a copy (`flags['OWNDATA']` False, `base` not None) in every round: "
      + ("yes." if not copies else f"NO, a copy in rounds {copies}."))
print(f"- The CLI's EXR against the Python render's, PSNR (`holoray compare`, inf: identical): {same} dB.")
sys.exit(3 if copies or not shape_ok or same != "inf" else 0)  # 3: written, a check failed
PY
[ "$status" = 0 ] || [ "$status" = 3 ] || exit 1
mv "$tmp/python_results.md" bench/python_results.md
cat bench/python_results.md
[ "$status" = 0 ] || { echo "run_python_bench.sh: a check failed (see above)" >&2; exit 1; }
