#!/usr/bin/env bash
# bench/timing.sh: clocks and area of the RTL from timing tools, per pipeline depth, of one configuration; merges its
# section into docs/hardware.md's "Timing and area per depth" block (bench:timing) and its rows into the table every
# modelled rate's clock and `voxcd size --target` read (host/device/timing.tsv): the rows and the section of the
# configuration and depths it measured are replaced, those of the others kept (bench/timing/report.py merge).
#
# For every depth the RTL offers (voxcd_device's parameter Depth, 0 up to the package's deepest; only 0 when the
# device has no such parameter), or those of --depths:
#   1. ASIC: voxcd_device at the configuration of --config (default: LANES 4 at the default widths; SAW = MAW = 12
#      as in bench/rtl_cost.sh unless --config gives them), its RAMs as SRAM macros (black boxes with a stated access time, bench/timing/sram_models.py),
#      yosys `synth -flatten` (adders as Kogge-Stone prefixes, host/sizing/kogge_stone.v), `dfflibmap` and
#      `abc -D <goal period>` (buffering, upsizing and downsizing, ABC_SCRIPT below) onto the OSU 0.18 um standard cells (Debian qflow-tech-osu018), buffer trees on
#      every net with more than 8 loads (bench/timing/fanout_buffers.py: ABC leaves flip-flop outputs unbuffered),
#      then OpenSTA (`sta`) at the goal clock with a wire load model: worst slack, so the largest clock, and the
#      cell area from the liberty file (yosys `stat -liberty`).
#   2. iCE40 (without --config only): the reduced configuration of bench/rtl_cost.sh at LANES 1 inside
#      bench/voxcd_fmax_top.sv; on the
#      HX8K `synth_ice40` (no DSP blocks on the part), on the UP5K `synth_ice40 -dsp` with the widest multipliers in
#      its 8 SB_MAC16 and the rest in logic cells (bench/timing/dsp_budget.py); nextpnr-ice40 with seeds 1, 2, 3,
#      the median "Max frequency".
#   3. Xilinx 7-series: the configuration of --config after `synth_xilinx -flatten -noiopad`: LUT, FF, DSP48E1 and block
#      RAM counts and the logic depth (LUT levels and CARRY4 cells on the longest path between state-holding cells).
#
# Needs yosys, berkeley-abc (with yosys), opensta, qflow-tech-osu018, nextpnr-ice40, fpga-icestorm and python3 (Debian
# packages). JOBS tool runs at a time (default 2); about half an hour per depth on 2 busy cores.
# Usage: bash bench/timing.sh [--depths 0,1,2] [--config "LANES 16 BANKS 4"] [--out DIR]
#   --depths  the depths to measure (default: every depth the RTL offers)
#   --config  the configuration: NAME VALUE pairs as DeviceConfig::to_string writes them (PW PF MW MF TW DW MEMW
#             LANES SAW MAW TAGW SB WB BANKS BL; the depth comes from --depths), over LANES 4 SAW 12 MAW 12 at the
#             default widths. The iCE40 flows (a reduced LANES 1 configuration that fits the parts) run only without it
#   --out     write the merged Markdown block and table into DIR (timing.md, timing.tsv) instead of
#             docs/hardware.md and host/device/timing.tsv
set -euo pipefail

JOBS="${JOBS:-2}"
# The ASIC flow's constants (GOAL_MHZ, the SRAM macros, the wire load, FANOUT, LIB, the scripts) and asic_flow.
# shellcheck source=bench/timing/asic.sh
source "$(dirname "${BASH_SOURCE[0]}")/timing/asic.sh"

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
command_text="bash bench/timing.sh"  # the command the report names: its options but --out (which moves no figure)
args=("$@")
for ((i = 0; i < ${#args[@]}; i++)); do
  if [ "${args[$i]}" = --out ]; then
    i=$((i + 1))
  elif [[ "${args[$i]}" == *" "* ]]; then
    command_text+=" \"${args[$i]}\""
  else
    command_text+=" ${args[$i]}"
  fi
done
depth_list=""
out=""
config=""
ice40=1  # the iCE40 flows: only for the default configuration
usage="usage: bash bench/timing.sh [--depths 0,1,2] [--config \"LANES 16 BANKS 4\"] [--out DIR]"
while (($#)); do
  case "$1" in
    --depths) depth_list="${2:?--depths needs a list such as 0,1,2}"; shift 2 ;;
    --config) config="${2:?--config needs NAME VALUE pairs such as \"LANES 16 BANKS 4\"}"; ice40=0; shift 2 ;;
    --out) out="${2:?--out needs a directory}"; shift 2 ;;
    *) echo "timing.sh: unknown argument '$1' ($usage)" >&2; exit 2 ;;
  esac
done

# The configuration as yosys chparam options: LANES 4 SAW 12 MAW 12 at the default widths, with --config's pairs in
# their place (each name a voxcd_device parameter of the same name).
declare -A params=([LANES]=4 [SAW]=12 [MAW]=12)
param_order=(LANES SAW MAW)
read -r -a pairs <<<"$config"
((${#pairs[@]} % 2 == 0)) || { echo "timing.sh: --config: '$config' is not NAME VALUE pairs" >&2; exit 2; }
for ((i = 0; i < ${#pairs[@]}; i += 2)); do
  name=${pairs[$i]} value=${pairs[$((i + 1))]}
  case "$name" in
    PW | PF | MW | MF | TW | DW | MEMW | LANES | SAW | MAW | TAGW | SB | WB | BANKS | BL | TX) ;;
    DEPTH) echo "timing.sh: --config: give the depth with --depths, not DEPTH" >&2; exit 2 ;;
    *) echo "timing.sh: --config: '$name' is not a configuration parameter (PW PF MW MF TW DW MEMW LANES SAW MAW" \
            "TAGW SB WB BANKS BL TX)" >&2; exit 2 ;;
  esac
  [[ "$value" =~ ^[0-9]+$ ]] || { echo "timing.sh: --config: $name '$value' is not a whole number" >&2; exit 2; }
  [[ -v "params[$name]" ]] || param_order+=("$name")
  params[$name]=$value
done
default_cfg=""
for name in "${param_order[@]}"; do default_cfg+="${default_cfg:+ }-set $name ${params[$name]}"; done

runs_name=timing.sh
# shellcheck source=bench/tool_runs.sh
source "$root/bench/tool_runs.sh"
need yosys yosys
need sta opensta
if ((ice40)); then
  need nextpnr-ice40 nextpnr-ice40
  need icepack fpga-icestorm
fi
need python3 python3
[ -f "$LIB" ] || { echo "timing.sh: $LIB not found: install the Debian package qflow-tech-osu018" >&2; missing=1; }
if ((missing)); then exit 1; fi

# ---- The depths the RTL offers ----
has_depth=0
# voxcd_device's parameter list: in its file, or (since it is written once) in voxcd_params.svh's macros.
if grep -Eqs '^\s*parameter\s+int\s+unsigned\s+Depth\b' "$root/rtl/voxcd_device.sv" "$root/rtl/voxcd_params.svh"; then
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
  ((ice40)) || continue
  launch "hx8k-d$d.log" yosys -q -l "hx8k-d$d.yslog" -p "$read_rtl voxcd_fmax_top.sv;
    chparam $small_cfg $(depth_set "$d") voxcd_fmax_top; synth_ice40 -top voxcd_fmax_top -json hx8k-d$d.json"
  launch "up5k-d$d.log" up5k_synth "$d"
done
finish
synth_secs=$((SECONDS - start))

# ---- Place and route ----
declare -A pnr_args=([hx8k]="--hx8k --package ct256" [up5k]="--up5k --package sg48")
for d in "${depths[@]}"; do
  ((ice40)) || continue
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

nextpnr_version="-"
if ((ice40)); then nextpnr_version="$(nextpnr-ice40 --version 2>&1 | head -n 1)"; fi
# This run's section and rows, then both merged into the block and the table as they are.
python3 "$root/bench/timing/report.py" --depths "$depth_list" --goal-mhz "$GOAL_MHZ" --sram "$SRAM_ACCESS_NS" \
  "$SRAM_SETUP_NS" "$SRAM_HOLD_NS" --wire "$WIRE_UM" "$WIRE_FF_UM" --fanout "$FANOUT" --small "$small_cfg" \
  --default "$default_cfg" --ice40 "$ice40" --secs "$synth_secs" "$secs" --cpu "$(tail -n 1 cpu.txt)" \
  --jobs "$JOBS" --yosys "$(yosys -V | head -n 1)" --nextpnr "$nextpnr_version" \
  --sta "$(sta -version 2>&1 | head -n 1)" --command "$command_text" \
  --markdown "$tmp/run.md" --table "$tmp/run.tsv"
python3 "$root/bench/timing/report.py" merge --run-markdown "$tmp/run.md" --run-table "$tmp/run.tsv" \
  --doc "$root/docs/hardware.md" --table "$root/host/device/timing.tsv" \
  --out-markdown "$tmp/timing.md" --out-table "$tmp/timing.tsv"
if [ -n "$out" ]; then
  mkdir -p "$out"
  cp "$tmp/timing.md" "$out/timing.md"
  cp "$tmp/timing.tsv" "$out/timing.tsv"
  echo "wrote $out/timing.md and $out/timing.tsv"
else
  bash "$root/bench/splice.sh" "$root/docs/hardware.md" timing "$tmp/timing.md"
  cp "$tmp/timing.tsv" "$root/host/device/timing.tsv"
  echo "wrote $root/host/device/timing.tsv"
fi
