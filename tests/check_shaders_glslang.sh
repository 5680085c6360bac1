#!/usr/bin/env bash
# Validates every program variant, exactly as the renderer composes it, with glslangValidator (GLSL ES 1.00 because
# each source starts with "#version 100"). Usage: check_shaders_glslang.sh <obscura-shaders binary>
set -euo pipefail
dump=$(mktemp -d)
trap 'rm -rf "$dump"' EXIT
"$1" --dump "$dump"
count=0
for file in "$dump"/*.vert "$dump"/*.frag; do
  if ! out=$(glslangValidator "$file" 2>&1); then
    echo "glslangValidator rejected $(basename "$file"):"
    echo "$out"
    exit 1
  fi
  count=$((count + 1))
done
echo "glslangValidator accepted $count shader stages as GLSL ES 1.00"
[ "$count" -ge 40 ]
