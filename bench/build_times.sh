#!/usr/bin/env bash
# bash bench/build_times.sh [BUILD_DIR]
# The build-time figures of docs/build.md, "Where the time goes", on this machine (run it on a quiet one):
#  1. the tool as `bash .ci/setup.sh run` builds it (target voxcd: no tests, benchmarks, Python module or Verilated
#     models), cold: a new build directory and ccache disabled; wall and CPU seconds;
#  2. three of the heaviest files of the library compiled with the sanitizer build's flags at RelWithDebInfo's
#     -O2 -g against .ci/sanitize.sh's -O1 -g1: CPU seconds each and the ratio of the sums.
# BUILD_DIR (default: a new temporary directory) is removed when done.
set -euo pipefail
cd "$(dirname "$0")/.."
dir="${1:-$(mktemp -d)/build-times}"
trap 'rm -rf "$dir"' EXIT
cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=Release -DVOXCD_TESTS=OFF -DVOXCD_BENCH=OFF -DVOXCD_PYTHON=OFF \
      >/dev/null
TIMEFORMAT="%R %U %S"
t=$( { time CCACHE_DISABLE=1 cmake --build "$dir" -j2 --target voxcd >/dev/null; } 2>&1 )
read -r wall user sys <<<"$t"
echo "tool (target voxcd), cold, -j2: ${wall} s wall, $(awk "BEGIN{print $user + $sys}") s CPU"
asan="-DNDEBUG -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined"
sum_o2=0
sum_o1=0
for f in regress/results_file object/repair scene/simulate; do
  # The library's own compile line for the file, without its launcher, dependency file and optimisation flags.
  base=$(ninja -C "$dir" -t commands "host/CMakeFiles/voxcd_host.dir/$f.cpp.o" | tail -1 |
         sed 's|^[^ ]*ccache ||; s| -o [^ ]*| -o /dev/null|; s| -MD -MT [^ ]* -MF [^ ]*||; s| -O3 -DNDEBUG||')
  o2=$( { time bash -c "$base -O2 -g $asan"; } 2>&1 | awk '{print $2 + $3}')
  o1=$( { time bash -c "$base -O1 -g1 $asan"; } 2>&1 | awk '{print $2 + $3}')
  echo "host/$f.cpp under the sanitizers: -O2 -g ${o2} s CPU, -O1 -g1 ${o1} s CPU"
  sum_o2=$(awk "BEGIN{print $sum_o2 + $o2}")
  sum_o1=$(awk "BEGIN{print $sum_o1 + $o1}")
done
echo "sanitizer build, -O2 -g over -O1 -g1: $(awk "BEGIN{printf \"%.2f\", $sum_o2 / $sum_o1}")x the compile time"
