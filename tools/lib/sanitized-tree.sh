# Sourced by tools/test-sanitizers.sh and tools/fuzz-gltf.sh: configures build-asan, the one sanitized tree both use.
# clang with AddressSanitizer (LeakSanitizer included) and UndefinedBehaviorSanitizer, -O1 -g1 (the optimisation the
# ASan docs suggest, and line tables for the reports); OBSCURA_FUZZ adds the libFuzzer target, built from this
# tree's objects (tests/fuzz/CMakeLists.txt). The tests run on OSMesa only (Mesa's EGL driver leaks from a module
# LSan cannot name: docs/robustness.md), without the browser and install entries, with timeouts four times the
# usual (sanitized GPU suites run 2 to 4 times slower).
configure_sanitized_tree() {
  # A tree another compiler configured (an older build-asan made with g++) cannot be switched to clang in place.
  if [ -f build-asan/CMakeCache.txt ] && ! grep -q '^CMAKE_CXX_COMPILER:.*clang++' build-asan/CMakeCache.txt; then
    rm -rf build-asan
  fi
  CC=clang CXX=clang++ cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Debug "-DCMAKE_C_FLAGS_DEBUG=-O1 -g1" \
    "-DCMAKE_CXX_FLAGS_DEBUG=-O1 -g1" -DOBSCURA_SANITIZE=ON -DOBSCURA_FUZZ=ON -DOBSCURA_TEST_BACKENDS=osmesa \
    -DOBSCURA_TEST_BROWSER=OFF -DOBSCURA_TEST_INSTALL=OFF -DOBSCURA_TEST_TIMEOUT_SCALE=4 "${ccache_cmake_args[@]}" \
    >/dev/null
}
