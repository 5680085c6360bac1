#!/usr/bin/env bash
# Renders the pictures in README.md and docs/ with obscura-render (run tools/build.sh first).
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
echo "render-docs-images: wrote $out/builtin_*.png"
