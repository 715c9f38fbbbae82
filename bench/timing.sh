#!/usr/bin/env bash
# bench/timing.sh: clocks and area of the RTL from timing tools, per pipeline depth; regenerates docs/hardware.md's
# "Timing and area per depth" block (bench:timing) and the table `voxcd size --target` reads (host/sizing/timing.tsv).
#
# For every depth the RTL offers (voxcd_device's parameter Depth, 0 up to the package's deepest; only 0 when the
# device has no such parameter), or those of --depths:
#   1. ASIC: voxcd_device at the default configuration (LANES 4, default widths, SAW = MAW = 12 as in
#      bench/rtl_cost.sh), its RAMs as SRAM macros (black boxes with a stated access time, bench/timing/sram_models.py),
#      yosys `synth -flatten` (adders as Kogge-Stone prefixes, host/sizing/kogge_stone.v), `dfflibmap` and
#      `abc -D <goal period>` (buffering, upsizing and downsizing, ABC_SCRIPT below) onto the OSU 0.18 um standard cells (Debian qflow-tech-osu018), buffer trees on
#      every net with more than 8 loads (bench/timing/fanout_buffers.py: ABC leaves flip-flop outputs unbuffered),
#      then OpenSTA (`sta`) at the goal clock with a wire load model: worst slack, so the largest clock, and the
#      cell area from the liberty file (yosys `stat -liberty`).
#   2. iCE40: the reduced configuration of bench/rtl_cost.sh at LANES 1 inside bench/voxcd_fmax_top.sv; on the
#      HX8K `synth_ice40` (no DSP blocks on the part), on the UP5K `synth_ice40 -dsp` with the widest multipliers in
#      its 8 SB_MAC16 and the rest in logic cells (bench/timing/dsp_budget.py); nextpnr-ice40 with seeds 1, 2, 3,
#      the median "Max frequency".
#   3. Xilinx 7-series: the default configuration after `synth_xilinx -flatten -noiopad`: LUT, FF, DSP48E1 and block
#      RAM counts and the logic depth (LUT levels and CARRY4 cells on the longest path between state-holding cells).
#
# Needs yosys, berkeley-abc (with yosys), opensta, qflow-tech-osu018, nextpnr-ice40, fpga-icestorm and python3 (Debian
# packages). JOBS tool runs at a time (default 2); about half an hour per depth on 2 busy cores.
# Usage: bash bench/timing.sh [--depths 0,1,2] [--out DIR]
#   --depths  the depths to measure (default: every depth the RTL offers)
#   --out     write the Markdown block and the table into DIR instead of docs/hardware.md and host/sizing/timing.tsv
set -euo pipefail

JOBS="${JOBS:-2}"
# The ASIC flow's constants (GOAL_MHZ, the SRAM macros, the wire load, FANOUT, LIB, the scripts) and asic_flow.
# shellcheck source=bench/timing/asic.sh
source "$(dirname "${BASH_SOURCE[0]}")/timing/asic.sh"

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
command_text="bash bench/timing.sh"  # the command the report names: its options but --out (which moves no figure)
args=("$@")
for ((i = 0; i < ${#args[@]}; i++)); do
  if [ "${args[$i]}" = --out ]; then i=$((i + 1)); else command_text+=" ${args[$i]}"; fi
done
depth_list=""
out=""
while (($#)); do
  case "$1" in
    --depths) depth_list="${2:?--depths needs a list such as 0,1,2}"; shift 2 ;;
    --out) out="${2:?--out needs a directory}"; shift 2 ;;
    *) echo "timing.sh: unknown argument '$1' (usage: bash bench/timing.sh [--depths 0,1,2] [--out DIR])" >&2; exit 2 ;;
  esac
done

runs_name=timing.sh
# shellcheck source=bench/tool_runs.sh
source "$root/bench/tool_runs.sh"
need yosys yosys
need sta opensta
need nextpnr-ice40 nextpnr-ice40
need icepack fpga-icestorm
need python3 python3
[ -f "$LIB" ] || { echo "timing.sh: $LIB not found: install the Debian package qflow-tech-osu018" >&2; missing=1; }
if ((missing)); then exit 1; fi

# ---- The depths the RTL offers ----
has_depth=0
# voxcd_device's parameter list: in its file, or (since it is written once) in voxcd_arch_pkg.sv's macros.
if grep -Eq '^\s*parameter\s+int\s+unsigned\s+Depth\b' "$root/rtl/voxcd_device.sv" "$root/rtl/voxcd_arch_pkg.sv"; then
  has_depth=1
fi
if [ -z "$depth_list" ]; then
  if ((has_depth)); then
    # The deepest: the package's localparam whose name says Max and Depth (voxcd_arch_pkg.sv).
    max=$(grep -Eo 'localparam\s+int\s+unsigned\s+\w*(Max\w*Depth|Depth\w*Max)\w*\s*=\s*[0-9]+' \
          "$root/rtl/voxcd_arch_pkg.sv" | grep -Eo '[0-9]+$' | head -n 1 || true)
    [ -n "$max" ] || { echo "timing.sh: rtl/voxcd_device.sv has a Depth parameter but rtl/voxcd_arch_pkg.sv names no" \
                            "deepest depth (a localparam such as MaxDepth); give --depths" >&2; exit 1; }
    depth_list=$(seq -s, 0 "$max")
  else
    depth_list=0
  fi
fi
IFS=, read -r -a depths <<<"$depth_list"
for d in "${depths[@]}"; do
  [[ "$d" =~ ^[0-9]+$ ]] || { echo "timing.sh: --depths: '$d' is not a depth (0, 1, 2, ...)" >&2; exit 2; }
  if ((d > 0 && !has_depth)); then
    echo "timing.sh: --depths: depth $d, but rtl/voxcd_device.sv has no Depth parameter (its one depth is 0)" >&2
    exit 2
  fi
done

# The RTL in the order of rtl/voxcd.f (// lines are comments; yosys skips Verilator's *.vlt).
mapfile -t rtl_files < <(grep -v -e "^[[:space:]]*//" -e "^[[:space:]]*$" -e "\.vlt[[:space:]]*$" "$root/rtl/voxcd.f")
work_dir
for f in "${rtl_files[@]}"; do cp "$root/rtl/$f" "$tmp/$f"; done
cp "$root/bench/voxcd_fmax_top.sv" "$root/bench/timing/"*.py "$root/host/sizing/kogge_stone.v" "$tmp/"
cd "$tmp"
read_rtl="read_verilog -sv ${rtl_files[*]}"
small_cfg="-set LANES 1 -set PW 10 -set PF 2 -set MW 8 -set MF 6 -set TW 20 -set DW 5 -set MEMW 16 -set SAW 8"
small_cfg+=" -set MAW 9 -set TAGW 4"

# up5k_synth D: synth_ice40 -dsp of the reduced configuration at depth D with at most 8 SB_MAC16.
up5k_synth() {
  local d=$1
  yosys -q -l "up5k-d$d.pre.yslog" -p "$read_rtl voxcd_fmax_top.sv; chparam $small_cfg $(depth_set "$d") voxcd_fmax_top;
    synth_ice40 -dsp -top voxcd_fmax_top -run begin:coarse; wreduce t:\$mul; write_json up5k-d$d.pre.json"
  python3 dsp_budget.py "up5k-d$d.pre.json" "up5k-d$d.mid.json" voxcd_fmax_top 8 >"up5k-d$d.dsp.txt"
  yosys -q -l "up5k-d$d.yslog" -p "read_verilog -D ICE40_HX -lib -specify +/ice40/cells_sim.v;
    read_json up5k-d$d.mid.json; synth_ice40 -dsp -top voxcd_fmax_top -run coarse: -json up5k-d$d.json"
}

start=$SECONDS
# ---- Synthesis, longest first ----
for d in "${depths[@]}"; do launch "asic-d$d.log" asic_flow "$d"; done
for d in "${depths[@]}"; do
  launch "xilinx-d$d.log" yosys -q -l "xilinx-d$d.yslog" -p "$read_rtl; chparam $default_cfg $(depth_set "$d") voxcd_device;
    synth_xilinx -flatten -noiopad -top voxcd_device;
    select -set comb t:FD* t:RAMB* %u t:SRL* %u t:RAM32M %u t:RAM64M %u t:DSP48E1 %u %n;
    tee -q -o xilinx-d$d.ltp.txt ltp @comb; tee -q -o xilinx-d$d.stat.json stat -json; write_json xilinx-d$d.json"
  launch "hx8k-d$d.log" yosys -q -l "hx8k-d$d.yslog" -p "$read_rtl voxcd_fmax_top.sv;
    chparam $small_cfg $(depth_set "$d") voxcd_fmax_top; synth_ice40 -top voxcd_fmax_top -json hx8k-d$d.json"
  launch "up5k-d$d.log" up5k_synth "$d"
done
finish
synth_secs=$((SECONDS - start))

# ---- Place and route ----
declare -A pnr_args=([hx8k]="--hx8k --package ct256" [up5k]="--up5k --package sg48")
for d in "${depths[@]}"; do
  for dev in hx8k up5k; do
    for seed in 1 2 3; do
      # A design that does not fit the part fails here; the report says so (no report file).
      # shellcheck disable=SC2086
      launch "pnr-$dev-d$d-$seed.log" bash -c "nextpnr-ice40 ${pnr_args[$dev]} --json $dev-d$d.json --freq 12 \
        --seed $seed --asc $dev-d$d-$seed.asc --report $dev-d$d-$seed.report.json && icepack $dev-d$d-$seed.asc \
        $dev-d$d-$seed.bin || true"
    done
  done
done
finish
secs=$((SECONDS - start))
times >cpu.txt  # second line: user and system CPU time of the tool runs

md="$tmp/timing.md"
tsv="$tmp/timing.tsv"
python3 "$root/bench/timing/report.py" --depths "$depth_list" --goal-mhz "$GOAL_MHZ" --sram "$SRAM_ACCESS_NS" \
  "$SRAM_SETUP_NS" "$SRAM_HOLD_NS" --wire "$WIRE_UM" "$WIRE_FF_UM" --fanout "$FANOUT" --small "$small_cfg" \
  --default "$default_cfg" --secs "$synth_secs" "$secs" --cpu "$(tail -n 1 cpu.txt)" --jobs "$JOBS" \
  --yosys "$(yosys -V | head -n 1)" --nextpnr "$(nextpnr-ice40 --version 2>&1 | head -n 1)" \
  --sta "$(sta -version 2>&1 | head -n 1)" --command "$command_text" \
  --markdown "$md" --table "$tsv"
if [ -n "$out" ]; then
  mkdir -p "$out"
  cp "$md" "$out/timing.md"
  cp "$tsv" "$out/timing.tsv"
  echo "wrote $out/timing.md and $out/timing.tsv"
else
  bash "$root/bench/splice.sh" "$root/docs/hardware.md" timing "$md"
  cp "$tsv" "$root/host/sizing/timing.tsv"
  echo "wrote $root/host/sizing/timing.tsv"
fi
