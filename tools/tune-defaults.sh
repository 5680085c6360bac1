#!/usr/bin/env bash
# Fits each AO estimator's intensity, bias and contrast per quality preset and radius in pixels to the ray-traced
# reference, makes them the defaults, and regenerates the accuracy report. One command, deterministic; re-run it after any change to the AO
# pipeline (passes, presets, shaders) and commit what it rewrites:
#   src/effects/ao/TunedDefaults.inc   the fitted table AoSettings reads
#   docs/accuracy.md             the generated tables (between the obscura-tune markers)
#   docs/images/accuracy-*.png   reference | AO | difference
#   tests/golden/*.png           the golden images, which show the default (tuned) AO
#   docs/images/builtin_*.png    the README's pictures (tools/render-docs-images.sh), likewise
# Reference images are cached in build/tuning-cache (traced once per view and radius, about a second each). About
# 35 minutes on two cores (2026-11-28: the fit 27 for one layer, 2.5 for GTAO medium with two; the rest 5). Usage:
# tools/tune-defaults.sh
set -euo pipefail
cd "$(dirname "$0")/.."

tools/build.sh
# GTAO's rows for ao.layers 2 (medium; the other presets fall back to one layer's rows) first, then every row for one
# layer: the second run keeps the first's rows as the file has them (obscura-tune reads the table it rewrites, so
# the rows fitted a moment ago survive though the binary was built with the older table).
build/obscura-tune --views tools/tuning-views.json --fit src/effects/ao/TunedDefaults.inc --estimators gtao \
  --presets medium --layers 2
build/obscura-tune --views tools/tuning-views.json --fit src/effects/ao/TunedDefaults.inc
tools/build.sh  # the core now reads the new table
# The report's browser column: what tools/browser-bench/estimator-costs.mjs measured last (bench-results/), if it ran.
browser_costs=()
if [ -f bench-results/browser-estimators.csv ]; then browser_costs=(--browser-ms bench-results/browser-estimators.csv); fi
build/obscura-tune --views tools/tuning-views.json --report docs/accuracy.md --images docs/images "${browser_costs[@]}"
# The same defaults through orthographic cameras: their own section of the report.
build/obscura-tune --views tools/orthographic-views.json --report docs/accuracy.md --images docs/images
OBSCURA_UPDATE_GOLDEN=1 ctest --test-dir build -R 'gpu\.osmesa\.Golden' >/dev/null
tools/render-docs-images.sh
echo "tune-defaults: rewrote src/effects/ao/TunedDefaults.inc, docs/accuracy.md, docs/images/*.png and"
echo "  tests/golden/*.png;"
echo "tune-defaults: now run tools/test.sh (the accuracy guard's bounds are in tests/test_accuracy.cpp)"
