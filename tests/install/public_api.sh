#!/usr/bin/env bash
# The public API surface against the installed package only:
#   1. each public header compiles on its own, and includes nothing but the standard library and obscura/ headers
#      (no GL header, no internal one);
#   2. api_surface.cpp, which names every public declaration, builds with the flags pkg-config gives
#      (obscura-headless and obscura-glfw, which require obscura) and runs.
# Usage: public_api.sh SOURCE_DIR WORK_DIR (after stage.sh)
set -euo pipefail
source=$1 work=$2
prefix="$work/prefix"
cxx=${CXX:-c++}
flags=(-std=c++17 -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Werror)
for header in "$prefix"/include/obscura/*.h; do
  name=$(basename "$header")
  if grep -E '^#include' "$header" | grep -vE '^#include (<[a-z_]+>|"obscura/[a-z_]+\.h")$'; then
    echo "public_api.sh: $name includes something outside the standard library and obscura/" >&2
    exit 1
  fi
  echo "#include <obscura/$name>" | "$cxx" "${flags[@]}" -I"$prefix/include" -x c++ -fsyntax-only -
done
export PKG_CONFIG_PATH="$prefix/lib/pkgconfig"
pkg-config --exists --print-errors "obscura-headless = $(pkg-config --modversion obscura)" obscura-glfw
# shellcheck disable=SC2046 # word splitting of pkg-config's output is intended
"$cxx" "${flags[@]}" "$source/tests/install/api_surface.cpp" -o "$work/api_surface" \
       $(pkg-config --cflags --libs obscura-headless obscura-glfw)
"$work/api_surface" "$prefix"
