#!/usr/bin/env bash
# Installs what Obscura needs on a fresh Debian 12 machine, and nothing that is already there.
# Debian packages only (apt); the browser tests' npm packages are installed by tools/test.sh into tests/browser.
set -euo pipefail

packages=(
  # build (ccache: tools/lib/ccache.sh)
  cmake g++ make pkg-config git python3 ccache
  # headless GL (OSMesa and Mesa EGL surfaceless), window GL (GLFW), GLES 2 headers
  libosmesa6-dev libegl-dev libegl-mesa0 libgles-dev libglfw3-dev
  # header-only libraries
  libglm-dev libtinygltf-dev libstb-dev nlohmann-json3-dev
  # compressed glTF geometry (KHR_draco_mesh_compression, EXT_meshopt_compression)
  libdraco-dev libmeshoptimizer-dev
  # tests and tools
  libgtest-dev glslang-tools assimp-testmodels gnuplot-nox
  # sanitizers and fuzzing (clang's runtime)
  clang libclang-rt-14-dev
  # web build, browser tests, desktop viewer test
  emscripten nodejs npm chromium xvfb xauth
  # reference ray tracer
  libembree-dev
)

# Names that installed packages provide count as present: NodeSource's nodejs, for one, provides (and conflicts
# with) Debian's npm, which apt would otherwise try, and fail, to install beside it.
provided=$(dpkg-query -W -f='${db:Status-Abbrev}|${Provides}\n' 2>/dev/null |
           awk -F'|' '$1 ~ /^ii/ { print $2 }' | tr ',' '\n' | sed -e 's/(.*)//' -e 's/ //g' | sort -u)

missing=()
for package in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" &&
     ! grep -qx -- "$package" <<<"$provided"; then
    missing+=("$package")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
$sudo apt-get update -q
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q --no-install-recommends "${missing[@]}"
