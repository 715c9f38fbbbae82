#!/usr/bin/env bash
# Sets up voxcd on Debian 12 and runs it: installs the Debian packages it needs when missing (as root, or
# through sudo), configures build/, builds what the command needs, then
#   bash .ci/setup.sh run [simulate options]   builds the tool (not the device models) and runs the main job on its
#                                              built-in default; with --backend rtl|sysc-rtl|sysc-tlm (or a scene
#                                              file naming one) it builds the device models too
#   bash .ci/setup.sh test [ctest options]      builds everything and runs the whole test suite (ctest)
# docs/build.md says what each builds and how long it takes.
set -euo pipefail
cd "$(dirname "$0")/.."
# Each phase's wall time on standard error, so that a slow step shows (docs/build.md has measured figures).
phase_start=$SECONDS
phase() { echo "setup.sh: $1 took $((SECONDS - phase_start)) s" >&2; phase_start=$SECONDS; }
mode="${1:-run}"
[ $# -gt 0 ] && shift
case "$mode" in
  run | test) ;;
  *) echo "usage: bash .ci/setup.sh run|test [options]" >&2; exit 2 ;;
esac

# What the tool and the device models need; the tests, benchmarks and the Python module need the rest.
run_pkgs=(cmake ninja-build g++ pkg-config ccache libeigen3-dev libcli11-dev zlib1g-dev libassimp-dev
          nlohmann-json3-dev libopenmpi-dev openmpi-bin verilator libsystemc-dev libjs-three)
test_pkgs=(libgtest-dev lcov libfcl-dev libbullet-dev libopenvdb-dev libboost-iostreams-dev assimp-testmodels yosys
           qflow-tech-osu018 pybind11-dev python3-pybind11 python3-numpy python3-pytest python3-dev chromium nodejs npm)
pkgs=("${run_pkgs[@]}")
[ "$mode" = test ] && pkgs+=("${test_pkgs[@]}")
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
  phase "installing ${#missing[@]} packages"
fi

# `test` builds everything; `run` configures a new build/ without the tests, benchmarks and Python module (whose
# packages it did not install) and leaves an existing build/ as it is.
parts=()
if [ "$mode" = test ]; then
  parts=(-DVOXCD_TESTS=ON -DVOXCD_BENCH=ON -DVOXCD_PYTHON=ON)
elif [ ! -f build/CMakeCache.txt ]; then
  parts=(-DVOXCD_TESTS=OFF -DVOXCD_BENCH=OFF -DVOXCD_PYTHON=OFF)
fi
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release "${parts[@]}" >/dev/null
phase "configuring build/"

# The backends that load the device models (docs/build.md, "The device models").
needs_models() {
  local prev=""
  for a in "$@"; do
    case "$prev $a" in
      "--backend rtl" | "--backend sysc-rtl" | "--backend sysc-tlm") return 0 ;;
    esac
    case "$a" in
      --backend=rtl | --backend=sysc-rtl | --backend=sysc-tlm) return 0 ;;
      *.json) [ -f "$a" ] && grep -Eq '"backend"[[:space:]]*:[[:space:]]*"(rtl|sysc-rtl|sysc-tlm)"' "$a" && return 0 ;;
    esac
    prev=$a
  done
  return 1
}

# A wide device (more than 8 lanes: --lanes, or LANES in --config): its full-size model is built on demand
# (-DVOXCD_RTL_WIDE=ON, docs/build.md "Options").
needs_wide() {
  local prev=""
  for a in "$@"; do
    case "$prev" in
      --lanes) [ "$a" -gt 8 ] 2>/dev/null && return 0 ;;
      --config) [[ "$a" =~ LANES\ +([0-9]+) ]] && [ "${BASH_REMATCH[1]}" -gt 8 ] && return 0 ;;
    esac
    case "$a" in
      --lanes=*) [ "${a#--lanes=}" -gt 8 ] 2>/dev/null && return 0 ;;
    esac
    prev=$a
  done
  return 1
}

case "$mode" in
  run)
    targets=(voxcd)
    if needs_models "$@"; then targets+=(voxcd_models); fi
    if needs_models "$@" && needs_wide "$@"; then
      cmake -S . -B build -DVOXCD_RTL_WIDE=ON >/dev/null
    fi
    cmake --build build -j2 --target "${targets[@]}"
    phase "building ${targets[*]}"
    exec build/voxcd simulate "$@"
    ;;
  test)
    cmake --build build -j2
    phase "building everything"
    cd build && exec ctest -j2 --output-on-failure "$@"
    ;;
esac
