#!/usr/bin/env bash
# Renders the README's pictures into docs/images (needs ../shared/scenes for
# the SPD scenes). For each scene: the EIA at 64x64 lenses x 8 px (512x512)
# and the centre sub-aperture view of a 200x200-lens x 5 px render.
set -euo pipefail
cd "$(dirname "$0")/.."
h=build/holoray
out=docs/images
tmp=$(mktemp -d)
mkdir -p "$out"
render() {  # name scene-file
  "$h" render "$2" -o "$out/$1_eia.png" --lenses 64x64 --pixels-per-lens 8 -q
  "$h" render "$2" -o "$tmp/$1_big.png" --lenses 200x200 --pixels-per-lens 5 -q
  "$h" subaperture "$tmp/$1_big.png" --pixels-per-lens 5 -o "$out/$1_view.png"
}
for s in balls_s4 gears_s4 teapot_s6 tree_s11; do render "${s%_s*}" "../shared/scenes/nff/$s.nff"; done
render primitives examples/primitives.nff
render room examples/room.nff
# A close-up of the elemental images: the top-left 96x96 pixels of the teapot EIA, 4x.
oiiotool "$out/teapot_eia.png" --cut 96x96+208+208 --resize 384x384 --filter box -o "$out/teapot_eia_closeup.png" 2>/dev/null ||
  oiiotool "$out/teapot_eia.png" --cut 96x96+208+208 --resize 384x384 -o "$out/teapot_eia_closeup.png"
# The paper's Room in Tachyon's language: holoray's pinhole view, Tachyon's
# own (tachyon-nox, run from the scene's folder for its image maps), the
# pseudoscopic EIA (the camera is inside the room) and its centre view.
room=../shared/scenes/tachyon/room.dat
"$h" render "$room" --camera pinhole -o "$tmp/room_pinhole.png" -q
oiiotool "$tmp/room_pinhole.png" --resize 256x256 -o "$out/room_tachyon_pinhole.png"
(cd "$(dirname "$room")" && tachyon-nox room.dat -aasamples 0 -format PNG -o "$tmp/room_tachyon.png" >/dev/null)
oiiotool "$tmp/room_tachyon.png" --resize 256x256 -o "$out/room_tachyon_reference.png"
"$h" render "$room" --mode pseudoscopic -o "$out/room_tachyon_eia.png" -q
"$h" subaperture "$out/room_tachyon_eia.png" -o "$tmp/room_view.png"
oiiotool "$tmp/room_view.png" --resize 256x256 -o "$out/room_tachyon_view.png"
# Tachyon's three AC3D models (Debian tachyon-doc) in their default views.
ac=/usr/share/doc/tachyon/examples/scenes
for m in f117 goblet tie2; do "$h" render "$ac/$m.ac" --camera pinhole -o "$tmp/ac_$m.png" -q; done
oiiotool "$tmp/ac_f117.png" "$tmp/ac_goblet.png" "$tmp/ac_tie2.png" --mosaic 3x1 --resize 768x256 -o "$out/ac_models.png"
# A glTF file's node animation played by a shot: frames 0, 16, 32 and 47
# previewed as pinhole views, and frame 24's EIA.
"$h" animate examples/shots/swinging_box.toml --camera pinhole --resolution 256x256 -o "$tmp/swing_views" -q
oiiotool "$tmp/swing_views/frame_0000.png" "$tmp/swing_views/frame_0016.png" "$tmp/swing_views/frame_0032.png" \
  "$tmp/swing_views/frame_0047.png" --mosaic 4x1 -o "$out/swinging_box_views.png"
"$h" animate examples/shots/swinging_box.toml -o "$tmp/swing_eia" -q
cp "$tmp/swing_eia/frame_0024.png" "$out/swinging_box_eia.png"
# A native panel image (issue 14): examples/primitives.nff on the 4K slanted
# lenticular display of examples/displays/lenticular_4k.toml, the whole panel
# scaled down, and a 48x27-pixel close-up with each pixel drawn as its three
# subpixel stripes, each lit by its own line's channel.
"$h" render examples/primitives.nff --display examples/displays/lenticular_4k.toml -o "$tmp/panel.png" -q
oiiotool "$tmp/panel.png" --resize 480x270 -o "$out/panel_4k_lenticular.png"
oiiotool "$tmp/panel.png" -o "$tmp/panel.ppm"
python3 docs/subpixel_closeup.py "$tmp/panel.ppm" "$tmp/closeup.ppm" 1190 1175 48 27 4
oiiotool "$tmp/closeup.ppm" -o "$out/panel_4k_lenticular_closeup.png"
oiiotool "$tmp/panel.png" --cut 120x68+1150+1150 --resample:interp=0 480x272 -o "$out/panel_4k_lenticular_pixels.png"
# What a viewer sees on that panel, simulated from two eye positions 80 mm
# apart at 600 mm (holoray simulate), side by side.
"$h" simulate "$tmp/panel.png" --display examples/displays/lenticular_4k.toml --eye -40,0,600 --width 480 -o "$tmp/eye_l.png"
"$h" simulate "$tmp/panel.png" --display examples/displays/lenticular_4k.toml --eye 40,0,600 --width 480 -o "$tmp/eye_r.png"
oiiotool "$tmp/eye_l.png" "$tmp/eye_r.png" --mosaic 2x1 -o "$out/simulated_eyes.png"
# A Looking Glass quilt (8x6 views of 420x560), scaled down, and an EIA's
# parallax sweep as a GIF (holoray views).
"$h" render examples/primitives.nff --quilt 8x6 --view-cone 40 -o "$tmp/quilt.png" -q
oiiotool "$tmp/quilt_qs8x6a0.75.png" --resize 672x672 -o "$out/quilt_qs8x6a0.75.png"
"$h" render examples/primitives.nff --lenses 160x120 --pixels-per-lens 8 -o "$tmp/eia_views.png" -q
"$h" views "$tmp/eia_views.png" --pixels-per-lens 8 -o "$out/parallax.gif"
# Path tracing (docs/guide/light.md): the area-lit room of examples/lights as
# an EIA and its centre view, and the glTF box under Blender's courtyard HDRI.
"$h" render examples/lights/cornell_box.nff --integrator path --spp 64 --lights examples/lights/cornell_box.toml \
  -o "$out/cornell_path_eia.png" -q
"$h" render examples/lights/cornell_box.nff --integrator path --spp 16 --lights examples/lights/cornell_box.toml \
  --lenses 200x200 --pixels-per-lens 5 -o "$tmp/cornell_big.png" -q
"$h" subaperture "$tmp/cornell_big.png" --pixels-per-lens 5 -o "$out/cornell_path_view.png"
"$h" render examples/swinging_box.gltf --camera pinhole --resolution 256x192 --integrator path --spp 256 \
  --environment /usr/share/blender/datafiles/studiolights/world/courtyard.exr -o "$out/box_courtyard_path.png" -q
rm -rf "$tmp"
ls -la "$out"
