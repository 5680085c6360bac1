#!/usr/bin/env bash
# The main job on a fresh Debian machine: install what is missing, build the native and the web versions, render
# the built-in scene to a PNG, then serve the demo page on 127.0.0.1 (in the foreground; Ctrl+C stops).
# Usage: tools/run.sh [port]   (default 8080)
set -euo pipefail
cd "$(dirname "$0")/.."
port="${1:-8080}"

tools/install-deps.sh
tools/build.sh
tools/build-web.sh

build/obscura-render --out build/obscura.png
build/obscura-render --view ao --out build/obscura-ao.png
echo "run: rendered the built-in scene to build/obscura.png (AO view: build/obscura-ao.png)"
echo "run: desktop viewer: build/obscura-view [scene.glb]"
exec node tools/serve-web.mjs build-web/site "$port"
