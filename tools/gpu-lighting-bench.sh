#!/usr/bin/env bash
# The browser benchmark's Obscura configurations (tools/browser-bench/bench.mjs, issue 26) and the lighting's own
# choices (tiers, lighting.depth), natively through Mesa EGL: for a machine with a GPU, where the browser's SwiftShader
# figures do not carry over. Prints, per scene, size and configuration, the wall-clock milliseconds per frame
# (glFinish-bounded) and the passes' own milliseconds, from `obscura-render --bench`.
#
# Usage: tools/gpu-lighting-bench.sh [BUILD_DIR] [FRAMES]      (defaults: build, 30 frames; about 3 minutes on a GPU)
# Needs BUILD_DIR/obscura-render (tools/build.sh) and Debian's assimp test models for 2CylinderEngine.glb.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
frames=${2:-30}
render="$build/obscura-render"
[ -x "$render" ] || { echo "no $render: build first (tools/build.sh)" >&2; exit 1; }
engine=/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb
pbr=assets/scenes/pbr-samples.glb
[ -f "$engine" ] || { echo "no $engine (apt install assimp-testmodels)" >&2; exit 1; }

# name|arguments: the bench's Obscura renderers (bench.mjs RENDERERS: the fog there is exp2, 20 % at the camera target,
# which --fog.density below gives for the engine's framing), then the lighting's choices.
configurations=(
  "defaults (AO on)|"
  "AO off|--no-ao"
  "preset low (AO on)|--preset low"
  "preset low, AO off|--preset low --no-ao"
  "every effect|--bloom --dof --fog --fog.mode exp2 --fog.density 0.00047818"
  "AO off, lighting.depth gbuffer|--no-ao --lighting.depth gbuffer"
  "AO off, lighting.depth prepass|--no-ao --lighting.depth prepass"
  "AO off, lighting.depth overdraw|--no-ao --lighting.depth overdraw"
  "lighting.quality low|--lighting.quality low"
  "lighting.quality high|--lighting.quality high"
)

echo "obscura-render --bench $frames --backend egl; $(date -u +%Y-%m-%dT%H:%M:%SZ); $(git rev-parse --short HEAD 2>/dev/null)"
for scene in "$engine" "$pbr"; do
  for size in 640x360 1280x720; do
    for entry in "${configurations[@]}"; do
      name=${entry%%|*}
      arguments=${entry#*|}
      # shellcheck disable=SC2086
      out=$("$render" --scene "$scene" --size "$size" --backend egl --bench "$frames" --out /tmp/gpu-lighting-bench.png \
            $arguments 2>&1 | grep -E '^(total|gbuffer|lighting|sao|hierarchy|blur-h|blur-v|fxaa|tonemap|fog|bloom|dof-composite) ' ||
            true)
      wall=$(echo "$out" | sed -n 's/.*wall clock per frame \([0-9.]*\) ms.*/\1/p')
      passes=$(echo "$out" | grep -v '^total' | awk '{printf "%s %s; ", $1, $2}')
      printf '%-16s %-9s %-34s %9s ms  %s\n' "$(basename "$scene" .glb)" "$size" "$name" "${wall:-?}" "$passes"
    done
  done
done
