#!/usr/bin/env bash
# CI on Debian 13 ("trixie": Embree 4, Python 3.13, numpy 2, Blender 4.3):
# the README's quick-start commands, exactly as the README writes them (the
# tests scripts/test_sets.sh names skipped), then its runnable blocks, in a fresh Debian 13 root holding a clone of this
# repository's committed HEAD, with ../shared beside it (read-only).
#
# The root is Debian's minimal system (debootstrap --variant=minbase) from
# Debian's archive; its tarball and apt's downloaded packages are cached in
# $HOLORAY_DEBIAN13_CACHE (default ~/.cache/holoray) so that a second run on
# one machine skips the downloads, but every run unpacks a new root and
# installs into it from nothing. Everything runs inside a private mount
# namespace (unshare -m), so nothing stays mounted, and the root is deleted
# at the end. A root that cannot be made fails the run; nothing is skipped.
# Needs root (debootstrap, unshare, chroot): runs itself under sudo otherwise. Usage: bash scripts/debian13_check.sh
# (KEEP_ROOT=DIR: keep the root, with its build, in DIR afterwards, for
# bench/run_embree_bench.sh; DIR must not exist yet.)
set -euo pipefail
cd "$(dirname "$0")/.."
repo=$PWD
# debootstrap, unshare -m and chroot need root.
[ "$(id -u)" -eq 0 ] || exec sudo --preserve-env=CI,HOLORAY_DEBIAN_MIRROR,HOLORAY_DEBIAN13_CACHE,KEEP_ROOT \
  HOME="$HOME" bash "$0" "$@"
mirror=${HOLORAY_DEBIAN_MIRROR:-http://deb.debian.org/debian}
cache=${HOLORAY_DEBIAN13_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/holoray}
mkdir -p "$cache/apt-archives/partial"

if ! command -v debootstrap >/dev/null; then
  echo "debian13_check: installing debootstrap"
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends debootstrap >/dev/null
fi

base=$cache/trixie-minbase.tar
if [ ! -s "$base" ]; then
  echo "== making the Debian 13 minimal root (debootstrap)"
  made=$(mktemp -d /var/tmp/holoray-debootstrap.XXXXXX)
  if ! debootstrap --variant=minbase trixie "$made/root" "$mirror" > "$made/log" 2>&1; then
    tail -n 20 "$made/log" >&2
    rm -rf --one-file-system "$made"
    echo "debian13_check: debootstrap could not make the Debian 13 root from $mirror" >&2
    exit 1
  fi
  tar -C "$made/root" -cf "$base.part" .
  mv "$base.part" "$base"
  rm -rf --one-file-system "$made"
fi

if [ -n "${KEEP_ROOT:-}" ]; then
  [ ! -e "$KEEP_ROOT" ] || { echo "debian13_check: KEEP_ROOT=$KEEP_ROOT exists already" >&2; exit 1; }
  mkdir -p "$KEEP_ROOT"
  root=$(cd "$KEEP_ROOT" && pwd)
else
  root=$(mktemp -d /var/tmp/holoray-debian13.XXXXXX)
  trap 'rm -rf --one-file-system "$root"' EXIT
fi
tar -C "$root" -xf "$base"
git clone -q --no-hardlinks "$repo" "$root/root/holoray"
mkdir -p "$root/root/shared"
# The README's test command runs as written; CTest skips the tests that
# scripts/test_sets.sh says Debian 12's run covers alone, read from the
# build folder (CTestCustom.cmake) before set-up makes the rest of it.
source scripts/test_sets.sh
mkdir -p "$root/root/holoray/build"
ctest_ignore_file "${DEBIAN13_SKIPPED_TESTS[@]}" > "$root/root/holoray/build/CTestCustom.cmake"
echo "== in Debian 13, CTest skips ${#DEBIAN13_SKIPPED_TESTS[@]} tests (scripts/test_sets.sh)"

# The README's quick start: its first sh block after "## Quick start".
quick_start=$(awk '/^## Quick start/ {q = 1} q && /^```sh$/ {b = 1; next} b && /^```/ {exit} b {print}' README.md)
[ -n "$quick_start" ] || { echo "debian13_check: no quick-start block in README.md" >&2; exit 1; }
echo "== in Debian 13, as the README says:"
printf '%s\n' "$quick_start"

# Inside a private mount namespace: the kernel's file systems, the network's
# resolver and certificate authorities, ../shared read-only and apt's
# download cache; then chroot. The
# script is an argument, not stdin, so that nothing it runs can read it.
inside='
root=$1 shared=$2 archives=$3 quick_start=$4
mount -t proc proc "$root/proc"
mount --rbind /sys "$root/sys"
mount --rbind /dev "$root/dev"
mount -t tmpfs tmpfs "$root/tmp"
mount --bind "$archives" "$root/var/cache/apt/archives"
if [ -d "$shared" ]; then
  mount --bind "$shared" "$root/root/shared"
  mount -o remount,bind,ro "$root/root/shared"
fi
cp /etc/resolv.conf "$root/etc/resolv.conf"
# The certificate authorities of this machine too, for the npm of the set-up
# (HTTPS): a network that inspects TLS is trusted through them here, as apt
# reaches its mirror through the resolver.
cp /etc/ssl/certs/ca-certificates.crt "$root/etc/holoray-host-ca.crt" 2>/dev/null || : > "$root/etc/holoray-host-ca.crt"
chroot "$root" /usr/bin/env -i HOME=/root LANG=C.UTF-8 TERM=dumb CI="${CI:-}" NODE_EXTRA_CA_CERTS=/etc/holoray-host-ca.crt \
  PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin \
  bash -euo pipefail -c "cd /root/holoray
grep PRETTY_NAME /etc/os-release
$quick_start
bash scripts/run_doc_examples.sh README.md"
'
unshare -m --propagation private bash -euo pipefail -c "$inside" debian13 "$root" "$(cd .. && pwd)/shared" \
  "$cache/apt-archives" "$quick_start" < /dev/null
echo "debian13_check: the README's commands pass on Debian 13"
