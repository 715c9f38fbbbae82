#!/usr/bin/env bash
# bench/rtl_cost.sh: hardware cost of the RTL (rtl/*.sv), as a Markdown fragment on stdout.
#
#   1. Synthesis cost per configuration: yosys synth_xilinx (7-series) and synth_ecp5 of voxcd_device for
#      LANES = 1, 2, 4, 8 at the default widths and reduced memory depths (SAW = MAW = 12): LUTs, FFs, DSPs and
#      block RAMs, read from `stat -json`.
#   2. Place and route on an iCE40: a configuration small enough for an HX8K (and an UP5K), synthesised through
#      the pin-limited wrapper bench/voxcd_fmax_top.sv with synth_ice40 and placed and routed by nextpnr-ice40 with
#      seeds 1, 2, 3: logic cells, RAMs, the median "Max frequency for clock" and the resulting lookup rate.
#
# With --distance, the same for the distance device (SB > 2): synthesis of SB 8 WB 8 at LANES 1 and 4, and place
# and route of a small SB 4 configuration on the HX8K.
#
# Needs the Debian packages yosys, nextpnr-ice40, fpga-icestorm and python3. Takes about 5 minutes on 2 cores
# (JOBS tool runs at a time, default 2). Usage: bench/rtl_cost.sh [--distance] [> cost.md]
set -euo pipefail

JOBS="${JOBS:-2}"
mode=states
if [ "${1:-}" = "--distance" ]; then mode=distance; fi

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
# The RTL, in the order of its one file list (rtl/voxcd.f; // lines are comments).
# Verilator's lint waivers (*.vlt) are not Verilog: yosys skips them.
mapfile -t rtl_files < <(grep -v -e "^[[:space:]]*//" -e "^[[:space:]]*$" -e "\.vlt[[:space:]]*$" "$root/rtl/voxcd.f")

runs_name=rtl_cost.sh
# shellcheck source=bench/tool_runs.sh
source "$root/bench/tool_runs.sh"
need yosys yosys
need nextpnr-ice40 nextpnr-ice40
need icepack fpga-icestorm
need python3 python3
if ((missing)); then exit 1; fi

work_dir

# Sources are copied so that the tools see short relative paths (the repository path may contain spaces).
for f in "${rtl_files[@]}"; do cp "$root/rtl/$f" "$tmp/$f"; done
cp "$root/bench/voxcd_fmax_top.sv" "$tmp/voxcd_fmax_top.sv"
cd "$tmp"
read_rtl="read_verilog -sv ${rtl_files[*]}"

start=$SECONDS

# ---- 1. Synthesis cost per configuration ----
sweep_lanes=(8 4 2 1)  # longest first
sweep_params="-set SAW 12 -set MAW 12"
if [ "$mode" = distance ]; then
  sweep_lanes=(4 1)
  sweep_params="-set SAW 12 -set MAW 12 -set SB 8 -set WB 8"
fi
# synth_xilinx keeps the hierarchy, synth_ecp5 flattens: `flatten` after synthesis only merges the counts of the
# mapped modules (yosys 0.23's `stat -json` of a hierarchy is not valid JSON).
declare -A synth_cmd=([xilinx]="synth_xilinx -noiopad -top voxcd_device; flatten" [ecp5]="synth_ecp5 -top voxcd_device")

# ---- 2. Place and route on an iCE40 ----
pnr_params="-set LANES 1 -set PW 10 -set PF 2 -set MW 8 -set MF 6 -set TW 20 -set DW 5 -set MEMW 16 -set SAW 8"
pnr_params+=" -set MAW 9 -set TAGW 4"
pnr_devices=(hx8k up5k)
if [ "$mode" = distance ]; then
  pnr_params+=" -set SB 4 -set WB 4"
  pnr_devices=(hx8k)
fi
seeds=(1 2 3)

launch ice40.log yosys -q -l ice40.yslog -p "$read_rtl voxcd_fmax_top.sv; chparam $pnr_params voxcd_fmax_top;
  synth_ice40 -top voxcd_fmax_top -json ice40.json; tee -q -o ice40.stat.json stat -json"
launch ice40_dsp.log yosys -q -l ice40_dsp.yslog -p "$read_rtl voxcd_fmax_top.sv; chparam $pnr_params voxcd_fmax_top;
  synth_ice40 -dsp -top voxcd_fmax_top; tee -q -o ice40_dsp.stat.json stat -json"
for lanes in "${sweep_lanes[@]}"; do
  for target in xilinx ecp5; do
    launch "$target-$lanes.log" yosys -q -l "$target-$lanes.yslog" -p "$read_rtl;
      chparam -set LANES $lanes $sweep_params voxcd_device; ${synth_cmd[$target]};
      tee -q -o $target-$lanes.stat.json stat -json"
  done
done
finish
synth_secs=$((SECONDS - start))

declare -A pnr_args=([hx8k]="--hx8k --package ct256" [up5k]="--up5k --package sg48")
for seed in "${seeds[@]}"; do
  for dev in "${pnr_devices[@]}"; do
    # shellcheck disable=SC2086
    launch "$dev-$seed.log" nextpnr-ice40 ${pnr_args[$dev]} --json ice40.json --freq 12 --seed "$seed" \
      --asc "$dev-$seed.asc" --report "$dev-$seed.report.json"
  done
done
finish
# A bitstream packs only from a complete, legal placement and routing.
for seed in "${seeds[@]}"; do
  for dev in "${pnr_devices[@]}"; do icepack "$dev-$seed.asc" "$dev-$seed.bin"; done
done
total_secs=$((SECONDS - start))
times >cpu.txt  # second line: user and system CPU time of the tool runs

yosys_version="$(yosys -V 2>&1 | head -n 1)"
nextpnr_version="$(nextpnr-ice40 --version 2>&1 | head -n 1)"

python3 - "$yosys_version" "$nextpnr_version" "$sweep_params" "$pnr_params" "$synth_secs" "$total_secs" \
  "${sweep_lanes[*]}" "${seeds[*]}" "$read_rtl" "$JOBS" "$(tail -n 1 cpu.txt)" "$mode" "${pnr_devices[*]}" <<'EOF'
import json
import re
import statistics
import sys

(yosys_version, nextpnr_version, sweep_params, pnr_params, synth_secs, total_secs, sweep_lanes, seeds,
 read_rtl, jobs, cpu, mode, pnr_devices) = sys.argv[1:]
distance = mode == "distance"
pnr_devices = pnr_devices.split()
sweep_lanes = sorted(int(x) for x in sweep_lanes.split())
seeds = [int(x) for x in seeds.split()]


def cells(path):
    with open(path) as f:
        stat = json.load(f)
    if "design" in stat:  # totals over a hierarchy
        return stat["design"]["num_cells_by_type"]
    (module,) = stat["modules"].values()
    return module["num_cells_by_type"]


def seconds(text):  # "1m2.345s" -> 62.345
    m = re.fullmatch(r"(\d+)m([\d.]+)s", text)
    return int(m.group(1)) * 60 + float(m.group(2))


def total(c, names):
    return sum(c.get(n, 0) for n in names)


def params_text(params):
    return ", ".join(f"{k}={v}" for k, v in re.findall(r"-set (\w+) (\S+)", params))


if distance:
    print("### Distance devices: synthesis cost")
    print()
    print(f"voxcd_device with {params_text(sweep_params)} and the other widths at their defaults: the voxmap copy "
          f"of each lane is 8 bank RAMs of 2^9 x 64 bits (2^12 words in all, as above), and each lane adds the "
          f"eight-bank row addresses, the node select and seven interpolation multipliers ((SB+1) x WB: four for "
          f"x, two for y, one for z) in three more slot registers.")
else:
    print("### Synthesis cost per configuration")
    print()
    print(f"voxcd_device at the default widths (rtl/voxcd_arch_pkg.sv) but memory depths reduced to SAW=12, MAW=12: "
          f"a 2^12-point shell (split into LANES banks) and a 2^12 x 64-bit voxmap copy per lane. The default "
          f"depths (SAW=16: 2^16 x 72-bit shell points; MAW=18: 2^18 x 64-bit voxmap words, 16 Mbit per lane) are "
          f"far beyond any FPGA's block RAM. The cost of the logic does not depend on the depths; the block RAM "
          f"count does (it scales with them).")
print()
print("| target | LANES | LUTs | FFs | DSPs | block RAMs | carry cells | LUTs as SRL / RAM |")
print("|---|--:|--:|--:|--:|--:|--:|--:|")
for target in ("xilinx", "ecp5"):
    for lanes in sweep_lanes:
        c = cells(f"{target}-{lanes}.stat.json")
        if target == "xilinx":
            luts = total(c, [f"LUT{i}" for i in range(1, 7)])
            ffs = total(c, [n for n in c if n.startswith("FD")])
            dsps = c.get("DSP48E1", 0)
            r36, r18 = c.get("RAMB36E1", 0), c.get("RAMB18E1", 0)
            brams = f"{r36 + 0.5 * r18:g} ({r36} RAMB36E1 + {r18} RAMB18E1)"
            carry = c.get("CARRY4", 0)
            lutmem = total(c, [n for n in c if n.startswith("SRL") or re.match(r"RAM(32|64|128|256)", n)])
        else:
            luts = c.get("LUT4", 0)
            ffs = c.get("TRELLIS_FF", 0)
            dsps = c.get("MULT18X18D", 0)
            brams = f"{c.get('DP16KD', 0)}"
            carry = c.get("CCU2C", 0)
            lutmem = total(c, ["TRELLIS_DPR16X4"])
        print(f"| {target} | {lanes} | {luts} | {ffs} | {dsps} | {brams} | {carry} | {lutmem} |")
print()
print("synth_ecp5 flattens the design before mapping, synth_xilinx does not (without -flatten); with -flatten "
      "synth_xilinx also maps to more LUTs (wide multiplexers), so the two targets' LUT counts are not directly "
      "comparable.")
print()
print("Columns: xilinx (7-series) LUTs = LUT1..LUT6, FFs = FD*, DSPs = DSP48E1, block RAMs in RAMB36 units "
      "(RAMB18E1 = 0.5), carry cells = CARRY4, LUTs as SRL / RAM = SRL16E, SRLC32E and LUT-RAM cells; "
      "ecp5 LUTs = LUT4 (not counting the 2 LUT4s of each CCU2C carry cell), FFs = TRELLIS_FF, "
      "DSPs = MULT18X18D, block RAMs = DP16KD, LUTs as RAM = TRELLIS_DPR16X4.")
print()
print(f"Made by bench/rtl_cost.sh with `yosys -p \"{read_rtl}; chparam -set LANES <n> {sweep_params} "
      f"voxcd_device; <synth> -top voxcd_device; stat -json\"`, `<synth>` = `synth_xilinx -noiopad; flatten` or "
      f"`synth_ecp5`; {yosys_version}.")
print()

# ---- Place and route ----
with open("ice40.json") as f:
    top = json.load(f)["modules"]["voxcd_fmax_top"]["netnames"]
in_bits = len(top["in_q"]["bits"])
out_bits = len(top["out_q"]["bits"])
dsp_cells = cells("ice40_dsp.stat.json").get("SB_MAC16", 0)
synth_lcs = cells("ice40.stat.json").get("SB_LUT4", 0)

print("### Distance devices: place and route on an iCE40" if distance else "### Place and route on an iCE40")
print()
print(f"voxcd_device with {params_text(pnr_params)}, inside the measurement wrapper bench/voxcd_fmax_top.sv "
      f"(a {in_bits}-bit input shift register drives every device input, {out_bits} registered device outputs are "
      f"XOR-reduced to one pin; the logic cells below include these registers). Fmax is the median of nextpnr "
      f"seeds {', '.join(map(str, seeds))} (all three in brackets); lookups per second = Fmax x LANES, the peak "
      f"rate of one point per lane per cycle (a slot with r > 1 hit records takes r cycles).")
print()
print("| device | logic cells | RAMs (4 kbit) | Fmax (MHz), median [seeds] | lookups / s |")
print("|---|--:|--:|--:|--:|")
lanes = int(re.search(r"-set LANES (\d+)", pnr_params).group(1))
for dev, name in (("hx8k", "iCE40 HX8K (ct256)"), ("up5k", "iCE40 UP5K (sg48)")):
    if dev not in pnr_devices:
        continue
    fmax = []
    for seed in seeds:
        with open(f"{dev}-{seed}.report.json") as f:
            rep = json.load(f)
        # The clock's "Max frequency for clock" after routing (the one clock domain of the design).
        (clk,) = rep["fmax"].values()
        fmax.append(clk["achieved"])
        util = rep["utilization"]
    med = statistics.median(fmax)
    lc, ram = util["ICESTORM_LC"], util["ICESTORM_RAM"]
    print(f"| {name} | {lc['used']} / {lc['available']} | {ram['used']} / {ram['available']} | "
          f"{med:.2f} [{', '.join(f'{x:.2f}' for x in fmax)}] | {med * lanes / 1e3:.3f} G "
          f"({med * lanes:.1f} M) |")
print()
if distance:
    print(f"`synth_ice40 -dsp` would need {dsp_cells} SB_MAC16; the row uses `synth_ice40` without -dsp "
          f"(multipliers in logic cells), as the 2-bit device's rows do; only the HX8K is placed.")
else:
    print(f"`synth_ice40 -dsp` would need {dsp_cells} SB_MAC16 (nine MWxPW products and two index products per "
          f"lane); the UP5K has 8, so both rows use `synth_ice40` without -dsp (multipliers in logic cells).")
print()
print(f"Made by bench/rtl_cost.sh with `yosys -p \"{read_rtl} voxcd_fmax_top.sv; chparam ... voxcd_fmax_top; "
      f"synth_ice40 -top voxcd_fmax_top -json ice40.json\"` ({synth_lcs} SB_LUT4), then `nextpnr-ice40 --hx8k "
      f"--package ct256`{'' if distance else ' or `--up5k --package sg48`'}, `--json ice40.json --freq 12 --seed <s>`, and icepack; "
      f"{yosys_version}; {nextpnr_version}.")
print()
cpu_secs = sum(seconds(x) for x in cpu.split())
print(f"Run time: {total_secs} s wall ({synth_secs} s of synthesis), {cpu_secs:.0f} s CPU; "
      f"{len(sweep_lanes) * 2 + 2} yosys and {len(pnr_devices) * len(seeds)} nextpnr runs, {jobs} at a time.")
EOF
