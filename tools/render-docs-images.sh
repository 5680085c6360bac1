#!/usr/bin/env bash
# Renders the pictures in README.md and docs/: the built-in scene with obscura-render, and the demo page in headless
# Chromium (AO off / on / split) with the browser tests' tooling. Run tools/build.sh and tools/build-web.sh first.
set -euo pipefail
cd "$(dirname "$0")/.."
out=docs/images
mkdir -p "$out"
build/obscura-render --size 960x540 --out "$out/builtin_final.png"
build/obscura-render --size 960x540 --no-ao --out "$out/builtin_final_no_ao.png"
build/obscura-render --size 960x540 --view ao --out "$out/builtin_ao.png"
build/obscura-render --size 960x540 --view ao-raw --out "$out/builtin_ao_raw.png"
build/obscura-render --size 960x540 --view normals --out "$out/builtin_normals.png"
build/obscura-render --size 960x540 --view depth --out "$out/builtin_depth.png"
# Mid-swing, and the motion vectors of that frame (the pendulum and the limb; the camera is still).
build/obscura-render --size 960x540 --time 1.2 --out "$out/builtin_moving.png"
build/obscura-render --size 960x540 --time 1.2 --view velocity --out "$out/builtin_velocity.png"
# Motion blur (docs/temporal-effects.md): the pendulum and the limb at 2 s, where the pendulum passes the bottom of
# its swing fastest, at 10 frames per second with the shutter open the whole interval; sharp | blurred | the mean of
# 64 renders over the exposure.
mb="--size 960x540 --time 2 --fps 10"
build/obscura-render $mb --out "$out/motion_sharp.png"
build/obscura-render $mb --motion-blur on --motion-blur.shutter 1 --out "$out/motion_blur.png"
build/obscura-render $mb --accumulate 64 --shutter 1 --out "$out/motion_reference.png"
# Temporal AO: the still room's AO at 4 taps in one frame | 4 taps over 8 frames | the default (12 taps) | the
# ray-traced reference.
ao="--size 480x270 --animation none --view ao"
build/obscura-render $ao --ao.samples 4 --out "$out/ao_4_taps.png"
build/obscura-render $ao --ao.samples 4 --ao.temporal on --frames 8 --out "$out/ao_temporal_4_taps.png"
build/obscura-render $ao --out "$out/ao_default.png"
build/obscura-reference --size 480x270 --animation none --view ao --out "$out/ao_reference.png"
# Antialiasing (docs/temporal-effects.md), a close view of the arch, the pendulum's rod and the boxes: none | FXAA |
# TAA after 16 frames | the frame rendered 4 times larger and box-downsampled.
aa="--camera tools/docs-taa-camera.json --animation none"
build/obscura-render $aa --no-fxaa --out "$out/aa_none.png"
build/obscura-render $aa --out "$out/aa_fxaa.png"
build/obscura-render $aa --taa on --no-fxaa --frames 16 --out "$out/aa_taa.png"
build/obscura-render $aa --no-fxaa --accumulate 1 --shutter 0 --supersample 4 --out "$out/aa_reference.png"
# Bloom and fog (docs/bloom-and-fog.md): bloom with a threshold low enough for the room's lit surfaces (0.95 at most),
# and exponential fog thickest at the floor (height falloff).
build/obscura-render --size 480x270 --bloom --bloom.threshold 0.2 --bloom.intensity 1.5 --out "$out/bloom.png"
build/obscura-render --size 480x270 --fog --fog.density 0.6 --fog.height-falloff 0.8 --fog.color 0.7,0.75,0.8 \
  --out "$out/fog_height.png"
# Edges (docs/edges.md): lines two pixels wide, and the toon style.
build/obscura-render --size 480x270 --edges --edges.width 2 --out "$out/edges.png"
build/obscura-render --size 480x270 --edges --edges.style toon --edges.width 2 --out "$out/edges_toon.png"
# Hatching (docs/camera-finish.md): world-space strokes in bands of the luma, under the lines, beside toon.
build/obscura-render --size 480x270 --edges --edges.style hatching --edges.width 2 --out "$out/edges_hatching.png"
# Auto exposure (docs/camera-finish.md) stepping through a light change: the sun 16x brighter from frame 10 of a
# 60 fps sequence; adapted to the old sun | the first frame after the step | 0.25 s after | 1 s after | adapted to the
# new sun | the new sun without auto exposure.
ae="--size 320x180 --animation none --auto-exposure"
build/obscura-render $ae --out "$out/auto_exposure_before.png"
for frames in 11 25 70; do
  build/obscura-render $ae --frames $frames --at 10 lighting.sun-intensity=50 --out "$out/auto_exposure_$frames.png"
done
build/obscura-render $ae --lighting.sun-intensity 50 --out "$out/auto_exposure_after.png"
build/obscura-render --size 320x180 --animation none --lighting.sun-intensity 50 --out "$out/auto_exposure_off.png"
# Lens flare and glare (docs/camera-finish.md): the sky's sun low in front of the camera, bloom alone | with the flare
# and a six-pointed star.
flare="--camera tools/docs-flare-camera.json --lighting.sun-elevation 16 --lighting.sun-azimuth 212 --bloom"
build/obscura-render $flare --out "$out/flare_bloom.png"
build/obscura-render $flare --lens-flare --lens-flare.intensity 0.15 --glare --glare.streaks 6 --glare.angle 15 \
  --glare.intensity 0.1 --out "$out/flare_glare.png"
# Colour grading and the display colour's stages (docs/camera-finish.md): ungraded | a grade by the parameters (white
# balance, saturation, contrast, a CDL offset), the vignette and grain | a .cube LUT (assets/luts/teal-orange.cube).
build/obscura-render --size 480x270 --out "$out/grading_off.png"
build/obscura-render --size 480x270 --grading --grading.temperature 7200 --grading.tint 4 --grading.saturation 1.2 \
  --grading.contrast 1.15 --grading.offset -0.005,-0.005,0.005 --vignette --vignette.intensity 0.3 \
  --vignette.smoothness 0.5 --grain --grain.intensity 0.06 --out "$out/grading_balance.png"
build/obscura-render --size 480x270 --grading --grading.lut assets/luts/teal-orange.cube --grading.contrast 1.1 \
  --vignette --vignette.intensity 0.3 --vignette.smoothness 0.5 --out "$out/grading_lut.png"
# Depth of field (docs/depth-of-field.md): an 85 mm lens at f/1.2 focused on the red sphere (autofocus on the point
# 0.48, 0.58 of the frame); pinhole | depth of field | the mean of 64 pinhole renders over the lens (the reference).
dof="--size 640x360 --dof.focal-length 85 --dof.fstop 1.2 --dof.focus-x 0.48 --dof.focus-y 0.58"
build/obscura-render $dof --out "$out/dof_pinhole.png"
build/obscura-render $dof --dof --out "$out/dof.png"
build/obscura-render $dof --aperture 64 --out "$out/dof_reference.png"
# Image-based ambient light (docs/lighting.md): the built-in sky (the default), and the made studio environment.
build/obscura-make-environment assets/environments/studio.hdr
build/obscura-render --size 480x270 --out "$out/lighting_sky.png"
build/obscura-render --size 480x270 --lighting.environment assets/environments/studio.hdr \
  --lighting.environment-intensity 1.5 --out "$out/lighting_studio.png"
# Materials and lights (docs/pbr.md): the metallic-roughness sample, and with bloom on its emission and highlights.
pbr="--scene assets/scenes/pbr-samples.glb --camera tools/docs-pbr-camera.json"
build/obscura-render $pbr --out "$out/pbr_samples.png"
build/obscura-render $pbr --bloom --out "$out/pbr_samples_bloom.png"
# The transparent layer and the material layers (docs/transparency.md): the glass sample.
build/obscura-render --scene assets/scenes/glass-samples.glb --camera tools/docs-glass-camera.json \
  --out "$out/glass_samples.png"
echo "render-docs-images: wrote $out/builtin_*.png, motion_*.png, ao_*.png, aa_*.png, bloom.png, fog_height.png," \
  "edges.png, edges_toon.png, edges_hatching.png, auto_exposure_*.png, flare_*.png, grading_*.png, dof*.png," \
  "lighting_*.png, pbr_*.png, glass_samples.png"

(cd tests/browser && npm ci --no-audit --no-fund --loglevel=error)
OBSCURA_UPDATE_SCREENSHOTS=1 node --test --test-name-pattern="page screenshots" tests/browser/page.test.mjs >/dev/null
echo "render-docs-images: wrote $out/web_ao_off.png, web_ao_on.png, web_split.png"
