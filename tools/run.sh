#!/usr/bin/env bash
# The main job on a fresh Debian machine: install what is missing, build everything, render the built-in scene,
# serve the demo page. Usage: tools/run.sh [port]   (default 8080)
set -euo pipefail
cd "$(dirname "$0")/.."
port="${1:-8080}"

tools/install-deps.sh
tools/build.sh

build/obscura-render --out build/obscura.png
build/obscura-render --view ao --out build/obscura-ao.png
echo "run: rendered the built-in scene to build/obscura.png (AO view: build/obscura-ao.png)"
