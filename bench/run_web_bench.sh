#!/usr/bin/env bash
# The light-field page (issue 72): a 4096x4096 EIA (64x64 lenses x 64 px) of
# primitives.nff written by `holoray web`, served by `holoray web --serve`,
# opened in headless Chromium (Debian's, through playwright-core; WebGL2 on
# SwiftShader, the CPU, where there is no GPU): the folder's size, the time
# from opening the address to the first view drawn (median of LOADS), and
# frames per second of parallax (pointer moves, FRAMES of them) and of
# refocus (the focus slider with APERTURE views open). Each run of frames
# ends with the canvas read back, so the drawing is counted. The do-nothing
# baseline: a page of a 64x64 EIA of 1 px per lens (one view), the same way.
# Usage: bash bench/run_web_bench.sh  (LOADS=5 FRAMES=200 APERTURE=8 LENSES=64 PPL=64)
set -euo pipefail
cd "$(dirname "$0")/.."
loads=${LOADS:-5} frames=${FRAMES:-200} aperture=${APERTURE:-8} lenses=${LENSES:-64} ppl=${PPL:-64}
tmp=$(mktemp -d)
trap 'kill $(jobs -p) 2>/dev/null || true; rm -rf "$tmp"' EXIT
[[ -d tests/web/node_modules/playwright-core ]] || { echo "run_web_bench.sh: run scripts/setup.sh first (tests/web's playwright-core)" >&2; exit 1; }
measure() {  # EIA folder -> JSON line
  build/holoray web --serve "$1" --port 0 > "$tmp/serve.log" &
  for _ in $(seq 50); do grep -q "http" "$tmp/serve.log" && break; sleep 0.1; done
  local url
  url=$(sed -n 's/.* at \(http[^ ]*\) .*/\1/p' "$tmp/serve.log")
  node bench/web_frames.mjs "$url" "$loads" "$frames" "$aperture"
  kill %1 && wait %1 2>/dev/null || true
}
build/holoray render examples/primitives.nff --lenses "${lenses}x${lenses}" --pixels-per-lens "$ppl" -q -o "$tmp/eia.png"
build/holoray web "$tmp/eia.png" --pixels-per-lens "$ppl" -q -o "$tmp/page"
build/holoray render examples/primitives.nff --lenses "${lenses}x${lenses}" --pixels-per-lens 1 -q -o "$tmp/one.png"
build/holoray web "$tmp/one.png" --pixels-per-lens 1 -q -o "$tmp/one"
echo "Command: LOADS=$loads FRAMES=$frames APERTURE=$aperture LENSES=$lenses PPL=$ppl bash bench/run_web_bench.sh"
echo "Machine: $(nproc) cores, $(sed -n 's/^model name[^:]*: //p' /proc/cpuinfo | head -1); $(chromium --version 2>/dev/null | head -1)"
echo
echo "| page | folder | load ms (median of $loads) | parallax fps | refocus fps (aperture $aperture) |"
echo "|---|---:|---:|---:|---:|"
row() {
  local line
  line=$(measure "$2")
  /usr/bin/python3 -c "import json,sys; r=json.loads(sys.argv[1]); print(f\"| $1 | $(du -sh "$2" | cut -f1) | {r['load_ms_median']} | {r['parallax_fps']:.1f} | {r['refocus_fps']:.2f} |\")" "$line"
}
row "${lenses}x${lenses} lenses x $ppl px ($((lenses * ppl))x$((lenses * ppl)) EIA)" "$tmp/page"
row "do nothing: ${lenses}x${lenses} lenses x 1 px (one view)" "$tmp/one"
