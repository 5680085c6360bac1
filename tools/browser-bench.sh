#!/usr/bin/env bash
# Browser benchmark: Obscura's demo page against three.js (plain, SAOPass, N8AO) in headless Debian chromium on
# SwiftShader. Builds the web version (incremental), installs tools/browser-bench's npm packages from its
# package-lock.json (three, n8ao, postprocessing, playwright-core; no browser is downloaded), then runs the benchmark.
# docs/benchmarks.md ("In the browser: Obscura against three.js") explains what it measures and the figures.
#
# Usage: tools/browser-bench.sh [--frames N] [--rounds R] [--warmup W] [--sizes 640x360,1280x720] [--quick]
#                               [--extras | --no-extras] [--csv FILE] [--shots DIR]
#   default: both sizes, 3 warm-up frames, 10 rounds x 3 frames per renderer, results in bench-results/browser-bench*.csv
#   --quick: smoke run (640x360, 2 rounds x 2 frames, results in build/browser-bench/)
# Screenshots of every renderer: build/browser-bench/*.png
set -euo pipefail
cd "$(dirname "$0")/.."
tools/build-web.sh
(cd tools/browser-bench && npm ci --no-audit --no-fund --loglevel=error)
exec node tools/browser-bench/bench.mjs "$@"
