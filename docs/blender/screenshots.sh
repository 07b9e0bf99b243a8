#!/usr/bin/env bash
# The Blender guide's screenshots (docs/guide/blender.md): Debian's Blender
# with its real interface under Xvfb, the add-on from build/blender, the
# tests' scene (tests/blender/scene.py) as a 96x64-lens EIA: the settings
# panel, then the render result in the image editor.
# Usage: bash docs/blender/screenshots.sh   (after scripts/setup.sh; needs xvfb)
set -euo pipefail
cd "$(dirname "$0")/../.."
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
export BLENDER_USER_SCRIPTS=$PWD/build/blender PATH=$PWD/build:$PATH HOLORAY_SHOTS=$tmp
blender -b --factory-startup --python docs/blender/make_blend.py -- "$tmp/ui.blend" >/dev/null
xvfb-run -a -s "-screen 0 1600x1000x24" blender "$tmp/ui.blend" --addons holoray_blender \
  --python docs/blender/screenshots.py >"$tmp/log" 2>&1 || { tail -20 "$tmp/log"; exit 1; }
for shot in settings result; do
  oiiotool "$tmp/ui_$shot.png" --resize 1280x0 -o "docs/images/blender_$shot.png"
done
echo "wrote docs/images/blender_settings.png docs/images/blender_result.png"
