#!/usr/bin/env bash
# CI's sanitizer step, run after `bash .ci/setup.sh test` (which installs the packages): the test suite built with
# AddressSanitizer (leaks included) and UndefinedBehaviorSanitizer into build-asan/, without the Verilated RTL and
# SystemC models (VOXCD_DEVICE_MODELS=OFF: their suites drive generated code, and building them with ASan would take
# longer than CI allows). Runs every test of that build but the ones labelled slow: ref, backends (ref and cpu),
# host, cli and the fuzz regressions. Any sanitizer report fails the run. docs/robustness.md, "Sanitizers".
set -euo pipefail
cd "$(dirname "$0")/.."
# -O1 -g1: about half the compile time of RelWithDebInfo's -O2 -g under the sanitizers, and reports still name
# every frame's file and line (docs/build.md, "Where the time goes").
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
      -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" -DVOXCD_SANITIZE=ON -DVOXCD_DEVICE_MODELS=OFF -DVOXCD_BENCH=OFF >/dev/null
# Everything this configuration has: the libraries, the tool, the Python module and the tests (no benchmarks).
cmake --build build-asan -j2
# UBSan stops at the first error (the build also has -fno-sanitize-recover); LeakSanitizer runs at every exit, with
# the one suppression tests/lsan.supp explains (a leak inside assimp 5.2.5).
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_init_order=1:detect_stack_use_after_return=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
export LSAN_OPTIONS="suppressions=$PWD/tests/lsan.supp:print_suppressions=0"
export SYSTEMC_DISABLE_COPYRIGHT_MESSAGE=1
# Left out as well: the rtl-labelled tests this build still has (they need the Verilated models), and the browser
# tests (a real browser driving the tool's page: their C++ side, the recordings, is tested here by host.Record.*), and
# the heavy ones (a minute or more under the sanitizers, seconds in the other builds, which run them).
cd build-asan && exec ctest -j2 --output-on-failure -LE "slow|rtl|browser|heavy" "$@"
