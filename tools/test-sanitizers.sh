#!/usr/bin/env bash
# The sanitizer leg of the test suite: a separate tree (build-asan, tools/lib/sanitized-tree.sh) built by clang with
# AddressSanitizer, LeakSanitizer and UndefinedBehaviorSanitizer runs, through ctest, every entry labelled cpu or cli
# and the GPU entries labelled sanitized (README, "Tests"): the CPU tests (loader, glTF corpus, fuzzer regressions,
# animation, compression, environment), the GPU suites on OSMesa (every effect, PBR, skinning, the environment, the
# viewer session, the AO's depth layers, temporal AO, the accuracy suites), the page's C++ side built natively
# (web_api.*), the public API (api.surface), the ray-traced reference and the command-line tools (each run of
# obscura-render, -reference and -compare is sanitized too); then two command-line runs of its own. Any sanitizer
# report, and any leak outside the third-party suppressions in tests/lsan.supp, fails it. tools/test.sh runs the
# entries labelled sanitized here only: its plain tree runs the same GPU suites on EGL.
#   tools/test-sanitizers.sh [build|run]      default: both
# Left out: the EGL backend (Mesa's EGL driver leaks from a module LSan cannot name: docs/robustness.md), the browser
# and install entries (no web build here; an installed sanitized library would need the runtimes in its consumers),
# the desktop viewer under Xvfb, the largest render size and the benchmark's smoke run (viewer.*, limits.*, label
# smoke).
set -euo pipefail
cd "$(dirname "$0")/.."
source tools/lib/ccache.sh
source tools/lib/sanitized-tree.sh
jobs=$(nproc 2>/dev/null || echo 2)
mode="${1:-all}"

if [ "$mode" = build ] || [ "$mode" = all ]; then
  configure_sanitized_tree
  # The tests' binaries and the tools they run, and the fuzzer (tools/fuzz-gltf.sh) from the same objects.
  cmake --build build-asan -j"$jobs" --target obscura_cpu_tests obscura_gpu_tests obscura_temporal_ao_tests \
    obscura_ao_layers_tests obscura_reference_tests obscura_accuracy_tests obscura_web_api_tests obscura_api_surface \
    obscura_cli_tests obscura-shaders obscura-hdr-study obscura-gltf-check obscura-gltf-fuzzer
fi
[ "$mode" = run ] || [ "$mode" = all ] || exit 0

export ASAN_OPTIONS="detect_leaks=1:abort_on_error=0:halt_on_error=1:strict_string_checks=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
export LSAN_OPTIONS="suppressions=$PWD/tests/lsan.supp:print_suppressions=0"

echo "test-sanitizers: the cpu, cli and sanitized (GPU on OSMesa) entries"
rm -rf build-asan/test-results build-asan/test-cache
ctest --test-dir build-asan -L 'cpu|cli|sanitized' -LE smoke --output-on-failure \
  --output-junit "$PWD/build-asan/ctest-junit.xml" -j"$jobs"

echo "test-sanitizers: a render and a refused file through the command line"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
build-asan/obscura-render --size 160x90 --out "$out/render.png"
status=0
build-asan/obscura-render --scene /usr/share/assimp/models/glTF2/IndexOutOfRange/IndexOutOfRange.gltf \
  --out "$out/never.png" 2>"$out/err" || status=$?
if [ "$status" -ne 2 ]; then
  echo "test-sanitizers: expected exit status 2 for a malformed file, got $status"; cat "$out/err"; exit 1
fi
echo "test-sanitizers: clean (ASan, LSan, UBSan)"
