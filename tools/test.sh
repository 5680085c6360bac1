#!/usr/bin/env bash
# Runs every test on a fresh Debian machine: installs what is missing, builds the native and the web versions,
# installs the browser tests', the npm package tests', the browser benchmark's and the glTF-Validator's npm packages
# (tests/browser, tests/npm-package, tools/browser-bench and tools/gltf-validator, from their package-lock.json
# files), then runs the whole suite: the glTF corpus against the Khronos glTF-Validator, CPU and GPU unit tests (the
# GPU suites on EGL here, on OSMesa in the sanitizer leg), the command line, the desktop viewer under Xvfb, the
# installed C++ package and its examples, the web page and the npm package in headless Chromium and the browser
# benchmark's smoke run; then the sanitizer leg (tools/test-sanitizers.sh) and the fuzzer (tools/fuzz-gltf.sh). Ends
# with a table of each stage's seconds, the 10 slowest tests and, when something failed, the failing tests by name
# (tools/test-report.py).
# Compiles through ccache where it is installed (tools/install-deps.sh installs it): a warm cache makes the builds
# a fraction of the run. While working, `ctest --test-dir build -L cpu` is the fast loop (README, "Tests").
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc 2>/dev/null || echo 2)

stages=$(mktemp)
results=build/test-results
junit="$PWD/build/ctest-junit.xml"
report() {
  local status=$?
  python3 tools/test-report.py "$stages" --junit "$junit" --junit "$PWD/build-asan/ctest-junit.xml" \
    --results "$results" --results build-asan/test-results || true
  # `times` in a command substitution would report the substitution's own subshell: it writes to a file instead.
  times > "$stages.times"
  echo "  (CPU time of everything run: $(tail -n 1 "$stages.times" | awk '{print "user " $1 ", system " $2}'))"
  rm -f "$stages" "$stages.times"
  exit "$status"
}
trap report EXIT

# Runs "$@" as the stage $1 (the rest is the command), timing it.
stage() {
  local name="$1" start status=0
  shift
  start=$(date +%s.%N)
  echo "== test.sh: $name"
  "$@" || status=$?
  awk -v name="$name" -v start="$start" -v end="$(date +%s.%N)" -v status="$status" \
    'BEGIN { printf "%s\t%.1f\t%d\n", name, end - start, status }' >> "$stages"
  return "$status"
}

npm_ci() {
  for folder in tests/browser tools/browser-bench tests/npm-package tools/gltf-validator; do
    (cd "$folder" && npm ci --no-audit --no-fund --loglevel=error)
  done
}

# Every entry but those labelled sanitized (the GPU suites on OSMesa): the sanitizer leg runs those, and this tree runs
# the same suites on EGL (tests/CMakeLists.txt, the labels).
native_tests() {
  rm -rf "$results" "$junit" build/test-cache
  ctest --test-dir build -LE sanitized --output-on-failure --output-junit "$junit" -j"$jobs"
}

stage "install-deps" tools/install-deps.sh
# Warnings are errors here, so the tree that passes CI builds clean with g++ and with Emscripten's clang.
stage "native build" tools/build.sh -DOBSCURA_WERROR=ON
stage "web build" tools/build-web.sh -DOBSCURA_WERROR=ON
stage "npm ci" npm_ci
stage "ctest (native, web)" native_tests
# One sanitized tree (clang) for the sanitizer leg's tests and the fuzzer.
stage "sanitized build" tools/test-sanitizers.sh build
stage "sanitizer tests" tools/test-sanitizers.sh run
stage "fuzzer" tools/fuzz-gltf.sh 60
