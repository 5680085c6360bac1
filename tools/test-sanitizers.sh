#!/usr/bin/env bash
# The sanitizer leg of the test suite: a separate tree (build-asan) built with AddressSanitizer, LeakSanitizer and
# UndefinedBehaviorSanitizer runs the CPU tests (loader and glTF corpus included), the GPU tests on OSMesa, and a
# command-line render. Any sanitizer report, and any leak outside the third-party suppressions in tests/lsan.supp,
# fails it.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc 2>/dev/null || echo 2)
# -O1 -g1, as the AddressSanitizer docs suggest: line tables are enough for symbolised reports, and the build takes
# half the time of -O2 -g (3 against 6 minutes on 2 cores), which is most of this leg.
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Debug "-DCMAKE_C_FLAGS_DEBUG=-O1 -g1" "-DCMAKE_CXX_FLAGS_DEBUG=-O1 -g1" \
  -DOBSCURA_SANITIZE=ON >/dev/null
cmake --build build-asan --target obscura_cpu_tests obscura_gpu_tests obscura-render -j"$jobs"

export ASAN_OPTIONS="detect_leaks=1:abort_on_error=0:halt_on_error=1:strict_string_checks=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
export LSAN_OPTIONS="suppressions=$PWD/tests/lsan.supp:print_suppressions=0"
export OBSCURA_TEST_BACKEND=osmesa

echo "test-sanitizers: CPU tests"
build-asan/tests/obscura_cpu_tests --gtest_brief=1
echo "test-sanitizers: GPU tests (OSMesa)"
build-asan/tests/obscura_gpu_tests --gtest_brief=1
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
