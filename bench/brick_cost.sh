#!/usr/bin/env bash
# bench/brick_cost.sh: what a lane costs with and without its multipliers (docs/hardware.md, "Brick lanes"), as a
# Markdown fragment on stdout. yosys maps one voxcd_lane (a sparse lane, BL 3, of a device with shared banks: no voxmap
# copy of its own) and the device's transform unit's share onto the OSU 0.18 um standard cells of Debian's
# qflow-tech-osu018, as bench/timing.sh and `voxcd size --cost` do (host/sizing/asic_cost.cpp: Kogge-Stone adders,
# ABC mapping for a 200 MHz period): the lane that multiplies (TX 0) against the brick lane (TX 1), at depth 0 and at
# the deepest depth, with each one's standard-cell area, cells, flip-flops and ABC's own delay estimate (stime) of
# its longest path. Needs yosys and qflow-tech-osu018; about 10 minutes on one core.
# Usage: bash bench/brick_cost.sh [--depths 0,5] [> cost.md]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
depths=0,5
if [ "${1:-}" = "--depths" ]; then depths=$2; fi
lib=/usr/share/qflow/tech/osu018/osu018_stdcells.lib
command -v yosys >/dev/null || { echo "brick_cost.sh needs yosys (Debian package yosys)" >&2; exit 1; }
[ -f "$lib" ] || { echo "brick_cost.sh needs $lib (Debian package qflow-tech-osu018)" >&2; exit 1; }
mapfile -t rtl_files < <(grep -v -e "^[[:space:]]*//" -e "^[[:space:]]*$" -e "\.vlt[[:space:]]*$" "$root/rtl/voxcd.f")
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for f in "${rtl_files[@]}"; do cp "$root/rtl/$f" "$tmp/$f"; done
cp "$root/host/sizing/kogge_stone.v" "$tmp/"
cd "$tmp"
abc_script="+strash;&get,-n;&fraig,-x;&put;dc2;strash;&get,-n;&dch,-f;&nf,{D};&put;buffer,-N,12;upsize,{D};dnsize,{D};stime,-p"

# lane TX DEPTH: the lane's area in um^2, cells, flip-flops and ABC's delay estimate in ps, on one line.
lane() {
  local log=lane_tx$1_d$2.log
  yosys -q -l "$log" -p "read_verilog -sv ${rtl_files[*]}; chparam -set BL 3 -set TX $1 -set Depth $2 -set SharedMap 1 \
    voxcd_lane; hierarchy -top voxcd_lane; proc; rename -top voxcd_lane; \
    synth -top voxcd_lane -flatten -run begin:fine; opt -fast -full; memory_map; opt -full; \
    techmap -map +/techmap.v -map kogge_stone.v; opt -fast; abc -fast; opt -fast; synth -top voxcd_lane -run check:; \
    dfflibmap -liberty $lib; abc -liberty $lib -D 5000 -script \"$abc_script\"; opt_clean -purge; \
    tee -o area.txt stat -liberty $lib" >/dev/null 2>&1
  local area cells ffs delay
  area=$(awk '/Chip area for (top )?module/ { a = $NF } END { print a }' area.txt)
  cells=$(awk '/Number of cells:/ { n = $NF } END { print n }' area.txt)
  ffs=$(awk '$1 ~ /^DFF/ && $2 ~ /^[0-9]+$/ { n += $2 } END { print n + 0 }' area.txt)
  delay=$(grep -o "Delay = *[0-9.]* ps" "$log" | tail -1 | grep -o "[0-9.]*" | head -1)
  echo "$area $cells $ffs ${delay:--}"
}

echo "| depth | lane | area (mm^2) | cells | flip-flops | ABC's longest path (ns) |"
echo "|--:|---|--:|--:|--:|--:|"
IFS=, read -r -a ds <<< "$depths"
for d in "${ds[@]}"; do
  for tx in 0 1; do
    read -r area cells ffs delay < <(lane "$tx" "$d")
    name=$([ "$tx" = 1 ] && echo "brick lane (TX 1)" || echo "lane that multiplies (TX 0)")
    ns=$([ "$delay" = - ] && echo - || awk -v p="$delay" 'BEGIN { printf "%.2f", p / 1000 }')
    awk -v d="$d" -v n="$name" -v a="$area" -v c="$cells" -v f="$ffs" -v t="$ns" \
      'BEGIN { printf "| %s | %s | %.4f | %s | %s | %s |\n", d, n, a / 1e6, c, f, t }'
  done
done
echo
echo "One voxcd_lane of a sparse device (BL 3) with shared voxmap banks (SharedMap: no voxmap copy), the default widths"
echo "(PW 24 MW 18: nine 18 x 24-bit products a lane that multiplies); a brick lane's device adds one transform unit"
echo "(nine 18 x 25-bit products) for all its lanes. $(yosys -V); cells: OSU 0.18 um (qflow-tech-osu018), ABC mapped"
echo "for 5 ns; no buffer trees, no static timing (bench/timing.sh measures clocks). Made by \`bash bench/brick_cost.sh\`."
