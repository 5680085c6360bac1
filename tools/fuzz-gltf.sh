#!/usr/bin/env bash
# Fuzzes scene loading with libFuzzer (clang), seeded with Debian's assimp-testmodels glTF files and
# tests/fuzz/seeds (skins, morph targets and animations in every form the loader reads; make-seeds.py wrote them).
#   tools/fuzz-gltf.sh [SECONDS]      default 60; the test suite runs the default, docs/robustness.md a longer run
# The corpus grows in build-fuzz/corpus (kept between runs); crashes land in build-fuzz/ as crash-* files.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
jobs=$(nproc 2>/dev/null || echo 2)
CC=clang CXX=clang++ cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DOBSCURA_FUZZ=ON \
  -DOBSCURA_BUILD_TESTS=OFF >/dev/null
cmake --build build-fuzz --target obscura-gltf-fuzzer -j"$jobs"

corpus=build-fuzz/corpus
mkdir -p "$corpus"
# Seeds named after their path under glTF2/ (several folders hold a BoxTextured.gltf), so every file seeds.
models=/usr/share/assimp/models/glTF2
find "$models" -type f \( -name '*.gltf' -o -name '*.glb' \) -printf '%P\n' | while IFS= read -r relative; do
  cp -n "$models/$relative" "$corpus/seed-${relative//\//_}"
done
cp -n tests/fuzz/regressions/* "$corpus/"
for seed in tests/fuzz/seeds/*.gltf tests/fuzz/seeds/*.glb; do cp -n "$seed" "$corpus/seed-$(basename "$seed")"; done
cd build-fuzz
./tests/fuzz/obscura-gltf-fuzzer -max_total_time="$seconds" -timeout=10 -rss_limit_mb=4096 -print_final_stats=1 \
  corpus 2>&1 | tail -n 12
