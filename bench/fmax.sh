#!/usr/bin/env bash
# bench/fmax.sh: the measured clock of the RTL, as a Markdown fragment on stdout.
#
#   1. iCE40 place and route: voxcd_device at the reduced widths of bench/rtl_cost.sh (LANES 1), and the same
#      widths at LANES 2 (the next larger configuration), inside bench/voxcd_fmax_top.sv; synth_ice40 (multipliers
#      in logic cells), then nextpnr-ice40 on an HX8K (ct256) and an UP5K (sg48) with seeds 1, 2, 3: logic cells,
#      RAMs and the median "Max frequency for clock"; a configuration that does not fit is reported as such.
#   2. Logic depth of the default configuration (LANES 4, default widths, SAW = MAW = 12 as in bench/rtl_cost.sh)
#      after `synth_xilinx -flatten`: the longest path between registers (yosys ltp over every cell but the ones
#      that hold state: flip-flops, block RAMs, shift-register LUTs, LUT RAMs and DSP48E1s, into which synth_xilinx
#      packs the pipeline registers around the multipliers), with the LUTs and carry cells on it.
#
# Needs yosys, nextpnr-ice40 and python3 (Debian packages). JOBS tool runs at a time (default 2).
# Usage: bash bench/fmax.sh [> fmax.md]
set -euo pipefail
JOBS="${JOBS:-2}"
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
# The RTL in the order of rtl/voxcd.f (// lines are comments; yosys skips Verilator's *.vlt).
mapfile -t rtl_files < <(grep -v -e "^[[:space:]]*//" -e "^[[:space:]]*$" -e "\.vlt[[:space:]]*$" "$root/rtl/voxcd.f")
for tool in yosys nextpnr-ice40 python3; do
  command -v "$tool" >/dev/null || { echo "fmax.sh: $tool not found (apt-get install $tool)" >&2; exit 1; }
done
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
for f in "${rtl_files[@]}"; do cp "$root/rtl/$f" "$tmp/$f"; done
cp "$root/bench/voxcd_fmax_top.sv" "$tmp/"
cd "$tmp"
read_rtl="read_verilog -sv ${rtl_files[*]}"
small="-set PW 10 -set PF 2 -set MW 8 -set MF 6 -set TW 20 -set DW 5 -set MEMW 16 -set SAW 8 -set MAW 9 -set TAGW 4"

run() {  # LOG CMD...: at most JOBS at a time
  local log="$1"; shift
  while (($(jobs -pr | wc -l) >= JOBS)); do wait -n || true; done
  "$@" >"$log" 2>&1 &
}
start=$SECONDS
for lanes in 1 2; do
  run "ice40-l$lanes.log" yosys -q -l "ice40-l$lanes.yslog" -p "$read_rtl voxcd_fmax_top.sv;
    chparam -set LANES $lanes $small voxcd_fmax_top; synth_ice40 -top voxcd_fmax_top -json ice40-l$lanes.json"
done
run xilinx.log yosys -q -l xilinx.yslog -p "$read_rtl; chparam -set SAW 12 -set MAW 12 voxcd_device;
  synth_xilinx -flatten -noiopad -top voxcd_device; select -set comb t:FD* t:RAMB* %u t:SRL* %u t:RAM32M %u t:RAM64M %u t:DSP48E1 %u %n;
  tee -q -o ltp.txt ltp @comb; write_json xilinx.json"
wait
for lanes in 1 2; do
  for dev in hx8k up5k; do
    case $dev in hx8k) args="--hx8k --package ct256" ;; up5k) args="--up5k --package sg48" ;; esac
    for seed in 1 2 3; do
      # shellcheck disable=SC2086
      run "pnr-l$lanes-$dev-$seed.log" nextpnr-ice40 $args --json "ice40-l$lanes.json" --freq 12 --seed "$seed" \
        --report "pnr-l$lanes-$dev-$seed.json"
    done
  done
done
wait
secs=$((SECONDS - start))
python3 - "$small" "$secs" "$(yosys -V | head -n 1)" "$(nextpnr-ice40 --version 2>&1 | head -n 1)" <<'PY'
import json, os, re, statistics, sys
small, secs, yv, nv = sys.argv[1:]
print("### Measured clock")
print()
print("voxcd_device inside bench/voxcd_fmax_top.sv at " +
      ", ".join(f"{k}={v}" for k, v in re.findall(r"-set (\w+) (\S+)", small)) +
      " (the reduced configuration of the table above) with LANES 1 and 2; synth_ice40 (multipliers in logic cells), "
      "nextpnr-ice40 seeds 1, 2, 3, median Max frequency [all three]. Since the output slice (voxcd_skid), the "
      "consumer's ready reaches only the slice's registers.")
print()
print("| LANES | device | logic cells | RAMs (4 kbit) | Fmax (MHz), median [seeds] |")
print("|--:|---|--:|--:|--:|")
for lanes in (1, 2):
    for dev, name in (("hx8k", "iCE40 HX8K (ct256)"), ("up5k", "iCE40 UP5K (sg48)")):
        fmax, lc, ram, fits = [], None, None, True
        for seed in (1, 2, 3):
            rep = f"pnr-l{lanes}-{dev}-{seed}.json"
            if not os.path.exists(rep):
                fits = False
                continue
            r = json.load(open(rep))
            fmax.append(min(v["achieved"] for v in r["fmax"].values()))
            u = r["utilization"]
            lc = f'{u["ICESTORM_LC"]["used"]} / {u["ICESTORM_LC"]["available"]}'
            ram = f'{u["ICESTORM_RAM"]["used"]} / {u["ICESTORM_RAM"]["available"]}'
        if not fits or not fmax:
            log = open(f"pnr-l{lanes}-{dev}-1.log").read()
            m = re.search(r"ICESTORM_LC:\s+(\d+)/\s*(\d+)", log)
            need = f"{m.group(1)} / {m.group(2)}" if m else "-"
            print(f"| {lanes} | {name} | {need} | - | does not fit |")
            continue
        print(f"| {lanes} | {name} | {lc} | {ram} | {statistics.median(fmax):.2f} [{', '.join(f'{f:.2f}' for f in fmax)}] |")
print()
# Logic depth after synth_xilinx.
cells = {}
# chparam may leave the top under a $paramod name: the module whose name ends in voxcd_device.
mod = next(v for k, v in json.load(open("xilinx.json"))["modules"].items() if k.split("\\")[-1] == "voxcd_device")
for n, c in mod["cells"].items():
    cells[n] = c["type"]
text = open("ltp.txt").read()
length = int(re.search(r"length=(\d+)", text).group(1))
via = re.findall(r"\(via (\S+)\)", text)
kinds = {}
for v in via:
    t = cells.get(v, cells.get(v.lstrip("\\"), "?"))
    t = "LUT" if t.startswith("LUT") else t
    kinds[t] = kinds.get(t, 0) + 1
luts, carry = kinds.get("LUT", 0), kinds.get("CARRY4", 0)
other = {k: v for k, v in kinds.items() if k not in ("LUT", "CARRY4")}
# The default device clock of the tool is this estimate (host/device/clock.h): after a run that gives other figures,
# host.DeviceClock.DefaultEqualsTheLogicDepthEstimateOfHardwareMd fails until the constants there follow.
lut_ns, carry_ns = 0.5, 0.1
est = luts * lut_ns + carry * carry_ns
print(f"Logic depth of the default configuration (LANES 4, default widths, SAW = MAW = 12) after `synth_xilinx "
      f"-flatten`: the longest path between state-holding cells (flip-flops, block RAMs, SRLs, LUT RAMs and "
      f"DSP48E1s, which hold the multipliers' pipeline registers) has {length} cells: {luts} LUT levels and {carry} "
      f"CARRY4 cells" + "".join(f", {v} {k}" for k, v in sorted(other.items())) + ". "
      f"Assuming {lut_ns} ns per LUT level (the LUT and its routing) and {carry_ns} ns per CARRY4 (round figures of "
      f"ours for a 7-series -1 part, not a vendor timing model: yosys has no 7-series delays, and a vendor static "
      f"timing analysis, with the DSP48E1s' own setup and clock-to-out times, gives the real figure; the wide-mux "
      f"cells MUXF7/MUXF8 are not counted), the path "
      f"takes {est:.1f} ns: an estimated clock of {1000 / est:.0f} MHz.")
print()
print(f"Made by `bash bench/fmax.sh` ({secs} s wall); {yv}; {nv}.")
PY
