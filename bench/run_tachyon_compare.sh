#!/usr/bin/env bash
# holoray's pinhole view of Tachyon scenes against Tachyon itself (issue 13):
# every example scene of Debian's tachyon-doc plus the paper's three in
# ../shared/scenes/tachyon, at each file's own resolution, one sample per
# pixel where Tachyon samples (--sample-at tachyon), tachyon-nox with
# -aasamples 0. Scenes holoray refuses are listed with the refusal. Then the
# wall time of both on the paper's three scenes (bench/tachyon_speed.py).
# Writes bench/tachyon_results.md. Usage: bash bench/run_tachyon_compare.sh
set -euo pipefail
cd "$(dirname "$0")/.."
holoray=$PWD/build/holoray
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
report=bench/tachyon_results.md
{
  echo "# holoray against Tachyon (pinhole view)"
  echo
  echo "\`bash bench/run_tachyon_compare.sh\` on $(date -u +%Y-%m-%d): PSNR of holoray's"
  echo "\`render SCENE --camera pinhole --sample-at tachyon\` against \`tachyon-nox SCENE -aasamples 0\`,"
  echo "8-bit PNG, linear encoding (as Tachyon writes)."
  echo
  echo "| scene | PSNR dB or refusal |"
  echo "|---|---|"
} > "$report"
run_dir() {  # folder, label prefix
  local dir=$1 prefix=$2
  [ -d "$dir" ] || return 0
  for f in "$dir"/*.dat; do
    local n; n=$(basename "$f" .dat)
    local msg
    if msg=$(cd "$dir" && "$holoray" render "$n.dat" --camera pinhole --sample-at tachyon -o "$out/h_$n.png" -q 2>&1); then
      (cd "$dir" && timeout 300 tachyon-nox "$n.dat" -aasamples 0 -format PNG -o "$out/t_$n.png" >/dev/null 2>&1)
      local p; p=$("$holoray" compare "$out/h_$n.png" "$out/t_$n.png" | awk '$1 == "all" {print $NF}')
      echo "| $prefix$n | $p |" >> "$report"
    else
      echo "| $prefix$n | refused: \`$(echo "$msg" | head -1 | sed 's/|/\\|/g')\` |" >> "$report"
    fi
  done
}
run_dir ../shared/scenes/tachyon "shared/"
run_dir /usr/share/doc/tachyon/examples/scenes ""
if [ -d ../shared/scenes/tachyon ]; then
  {
    echo
    echo "## Speed, the same work (python3 bench/tachyon_speed.py, 5 alternated runs, medians)"
    echo
    python3 bench/tachyon_speed.py "$holoray" ../shared/scenes/tachyon/{room,smallballs,teapot}.dat --runs 5
  } >> "$report"
fi
cat "$report"
