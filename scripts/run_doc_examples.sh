#!/usr/bin/env bash
# Runs every command the README and the user guide show as runnable, so the
# docs cannot drift from the program. A runnable block is a fenced block
# whose info string is `sh runnable`; the blocks of one file run in order,
# in one fresh folder holding links to the checkout's examples/ and build/,
# with build/ first on the PATH (the README's `./build/holoray` and the
# guide's `holoray` both resolve). A command that fails fails the check,
# naming the file and the block's first line.
# Usage: bash scripts/run_doc_examples.sh [FILE.md ...]  (default: README.md docs/guide/*.md)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
cd "$root"
files=("$@")
((${#files[@]})) || files=(README.md docs/guide/*.md)
[ -x build/holoray ] || { echo "run_doc_examples: build/holoray is missing: run scripts/setup.sh first" >&2; exit 1; }
# Containers run as root, which mpirun refuses unless told.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export PATH="$root/build:$PATH"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
blocks=0
k=0
for f in "${files[@]}"; do
  k=$((k + 1))
  dir="$work/$k"
  mkdir "$dir"
  ln -s "$root/examples" "$dir/examples"
  ln -s "$root/build" "$dir/build"
  # Each runnable block as one script: its lines between the fences.
  n=0
  while IFS= read -r -d '' block; do
    n=$((n + 1))
    blocks=$((blocks + 1))
    first="$(printf '%s\n' "$block" | head -n 1)"
    echo "== $f, block $n: $first"
    if ! (cd "$dir" && bash -euo pipefail -c "$block" > "$dir/block$n.log" 2>&1); then
      echo "run_doc_examples: $f: block $n failed: $first" >&2
      tail -n 20 "$dir/block$n.log" >&2
      exit 1
    fi
  done < <(awk '
    /^```sh runnable[[:space:]]*$/ { inside = 1; text = ""; next }
    inside && /^```[[:space:]]*$/ { inside = 0; printf "%s%c", text, 0; next }
    inside { text = text $0 "\n" }
  ' "$f")
done
echo "run_doc_examples: $blocks blocks ran"
