# Sourced by the build scripts (tools/build.sh, build-web.sh, test-sanitizers.sh, fuzz-gltf.sh): compile through
# ccache where it is installed (tools/install-deps.sh installs it). ccache_cmake_args holds the CMake arguments.
# CCACHE_BASEDIR is the repository root, so paths inside it hash as relative ones and a clone anywhere (CI's fresh
# clone, another worktree) hits the objects another one compiled; CCACHE_NOHASHDIR leaves the working folder out of
# the hash of -g builds for the same reason (their debug info then names the folder that first compiled them).
ccache_cmake_args=()
if command -v ccache >/dev/null 2>&1; then
  export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$PWD}"
  export CCACHE_NOHASHDIR="${CCACHE_NOHASHDIR:-1}"
  ccache_cmake_args=(-DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
fi
