#!/usr/bin/env bash
# Installs the build into a scratch prefix (cmake --install) and builds examples/ against that prefix alone
# (find_package(Obscura COMPONENTS headless glfw) through CMAKE_PREFIX_PATH), warnings as errors. The install.* and
# examples.* tests then run what this leaves in WORK.
# Usage: stage.sh BUILD_DIR SOURCE_DIR WORK_DIR
set -euo pipefail
build=$1 source=$2 work=$3
rm -rf "$work"
mkdir -p "$work"
cmake --install "$build" --prefix "$work/prefix" >"$work/install.log"
# What is installed: the public headers only, under include/obscura/.
if find "$work/prefix/include" -type f | grep -v '/include/obscura/[a-z_]*\.h$'; then
  echo "stage.sh: files outside include/obscura/*.h were installed" >&2
  exit 1
fi
launcher=()
if command -v ccache >/dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
cmake -S "$source/examples" -B "$work/examples" -DCMAKE_PREFIX_PATH="$work/prefix" -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_CXX_FLAGS="-Wall -Wextra -Wpedantic -Wshadow -Werror" "${launcher[@]}" >"$work/examples-configure.log"
cmake --build "$work/examples" -j2
