#!/usr/bin/env bash
# Runs every test on a fresh Debian machine: installs what is missing, builds the native and the web versions,
# installs the browser tests', the npm package tests', the browser benchmark's and the glTF-Validator's npm packages
# (tests/browser, tests/npm-package, tools/browser-bench and tools/gltf-validator, from their package-lock.json
# files), then runs the whole suite: the glTF corpus against the Khronos glTF-Validator, CPU and GPU unit tests (the
# GPU suites on EGL here, on OSMesa in the sanitizer leg), the command line, the desktop viewer under Xvfb, the
# installed C++ package and its examples, the web page and the npm package in headless Chromium and the browser
# benchmark's smoke run; then the sanitizer leg (tools/test-sanitizers.sh) and the fuzzer (tools/fuzz-gltf.sh). The
# browser tests run as a lane of their own beside the native tests, the sanitizer leg and the fuzzer: they run one at
# a time (one Chromium, RESOURCE_LOCK chromium) and leave a core mostly idle while the page waits on its frames, so
# on two cores the other stages fill it. Ends with a table of each stage's seconds and the wall clock, the 10 slowest
# tests and, when something failed, the failing tests by name (tools/test-report.py); a failing test stage does not
# stop the others.
# Compiles through ccache where it is installed (tools/install-deps.sh installs it): a warm cache makes the builds
# a fraction of the run. While working, `ctest --test-dir build -L cpu` is the fast loop (README, "Tests").
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc 2>/dev/null || echo 2)

stages=$(mktemp)
browser_log=$(mktemp)
started=$(date +%s.%N)
results=build/test-results
junit="$PWD/build/ctest-junit.xml"
browser_junit="$PWD/build/ctest-junit-browser.xml"
browser_lane=""
report() {
  local status=$?
  # Interrupted, or a build failed: the browser lane's ctest ends too (by its parent's PID: the lane alone).
  if [ -n "$browser_lane" ] && kill -0 "$browser_lane" 2>/dev/null; then
    pkill -TERM -P "$browser_lane" || true
    wait "$browser_lane" || true
  fi
  python3 tools/test-report.py "$stages" --junit "$junit" --junit "$browser_junit" \
    --junit "$PWD/build-asan/ctest-junit.xml" --results "$results" --results build-asan/test-results \
    --wall "$(awk -v start="$started" -v end="$(date +%s.%N)" 'BEGIN { printf "%.1f", end - start }')" || true
  # `times` in a command substitution would report the substitution's own subshell: it writes to a file instead.
  times > "$stages.times"
  echo "  (CPU time of everything run: $(tail -n 1 "$stages.times" | awk '{print "user " $1 ", system " $2}'))"
  rm -f "$stages" "$stages.times" "$browser_log"
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

# Every entry but those labelled sanitized (the GPU suites on OSMesa: the sanitizer leg runs those, and this tree runs
# the same suites on EGL; tests/CMakeLists.txt, the labels), in two ctest runs: the browser lane, and the rest.
browser_tests() {
  ctest --test-dir build -L browser -LE sanitized --output-on-failure --output-junit "$browser_junit" -j1
}
native_tests() {
  ctest --test-dir build -LE 'sanitized|browser' --output-on-failure --output-junit "$junit" -j"$jobs"
}

stage "install-deps" tools/install-deps.sh
# Warnings are errors here, so the tree that passes CI builds clean with g++ and with Emscripten's clang.
stage "native build" tools/build.sh -DOBSCURA_WERROR=ON
stage "web build" tools/build-web.sh -DOBSCURA_WERROR=ON
stage "npm ci" npm_ci
rm -rf "$results" "$junit" "$browser_junit" build/test-cache
# The browser lane, in the background; its output follows the other stages'.
stage "ctest: browser lane (beside the next stages)" browser_tests > "$browser_log" 2>&1 &
browser_lane=$!
failed=0
stage "ctest: the rest (native, CLI, viewer, install)" native_tests || failed=1
# One sanitized tree (clang) for the sanitizer leg's tests and the fuzzer.
if stage "sanitized build" tools/test-sanitizers.sh build; then
  stage "sanitizer tests" tools/test-sanitizers.sh run || failed=1
  stage "fuzzer" tools/fuzz-gltf.sh 60 || failed=1
else
  failed=1
fi
lane_status=0
wait "$browser_lane" || lane_status=$?
browser_lane=""
echo "== test.sh: the browser lane's output"
cat "$browser_log"
[ "$lane_status" -eq 0 ] || failed=1
exit "$failed"
