#!/usr/bin/env bash
# CI's smallest configuration (docs/build.md, "Options"): every optional part off (no device models, tests,
# benchmarks or Python module), so that a build without them cannot rot. Builds everything it has into build-min/
# (the libraries and the tool; ccache has most of it from the full build), then runs the tool: the backends that
# need the models must say that this build has none, and the main job must run on the cpu backend.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build-min -G Ninja -DCMAKE_BUILD_TYPE=Release -DVOXCD_DEVICE_MODELS=OFF -DVOXCD_TESTS=OFF \
      -DVOXCD_BENCH=OFF -DVOXCD_PYTHON=OFF >/dev/null
cmake --build build-min -j2
version=$(build-min/voxcd --version)
echo "$version"
for b in rtl sysc-rtl sysc-tlm; do
  echo "$version" | grep -Eq "^  $b +not ready: this build was configured without the device models" ||
    { echo "minimal.sh: voxcd --version does not say that $b needs the device models" >&2; exit 1; }
done
build-min/voxcd simulate --frames 3 --objects 32 | grep "state hash"
