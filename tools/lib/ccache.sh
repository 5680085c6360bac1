# Sourced by the build scripts (tools/build.sh, build-web.sh, test-sanitizers.sh, fuzz-gltf.sh): compile through
# ccache where it is installed (tools/install-deps.sh installs it). ccache_cmake_args holds the CMake arguments.
# CCACHE_BASEDIR is the repository root, so paths inside it hash as relative ones and a clone anywhere (CI's fresh
# clone, another worktree) hits the objects another one compiled; CCACHE_NOHASHDIR leaves the working folder out of
# the hash of -g builds for the same reason (their debug info then names the folder that first compiled them).
ccache_cmake_args=()
if command -v ccache >/dev/null 2>&1; then
  export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$PWD}"
  export CCACHE_NOHASHDIR="${CCACHE_NOHASHDIR:-1}"
  # The test binaries' precompiled headers (tests/CMakeLists.txt): without this sloppiness ccache declines every
  # source compiled with one (ccache's manual, "Precompiled headers"); the .gch it reads is hashed like any header.
  export CCACHE_SLOPPINESS="${CCACHE_SLOPPINESS:-pch_defines,time_macros}"
  ccache_cmake_args=(-DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
fi
