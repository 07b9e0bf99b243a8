#!/usr/bin/env bash
# The live guide's screenshot (docs/guide/live.md): holoray live's real
# window under Xvfb, grabbed from the screen as X shows it (the swapchain's
# image, not the program's own screenshot): examples/primitives.nff as a
# 64x64-lens EIA, 12 px a lens, after a drag. The title it had is printed.
# Usage: bash docs/live/screenshot.sh   (after scripts/setup.sh)
set -euo pipefail
cd "$(dirname "$0")/../.."
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "1 orbit 96 -40" > "$tmp/events.txt"
xvfb-run -a -s "-screen 0 768x768x24" sh -c '
  build/holoray live examples/primitives.nff --lenses 64x64 --pixels-per-lens 12 --events "$0/events.txt" \
    --exit-after 1000000 > "$0/log" 2>&1 &
  pid=$!
  sleep 5  # a few frames past the drag
  python3 scripts/xwindow.py wait "holoray live:" 120 > "$0/title"
  python3 scripts/xwindow.py grab docs/images/live_window.png
  python3 scripts/xwindow.py close "holoray live"
  wait $pid' "$tmp" || { cat "$tmp/log"; exit 1; }
echo "title: $(cat "$tmp/title")"
echo "wrote docs/images/live_window.png"
