#!/usr/bin/env bash
# Sets up voxcd on Debian 12 and runs it: installs the Debian packages it needs when missing (as root, or
# through sudo), configures and builds into build/, then
#   bash .ci/setup.sh run   runs the main job on its built-in default
#   bash .ci/setup.sh test  runs the whole test suite (ctest)
set -euo pipefail
cd "$(dirname "$0")/.."
mode="${1:-run}"
[ $# -gt 0 ] && shift

pkgs=(cmake ninja-build g++ pkg-config ccache verilator libsystemc-dev libgtest-dev libeigen3-dev libcli11-dev
      zlib1g-dev libassimp-dev libfcl-dev libbullet-dev nlohmann-json3-dev libopenvdb-dev libboost-iostreams-dev
      assimp-testmodels yosys qflow-tech-osu018 pybind11-dev python3-pybind11 python3-numpy python3-pytest python3-dev
      openmpi-bin libopenmpi-dev chromium libjs-three nodejs npm)
missing=()
for p in "${pkgs[@]}"; do
  # A node.js from elsewhere may bring its own npm (and conflict with Debian's): the command is what is needed.
  [ "$p" = npm ] && command -v npm >/dev/null && continue
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "installing: ${missing[*]}"
  sudo=""
  [ "$(id -u)" = 0 ] || sudo=sudo
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j2

case "$mode" in
  run) exec build/voxcd simulate "$@" ;;
  test) cd build && exec ctest -j2 --output-on-failure "$@" ;;
  *) echo "usage: bash .ci/setup.sh run|test" >&2; exit 2 ;;
esac
