#!/usr/bin/env bash
# bench/sparse_cost.sh: what a sparse device's second read port costs, as a Markdown fragment on stdout (docs/hardware.md,
# "Sparse maps and shells"): yosys synth_xilinx (7-series) of one voxmap memory of 4096 x 64 bits as the one-port
# voxcd_ram and as voxcd_ram2 (port A: write, else read; port B: read), then of voxcd_device at LANES 4, SAW = MAW =
# 12 (the memories of bench/rtl_cost.sh) as the dense device and as the sparse device (BL 3): block RAMs, LUTs and
# FFs from `stat`. Needs yosys; takes a few minutes on 2 cores. Usage: bash bench/sparse_cost.sh [> cost.md]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
mapfile -t rtl_files < <(grep -v -e "^[[:space:]]*//" -e "^[[:space:]]*$" -e "\.vlt[[:space:]]*$" "$root/rtl/voxcd.f")
command -v yosys >/dev/null || { echo "sparse_cost.sh needs yosys (Debian package yosys)" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for f in "${rtl_files[@]}"; do cp "$root/rtl/$f" "$tmp/$f"; done
cd "$tmp"
read_rtl="read_verilog -sv ${rtl_files[*]}"

# synth TOP PARAMS LOG: synth_xilinx, flattened, with stat.
synth() {
  yosys -q -l "$3" -p "$read_rtl; chparam $2 $1; synth_xilinx -noiopad -top $1; flatten; stat" >/dev/null 2>&1
}
# count LOG PATTERN: the sum of the last stat's cells matching PATTERN.
count() {
  awk -v p="$2" '/Number of cells/ { n = 0; delete c } $1 ~ p && $2 ~ /^[0-9]+$/ { c[$1] = $2 }
                 END { for (k in c) n += c[k]; print n + 0 }' "$1"
}
row() {
  local log=$1 what=$2
  echo "| $what | $(count "$log" '^RAMB36E1$') | $(count "$log" '^RAMB18E1$') | $(count "$log" '^LUT[1-6]$') |" \
       "$(count "$log" '^FD[A-Z]*$') |"
}

start=$SECONDS
synth voxcd_ram "-set Width 64 -set AddrW 12" ram.log &
synth voxcd_ram2 "-set Width 64 -set AddrW 12" ram2.log &
wait
synth voxcd_device "-set LANES 4 -set SAW 12 -set MAW 12" dense.log &
synth voxcd_device "-set LANES 4 -set SAW 12 -set MAW 12 -set BL 3" sparse.log &
wait
echo "| synthesised | RAMB36E1 | RAMB18E1 | LUTs | FFs |"
echo "|---|--:|--:|--:|--:|"
row ram.log "voxcd_ram, 4096 x 64 (one read port)"
row ram2.log "voxcd_ram2, 4096 x 64 (two read ports)"
row dense.log "voxcd_device LANES 4, SAW = MAW = 12 (dense)"
row sparse.log "the same with BL 3 (sparse)"
echo
echo "$(yosys -V | head -1), synth_xilinx -noiopad, flattened ($((SECONDS - start)) s)."
