#!/usr/bin/env bash
# bench/energy.sh: energy per lookup of one device configuration at 0.18 um, measured with OpenSTA's report_power on
# the mapped netlist with switching activity from a Verilator simulation of real scenes; regenerates docs/hardware.md's
# "Energy per lookup" block (bench:energy) and host/sizing/energy.tsv.
#
#   1. Netlist: bench/timing.sh's ASIC flow (bench/timing/asic.sh: yosys with Kogge-Stone adders onto the OSU 0.18 um
#      cells, SRAM macros as black boxes, buffer trees) for the configuration, kept under build/energy/ for reruns
#      (bench/energy/netlist.sh; 10 to 30 minutes the first time).
#   2. Stimulus: bench_energy writes a vector file per scene (the built-in scene of voxcd simulate at 1,024 objects for
#      --frames frames, the room and the robot, two tori), each scene at a voxel where its memories fit the
#      configuration's SAW and MAW, in the configuration of the rtl backend's model (its widths, LANES and DEPTH; the
#      model's memory depths).
#   3. Activity: `voxcd conform FILE --backend rtl --trace F.fst`, fst2vcd, and bench/energy/toggles.py counts each
#      signal bit's toggles and high cycles over the run (first job to last completion); bench/energy/activity.py
#      turns the registers', input ports' and SRAM read data's rates into set_power_activity commands.
#   4. Power: OpenSTA at the configuration's measured clock (host/device/timing.tsv, or --clock) with the flow's
#      wire load model; bench/energy/report.py adds the SRAM macros' access energy (an estimate: its model is stated
#      there and in the block) and writes the block and the table, with a projection to 45, 16 and 7 nm (Stillmaker
#      and Baas 2017), labelled as one.
#
# Needs yosys, opensta, qflow-tech-osu018, gtkwave (fst2vcd), python3 (Debian packages) and a build with the rtl
# backend and the model of the configuration (voxcd, voxcd_rtl_backend and bench_energy; --build). A build that
# makes only the model needed: cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DVOXCD_BENCH=ON
#   -DVOXCD_RTL_LANES=4 -DVOXCD_RTL_CONFIGS= -DVOXCD_RTL_DIST_MODELS= -DVOXCD_RTL_BANKED_MODELS=
#   -DVOXCD_RTL_DEPTH_MODELS= -DVOXCD_RTL_SPARSE_MODELS=   (add the model's pairs to VOXCD_RTL_DEPTH_MODELS for D > 0)
# Usage: bash bench/energy.sh [--config "PW 24 ... LANES 4 SAW 12 MAW 12 TAGW 16"] [--depth D] [--frames N]
#                             [--clock MHZ] [--max-lookups N] [--build DIR] [--out DIR]
#   --config  the configuration, as DeviceConfig::to_string writes it (default: bench/timing.sh's, SAW = MAW = 12)
#   --depth   the pipeline depth (default 0, or the config's DEPTH)
#   --frames  frames of the simulate scene (default 20)
#   --clock   the clock in MHz (default: host/device/timing.tsv's asic-osu018 row of the configuration and depth)
#   --out     write the Markdown block and the table into DIR instead of docs/hardware.md and host/sizing/energy.tsv
set -euo pipefail

JOBS="${JOBS:-2}"
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
# shellcheck source=bench/timing/asic.sh
source "$root/bench/timing/asic.sh"
# shellcheck source=bench/energy/netlist.sh
source "$root/bench/energy/netlist.sh"

command_text="bash bench/energy.sh"
args=("$@")
for ((i = 0; i < ${#args[@]}; i++)); do
  case "${args[$i]}" in
    --out | --build) i=$((i + 1)) ;;
    *) command_text+=" ${args[$i]}" ;;
  esac
done
config="PW 24 PF 8 MW 18 MF 16 TW 48 DW 10 MEMW 64 LANES 4 SAW 12 MAW 12 TAGW 16"
depth="" frames=20 clock="" max_lookups=200000 build="$root/build" out=""
while (($#)); do
  case "$1" in
    --config) config="${2:?--config needs the configuration pairs}"; shift 2 ;;
    --depth) depth="${2:?--depth needs a depth}"; shift 2 ;;
    --frames) frames="${2:?--frames needs a number}"; shift 2 ;;
    --clock) clock="${2:?--clock needs MHz}"; shift 2 ;;
    --max-lookups) max_lookups="${2:?--max-lookups needs a number}"; shift 2 ;;
    --build) build="$(cd "${2:?--build needs a directory}" && pwd)"; shift 2 ;;
    --out) out="${2:?--out needs a directory}"; shift 2 ;;
    *) echo "energy.sh: unknown argument '$1' (see the usage at the top of bench/energy.sh)" >&2; exit 2 ;;
  esac
done

runs_name=energy.sh
# shellcheck source=bench/tool_runs.sh
source "$root/bench/tool_runs.sh"
need yosys yosys
need sta opensta
need fst2vcd gtkwave
need python3 python3
[ -f "$LIB" ] || { echo "energy.sh: $LIB not found: install the Debian package qflow-tech-osu018" >&2; missing=1; }
if ((missing)); then exit 1; fi

# The configuration: its DEPTH (if any) is the depth; the rest become chparam settings.
read -r -a pairs <<<"$config"
((${#pairs[@]} % 2 == 0)) || { echo "energy.sh: --config: '$config' is not NAME VALUE pairs" >&2; exit 2; }
cfg_set="" base_pairs=""
for ((i = 0; i < ${#pairs[@]}; i += 2)); do
  n=${pairs[$i]} v=${pairs[$((i + 1))]}
  if [ "$n" = DEPTH ]; then
    [ -z "$depth" ] || [ "$depth" = "$v" ] || { echo "energy.sh: --depth $depth but the config says DEPTH $v" >&2; exit 2; }
    depth=$v
    continue
  fi
  cfg_set+=" -set $n $v"
  base_pairs+="${base_pairs:+ }$n $v"
done
depth=${depth:-0}
model_pairs="$base_pairs"
if ((depth > 0)); then model_pairs+=" DEPTH $depth"; fi

# The clock: timing.tsv's row of this configuration and depth.
clock_source="--clock"
if [ -z "$clock" ]; then
  clock=$(awk -F'\t' -v d="$depth" -v c="$base_pairs" '$1 == "asic-osu018" && $2 == d && $12 == c { print $3 }' \
          "$root/host/device/timing.tsv" | head -n 1)
  [ -n "$clock" ] || { echo "energy.sh: host/device/timing.tsv has no asic-osu018 row of depth $depth and config" \
                            "'$base_pairs': give --clock MHZ" >&2; exit 1; }
  clock_source="OpenSTA's largest clock of the configuration at depth $depth, host/device/timing.tsv"
fi

start=$SECONDS
echo "energy: netlist of '$base_pairs' at depth $depth" >&2
net_dir=$(energy_netlist "$root" "${cfg_set# }" "$depth")

echo "energy: building voxcd, voxcd_rtl_backend and bench_energy in $build" >&2
cmake --build "$build" -j "$JOBS" --target voxcd voxcd_rtl_backend bench_energy >/dev/null
voxcd="$build/voxcd"
bench_energy=$(find "$build" -maxdepth 2 -name bench_energy -type f -perm -u+x | head -n 1)
if [ ! -x "$voxcd" ] || [ -z "$bench_energy" ]; then echo "energy.sh: no voxcd or bench_energy in $build" >&2; exit 1; fi

run="$root/build/energy/run"
rm -rf "$run"
mkdir -p "$run"
"$bench_energy" --out "$run" --config "$base_pairs" --model "$(echo "$model_pairs" |
  sed -E 's/SAW [0-9]+/SAW 16/; s/MAW [0-9]+/MAW 18/')" --frames "$frames" --max-lookups "$max_lookups" >"$run/scenes.txt"
model_line=$(echo "$model_pairs" | sed -E 's/SAW [0-9]+/SAW 16/; s/MAW [0-9]+/MAW 18/')
cat "$run/scenes.txt" >&2

scene_args=()
while read -r _ name _ file _ jobs _ lookups _ pairs _ voxel _ shell _ map _ scene_frames; do
  d="$run/$name"
  mkdir -p "$d"
  printf '{"jobs": %s, "lookups": %s, "pairs": %s, "voxel": %s, "shell_words": %s, "map_words": %s, "frames": %s}\n' \
    "$jobs" "$lookups" "$pairs" "$voxel" "$shell" "$map" "$scene_frames" >"$d/info.json"
  echo "energy: $name: rtl backend with a trace" >&2
  "$voxcd" conform "$file" --backend rtl --trace "$d/trace.fst" >"$d/conform.txt"
  echo "energy: $name: toggles" >&2
  python3 "$root/bench/energy/toggles.py" "$d/trace.fst" - "$d/toggles.json"
  rm -f "$d/trace.fst"  # tens of MB a scene; the counts are kept
  python3 "$root/bench/energy/activity.py" "$net_dir/netlist.v" "$LIB" "$d/toggles.json" "$d/power.v" \
    "$d/activity.tcl" "$d/match.json"
  cat >"$d/power.tcl" <<EOF
read_liberty $LIB
read_liberty $net_dir/srams.lib
read_verilog $d/power.v
link_design voxcd_device
set_wire_load_model -name voxcd_wire -library voxcd_sram
create_clock -name clk -period $(python3 -c "print(1e3 / $clock)") [get_ports clk_i]
set_input_delay 0 -clock clk [delete_from_list [all_inputs] [get_ports clk_i]]
set_output_delay 0 -clock clk [all_outputs]
source $d/activity.tcl
catch { report_power -digits 6 } err
puts "report_power: \$err"
source $root/bench/energy/power_sum.tcl
EOF
  echo "energy: $name: OpenSTA report_power" >&2
  sta -exit "$d/power.tcl" >"$d/power.txt" 2>&1
  grep -q "^group comb" "$d/power.txt" || { tail -n 20 "$d/power.txt" >&2; exit 1; }
  scene_args+=("$name:$d")
done <"$run/scenes.txt"

md="$run/energy.md"
tsv="$run/energy.tsv"
versions="$(yosys -V | head -n 1); OpenSTA $(sta -version 2>&1 | head -n 1); $(verilator --version | head -n 1);"
versions+=" fst2vcd of gtkwave $(dpkg-query -W -f '${Version}' gtkwave 2>/dev/null || echo '?');"
versions+=" $(python3 --version); $((SECONDS - start)) s"
python3 "$root/bench/energy/report.py" --scenes "${scene_args[@]}" --srams "$net_dir/srams.json" --mhz "$clock" \
  --clock-source "$clock_source" --config "$base_pairs" --depth "$depth" --command "$command_text" \
  --date "$(date -u +%Y-%m-%d)" --versions "$versions" --model "$model_line" --sta "$net_dir/sta.txt" \
  --goal-mhz "$GOAL_MHZ" --markdown "$md" --table "$tsv"
if [ -n "$out" ]; then
  mkdir -p "$out"
  cp "$md" "$out/energy.md"
  cp "$tsv" "$out/energy.tsv"
  echo "wrote $out/energy.md and $out/energy.tsv"
else
  bash "$root/bench/splice.sh" "$root/docs/hardware.md" energy "$md"
  cp "$tsv" "$root/host/sizing/energy.tsv"
  echo "wrote $root/host/sizing/energy.tsv"
fi
