#!/usr/bin/env bash
# Builds and tests every value of every CMake option that CI does not build (docs/build.md, "Options"): one build
# directory each, build-options/<name>/, ccache sharing what they compile alike. CI builds the defaults (setup.sh
# test), the smallest configuration (minimal.sh) and the sanitizer build (sanitize.sh); this covers the rest. Slow
# (each configuration is a build of its own): run it after changing an option or a list of models.
#   bash .ci/options.sh [NAME...]     NAME: models, run, wide, nomodels, nowerror, fuzz (default: all)
# Prints one line per configuration, "options: NAME passed" or "options: NAME FAILED (...)", and exits non-zero
# when one failed.
set -euo pipefail
cd "$(dirname "$0")/.."
export SYSTEMC_DISABLE_COPYRIGHT_MESSAGE=1 CCACHE_BASEDIR="$PWD"
names=("$@")
((${#names[@]})) || names=(models run wide nomodels nowerror fuzz)

configure() {  # configure NAME CMAKE-ARGS...
  local dir=build-options/$1
  shift
  cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
}

failed=0
report() {  # report NAME STATUS
  if [ "$2" = 0 ]; then echo "options: $1 passed"; else echo "options: $1 FAILED (status $2)"; failed=1; fi
}

for name in "${names[@]}"; do
  dir=build-options/$name
  set +e
  case "$name" in
    models)
      # The model lists at their other values: the fewest lane counts each takes (VOXCD_RTL_LANES must include 4),
      # another derived scene, and one more model in every other list. Then every test of the models, slow ones
      # included.
      dist="SB 8 WB 8 LANES 1;SB 8 WB 8 LANES 2;SB 8 WB 8 LANES 4;SB 8 WB 8 LANES 8;SB 4 WB 8 LANES 2"
      banked="LANES 1 BANKS 1;LANES 2 BANKS 2;LANES 4 BANKS 4;LANES 8 BANKS 8;LANES 8 BANKS 2;SB 8 WB 8 LANES 4 BANKS 1"
      depth="LANES 4 DEPTH 1;LANES 4 DEPTH 2;LANES 4 DEPTH 3;LANES 4 DEPTH 4;LANES 4 DEPTH 5;LANES 1 DEPTH 5"
      depth+=";LANES 8 DEPTH 5;LANES 8 BANKS 2 DEPTH 5;SB 8 WB 8 LANES 2 BANKS 2 DEPTH 5;SB 8 WB 8 LANES 1 DEPTH 2"
      axi="LANES 4 AxilDw 32 JobDw 64 RecDw 64;LANES 2 AxilDw 64 JobDw 1024 RecDw 256 DEPTH 5"
      sysc_dist="SB 8 WB 8 LANES 4;SB 4 WB 8 LANES 2;SB 16 WB 8 LANES 1"
      (configure models -DVOXCD_RTL_LANES=4 -DVOXCD_SYSC_LANES=1 -DVOXCD_RTL_CONFIGS=paper.json \
         "-DVOXCD_RTL_DIST_MODELS=$dist;SB 16 WB 8 LANES 1;SB 4 WB 4 LANES 1" \
         "-DVOXCD_RTL_BANKED_MODELS=$banked;LANES 2 BANKS 1" "-DVOXCD_RTL_DEPTH_MODELS=$depth;LANES 2 DEPTH 3" \
         "-DVOXCD_AXI_MODELS=$axi;LANES 1 AxilDw 32 JobDw 8 RecDw 8" \
         "-DVOXCD_SYSC_DIST_MODELS=$sysc_dist;SB 8 WB 8 LANES 1" "-DVOXCD_SYSC_AXI_PAIRS=LANES 2" \
         "-DVOXCD_SYSC_BANKED_MODELS=LANES 4 BANKS 4;LANES 2 BANKS 1" \
         "-DVOXCD_SYSC_DEPTH_MODELS=LANES 4 DEPTH 5;LANES 1 DEPTH 2" &&
       cmake --build "$dir" -j2 &&
       (cd "$dir" && ctest -j2 --output-on-failure -L "rtl|sysc|axi|dpi|backends|python|install"))
      ;;
    run)
      # What `bash .ci/setup.sh run` configures: the models but no tests, benchmarks or Python module. The tool
      # builds without the models; then the one command makes the rtl and sysc backends ready.
      (configure run -DVOXCD_TESTS=OFF -DVOXCD_BENCH=OFF -DVOXCD_PYTHON=OFF &&
       cmake --build "$dir" -j2 --target voxcd &&
       "$dir/voxcd" --version | grep -Eq "^  rtl +not ready: the RTL models are not built" &&
       cmake --build "$dir" -j2 --target voxcd_models &&
       "$dir/voxcd" --version | grep -Eq "^  sysc-rtl +ready" &&
       "$dir/voxcd" simulate --frames 20 --objects 16 --backend rtl | grep "state hash" &&
       cmake --build "$dir" -j2)
      ;;
    wide)
      # The full-size wide devices (VOXCD_RTL_WIDE, docs/hardware.md "Wide devices"): their tests, and the main job
      # on the 32-lane device against the cpu backend's state hash and device cycles.
      (configure wide -DVOXCD_RTL_WIDE=ON -DVOXCD_BENCH=OFF -DVOXCD_PYTHON=OFF &&
       cmake --build "$dir" -j2 --target voxcd voxcd_models test_rtl test_backends &&
       (cd "$dir" && ctest -j2 --output-on-failure -R "RtlWide|conform_wide|Simulate.Wide") &&
       a=$("$dir/voxcd" simulate --objects 1024 --frames 100 --lanes 32 --backend cpu --no-progress | grep -E "^(device|state hash)" | sed 's/(.*)//') &&
       b=$("$dir/voxcd" simulate --objects 1024 --frames 100 --lanes 32 --backend rtl --no-progress | grep -E "^(device|state hash)" | sed 's/(.*)//') &&
       [ "$a" = "$b" ])
      ;;
    nomodels)
      # No device models, with the tests (the sanitizer build has this too, under ASan): every test it has.
      (configure nomodels -DVOXCD_DEVICE_MODELS=OFF && cmake --build "$dir" -j2 &&
       (cd "$dir" && ctest -j2 --output-on-failure -LE slow))
      ;;
    nowerror)
      # Warnings not errors, no models: the build must still be warning-free, so this only has to build.
      (configure nowerror -DVOXCD_WERROR=OFF -DVOXCD_DEVICE_MODELS=OFF && cmake --build "$dir" -j2)
      ;;
    fuzz)
      # The libFuzzer build (clang), both sanitizer sets, a thousand executions of every target.
      (bash tests/fuzz/run.sh 1000 && FUZZ_SANITIZERS=leak,undefined bash tests/fuzz/run.sh 1000)
      ;;
    *) echo "options.sh: unknown configuration $name (models, run, wide, nomodels, nowerror, fuzz)" >&2; exit 2 ;;
  esac
  status=$?
  set -e
  report "$name" "$status"
done
exit "$failed"
