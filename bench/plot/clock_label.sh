#!/usr/bin/env bash
# bench/plot/clock_label.sh FILE.csv: the clock of a benchmark CSV's device rates as a plot label, from the
# "# clock_mhz:" and "# clock_source:" lines the bench programs write first (bench/bench_common.h):
# "100.4 MHz, OpenSTA, OSU 0.18 um, docs/hardware.md" or "150 MHz, given by --clock" ("estimate (docs/hardware.md)" for
# an estimated clock); "clock not stated" without them.
set -euo pipefail
mhz=$(sed -n 's/^# clock_mhz: //p' "$1" | head -n 1)
source=$(sed -n 's/^# clock_source: //p' "$1" | head -n 1)
if [[ -z $mhz ]]; then
  echo "clock not stated"
  exit 0
fi
case $source in estimate*) source="estimate (docs/hardware.md)" ;; esac
echo "$mhz MHz, $source"
