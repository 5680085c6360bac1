#!/usr/bin/env bash
# Obscura's native benchmarks on a machine with a GPU but none of this project's packages: the device machine a task
# may be lent (an NVIDIA GPU, its driver's EGL, no network). Two halves:
#
#   tools/device-bench.sh prepare   here (Debian, after tools/build.sh): gathers into .device/ (ignored by git) the
#                                   release binaries, the shared libraries a bare machine lacks (draco, meshoptimizer,
#                                   glvnd's EGL loader), a stand-in for libOSMesa (the binaries link it; on the GPU only
#                                   --backend egl runs) and Debian's glTF test models (the engine the benchmarks
#                                   read, the files the GPU suite loads).
#   tools/device-bench.sh tests [OUT]
#                                   there: the GPU test suite (obscura_gpu_tests) on the GPU's EGL context, as ctest's
#                                   gpu.egl entries run it on Mesa; OUT/gpu-tests.txt, OUT/gpu-tests.xml (JUnit) and
#                                   OUT/frames (the frames some tests compare). About four minutes on an H200 (the
#                                   shader test compiling every variant takes half); GTEST_FILTER=... runs a part.
#   tools/device-bench.sh run [OUT] there, in the repository's root (.device carried): fails within seconds if EGL
#                                   gives no GPU context, then runs, each under its own time limit, the AO layers' and
#                                   normals' costs (obscura-bench section 12, issue 30), the browser benchmark's Obscura
#                                   configurations and the lighting's choices (tools/gpu-lighting-bench.sh, issue 26),
#                                   the full obscura-bench run, and its alone-only sections (lighting, culling,
#                                   transparency). Writes OUT/log.txt (each step's time and status), OUT/<step>.txt
#                                   (its output) and OUT/results.tar.gz (every CSV); OUT defaults to $OUT or
#                                   /tmp/device-bench; FRAMES (default 30) frames a figure. About two minutes on an
#                                   H200 (90 s at 30 frames, 115 s at 60).
#
# docs/benchmarks.md ("On a GPU") has the figures and what carries over from the CPU rasterisers.
set -uo pipefail
cd "$(dirname "$0")/.."
here=$PWD
mode=${1:-}

prepare() {
  set -e
  cmake --build build --target obscura-bench obscura-render obscura_gpu_tests -j"$(nproc)" >/dev/null
  rm -rf .device
  mkdir -p .device/bin .device/lib .device/models
  # The test binaries that need no Embree (its library alone is 43 MB): the GPU suite.
  cp build/obscura-bench build/obscura-render build/tests/obscura_gpu_tests .device/bin/
  strip .device/bin/*
  local lib=/lib/x86_64-linux-gnu
  cp -L "$lib/libdraco.so.7" "$lib/libmeshoptimizer.so.2d" "$lib/libEGL.so.1" "$lib/libGLdispatch.so.0" .device/lib/
  # The binaries link libOSMesa (the CPU backend), whose LLVM alone is larger than a device call may carry; there the
  # EGL backend runs, so a library that only says so stands in for it.
  cat > .device/osmesa-stand-in.c <<'EOF'
#include <stddef.h>
#include <stdio.h>
static void *unavailable(void) { fprintf(stderr, "OSMesa is not on this machine: use --backend egl\n"); return NULL; }
void *OSMesaCreateContextAttribs(const int *attributes, void *share) {
  (void)attributes; (void)share; return unavailable();
}
void OSMesaDestroyContext(void *context) { (void)context; }
unsigned char OSMesaMakeCurrent(void *c, void *b, unsigned t, int w, int h) {
  (void)c; (void)b; (void)t; (void)w; (void)h; return 0;
}
void *OSMesaGetProcAddress(const char *name) { (void)name; return NULL; }
EOF
  cc -shared -fPIC -O2 -Wl,-soname,libOSMesa.so.8 -o .device/lib/libOSMesa.so.8 .device/osmesa-stand-in.c
  # Debian's glTF test models (3 MB): the engine the benchmarks read and the files the GPU suite loads.
  cp -rL /usr/share/assimp/models/glTF2 .device/models/
  grep -qx '/.device/' .git/info/exclude 2>/dev/null || echo '/.device/' >> .git/info/exclude
  # The binaries read the source tree (assets/) and the engine by the absolute paths they were built with.
  grep -m1 '^CMAKE_HOME_DIRECTORY' build/CMakeCache.txt | cut -d= -f2 > .device/source-dir
  local commit
  commit=$(git rev-parse --short HEAD)
  [ -z "$(git status --porcelain --untracked-files=no)" ] || commit="$commit with uncommitted changes"
  echo "$commit" > .device/commit
  du -sh .device
}

# The device machine's GPU through its EGL, the binaries' absolute paths made to resolve there.
use_device_gpu() {
  local nvidia=/usr/local/nvidia
  export LD_LIBRARY_PATH=$here/.device/lib:$nvidia/lib64:$nvidia/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
  local vendor=$nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
  [ -f "$vendor" ] && export __EGL_VENDOR_LIBRARY_FILENAMES=$vendor
  local source_dir
  source_dir=$(cat .device/source-dir)
  if [ "$source_dir" != "$here" ] && [ ! -e "$source_dir" ]; then
    mkdir -p "$(dirname "$source_dir")" && ln -s "$here" "$source_dir"
  fi
  if [ ! -d /usr/share/assimp/models/glTF2 ]; then
    mkdir -p /usr/share/assimp/models && cp -r .device/models/glTF2 /usr/share/assimp/models/
  fi
}

tests() {
  local out=${1:-${OUT:-/tmp/device-bench}}
  mkdir -p "$out"
  use_device_gpu
  # OBSCURA_TEST_DUMP: the tests that can write the frames they compare (depth of field, motion blur) do so, to look
  # at here (a device call brings back a few files: keep those of the test in question).
  mkdir -p "$out/frames"
  OBSCURA_TEST_DUMP=$out/frames OBSCURA_TEST_BACKEND=egl timeout 300 .device/bin/obscura_gpu_tests \
    --gtest_output="xml:$out/gpu-tests.xml" > "$out/gpu-tests.txt" 2>&1
  local status=$?
  grep -E '^\[  (PASSED|FAILED) |tests? ran|^\[  SKIPPED \] [0-9]' "$out/gpu-tests.txt"
  return "$status"
}

run() {
  local out=${1:-${OUT:-/tmp/device-bench}}
  local frames=${FRAMES:-30}
  mkdir -p "$out"
  local log=$out/log.txt
  local results=/tmp/device-bench-results
  rm -rf "$results" && mkdir -p "$results"
  use_device_gpu
  {
    echo "device-bench: $(date -u +%Y-%m-%dT%H:%M:%SZ), binaries of $(cat .device/commit), $frames frames a figure"
    nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm --format=csv,noheader 2>&1 | head -2
    echo "cpu: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2)"
  } > "$log"
  local bin=$here/.device/bin
  step() {  # step NAME SECONDS COMMAND...: its output in OUT/NAME.txt, its time and status in the log
    local name=$1 limit=$2
    shift 2
    local start status
    start=$(date +%s%N)
    timeout "$limit" "$@" > "$out/$name.txt" 2>&1
    status=$?
    printf '%-14s rc=%-3s %6d ms\n' "$name" "$status" $(( ($(date +%s%N) - start) / 1000000 )) >> "$log"
    (cd "$results" && tar czf "$out/results.tar.gz" .)
    return "$status"
  }
  # A GPU context, or stop at once (the device's time is short): one small frame, its renderer's name printed.
  if ! step egl-check 60 "$bin/obscura-render" --backend egl --size 320x180 --bench 2 \
      --out "$results/egl-check.png"; then
    { echo "no EGL context on the GPU:"; tail -5 "$out/egl-check.txt"
      ls /usr/share/glvnd/egl_vendor.d /usr/local/nvidia/share/glvnd/egl_vendor.d /usr/local/nvidia/lib64 2>&1 | head -40
    } >> "$log"
    return 1
  fi
  grep -m1 'backend egl' "$out/egl-check.txt" >> "$log"
  step ao-layers 90 "$bin/obscura-bench" --backend egl --frames "$frames" --ao-layers-only --out "$results/ao-layers"
  step lighting-cli 150 bash tools/gpu-lighting-bench.sh "$bin" "$frames"
  step full 180 "$bin/obscura-bench" --backend egl --frames "$frames" --out "$results/full"
  step lighting 60 "$bin/obscura-bench" --backend egl --frames "$frames" --lighting-only --out "$results/alone"
  step culling 45 "$bin/obscura-bench" --backend egl --frames "$frames" --culling-only --out "$results/alone"
  step transparency 45 "$bin/obscura-bench" --backend egl --frames "$frames" --transparency-only --out "$results/alone"
  echo "done $(date -u +%H:%M:%SZ)" >> "$log"
}

case "$mode" in
  prepare) prepare ;;
  run) shift; run "$@" ;;
  tests) shift; tests "$@" ;;
  *) echo "usage: tools/device-bench.sh prepare | run [OUT] | tests [OUT]" >&2; exit 2 ;;
esac
