#!/usr/bin/env bash
# bench/results.sh [--quick]: regenerates every measured block of docs/results.md and its plots docs/results/*.png.
#
# Builds bench_results, bench_simulate, bench_pair and bench_broadphase in build-results/ (Release), runs them,
# synthesises voxcd_device at a few fixed-point widths with yosys, draws the plots with gnuplot and splices each
# table into docs/results.md (bench/splice.sh). The data behind the plots stays in build-results/results/.
# Full run: about 30 minutes on 2 cores; --quick (fewer repeats, poses, sizes and frames): a few minutes.
#
# Needs the Debian packages gnuplot-nox (plots), yosys (hardware cost) and python3, besides the build's own.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
quick=0
for a in "$@"; do
  case "$a" in
    --quick) quick=1 ;;
    *) echo "usage: bash bench/results.sh [--quick]" >&2; exit 2 ;;
  esac
done

missing=0
need() {  # tool debian-package
  if ! command -v "$1" >/dev/null 2>&1; then
    echo "results.sh: $1 not found: install the Debian package $2 (apt-get install $2)" >&2
    missing=1
  fi
}
need gnuplot gnuplot-nox
need yosys yosys
need python3 python3
need cmake cmake
need ninja ninja-build
if ((missing)); then exit 1; fi

build=build-results
data="$build/results"
plots=docs/results
mkdir -p "$data" "$plots"
start=$SECONDS
echo "results.sh: building in $build" >&2
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" -j2 --target bench_results bench_simulate bench_pair bench_broadphase >/dev/null

if ((quick)); then
  reps=3 poses=32 err_poses=400 points=200000 frames=200 big_frames=10
  shells=25,92,219,606,1150,2314,5321,9337 maps=20,120,700,3500,16000,80000,200000
  voxels=0.4,0.2,0.1,0.05 widths=8:2,12:4,16:8,20:8 cost_widths=(8:2 16:8)
  fig14_counts=2,4,8,16,32,64,128,256 big_counts=256,1024,4096,16384
  pair_args=(--repeats 3 --poses 20 --voxel 0.04) bp_args=(--max-n 4096 --frames 60 --repeats 3)
else
  reps=7 poses=256 err_poses=4000 points=2000000 frames=1000 big_frames=30
  shells=25,92,219,384,606,840,1150,1509,1909,2314,5321,9337
  maps=20,50,120,300,700,1500,3500,8000,16000,35000,80000,200000
  voxels=0.4,0.2,0.1,0.05,0.025 widths=8:2,10:4,12:4,14:6,16:8,20:8 cost_widths=(8:2 12:4 16:8 20:8)
  fig14_counts=2,4,8,16,32,48,64,128,192,256 big_counts=256,1024,4096,16384,65536
  pair_args=(--repeats 5 --poses 60) bp_args=(--max-n 65536 --frames 100 --repeats 3 --budget 60)
fi

run() {  # label command...: runs a bench program, its progress to the log
  echo "results.sh: $1 ($((SECONDS - start)) s)" >&2
  shift
  "$@" >/dev/null 2>>"$data/progress.log"
}
: >"$data/progress.log"
run "pairs: Table 1, Figs. 11-13" "$build/bench_results" pairs --repeats "$reps" --poses "$poses" \
  --shells "$shells" --maps "$maps" --out "$data/pairs.md" --csv "$data/pairs.csv"
run "speed against error" "$build/bench_results" error --repeats "$reps" --poses "$err_poses" --voxels "$voxels" \
  --out "$data/error.md" --csv "$data/error.csv"
run "fixed-point widths" "$build/bench_results" fixed --points "$points" --widths "$widths" \
  --out "$data/fixed.md" --csv "$data/fixed.csv"
run "N-body: Fig. 14, the paper's pipeline" "$build/bench_simulate" --counts "$fig14_counts" \
  --prunings all,sphere,sap,coherent,queue --voxel 1 --no-midphase --frames "$frames" --repeats "$reps" \
  --out "$data/nbody.md" --csv "$data/nbody.csv"
run "N-body: Fig. 14 with the mid-phase" "$build/bench_simulate" --counts "$fig14_counts" \
  --prunings all,sphere,sap,coherent,queue --voxel 1 --frames "$frames" --repeats "$reps" \
  --out "$data/nbody_mid.md" --csv "$data/nbody_mid.csv"
run "N-body: large N" "$build/bench_simulate" --counts "$big_counts" --prunings sap,tree --frames "$big_frames" \
  --repeats 3 --out "$data/large.md" --csv "$data/large.csv"
run "peers: pair queries (bench_pair)" "$build/bench_pair" "${pair_args[@]}" --out "$data/peers_pair.md"
run "peers: broadphases (bench_broadphase)" "$build/bench_broadphase" "${bp_args[@]}" --out "$data/peers_bp.md" \
  --csv "$data/peers_bp.csv"

# ---- hardware cost against the fixed-point widths (yosys synth_ecp5 of voxcd_device) ----
echo "results.sh: yosys at widths ${cost_widths[*]} ($((SECONDS - start)) s)" >&2
load="$(cut -d' ' -f1 /proc/loadavg)"
ys="$(mktemp -d)"
trap 'rm -rf "$ys"' EXIT
rtl_files=(voxcd_pkg.sv voxcd_ram.sv voxcd_lane.sv voxcd_device.sv)
for f in "${rtl_files[@]}"; do cp "rtl/$f" "$ys/$f"; done
pids=()
for w in "${cost_widths[@]}"; do
  mf=${w%:*} pf=${w#*:}
  params="-set LANES 1 -set SAW 12 -set MAW 12 -set MF $mf -set MW $((mf + 2)) -set PF $pf -set PW $((pf + 16))"
  while (($(jobs -pr | wc -l) >= 2)); do wait -n || true; done
  (cd "$ys" && yosys -q -l "cost-$mf-$pf.log" -p "read_verilog -sv ${rtl_files[*]}; chparam $params voxcd_device;
    synth_ecp5 -top voxcd_device; tee -q -o cost-$mf-$pf.json stat -json" >/dev/null 2>&1) &
  pids+=("$!")
done
for p in "${pids[@]}"; do
  wait "$p" || { echo "results.sh: yosys failed, see $ys/cost-*.log" >&2; tail -n 20 "$ys"/cost-*.log >&2; exit 1; }
done
python3 - "$ys" "$data" "$(yosys -V | head -n 1)" "$load" "${cost_widths[@]}" <<'EOF'
import csv, datetime, json, os, sys
ys, data, version, load, *widths = sys.argv[1:]
rates = {}
with open(os.path.join(data, "fixed.csv")) as f:
    for r in csv.DictReader(f):
        rates[(r["mf"], r["pf"])] = r
model = "unknown processor"
with open("/proc/cpuinfo") as f:
    for line in f:
        if line.startswith("model name"):
            model = line.split(":", 1)[1].strip()
            break
rows = []
for w in widths:
    mf, pf = w.split(":")
    with open(os.path.join(ys, f"cost-{mf}-{pf}.json")) as f:
        stat = json.load(f)
    if "design" in stat:  # totals over the (flattened) design
        c = stat["design"]["num_cells_by_type"]
    else:
        (mod,) = stat["modules"].values()
        c = mod["num_cells_by_type"]
    rows.append((mf, pf, c.get("LUT4", 0), c.get("TRELLIS_FF", 0), c.get("MULT18X18D", 0), c.get("CCU2C", 0),
                 c.get("DP16KD", 0)))
with open(os.path.join(data, "cost.csv"), "w") as f:
    f.write("mf,pf,lut4,ff,mult18,ccu2c,dp16kd,shell_rate,any_rate\n")
    for r in rows:
        rate = rates.get((r[0], r[1]), {})
        f.write(",".join(map(str, r)) + f",{rate.get('shell_rate', '')},{rate.get('any_rate', '')}\n")
with open(os.path.join(data, "cost.md"), "w") as f:
    f.write(f"_Generated by `bash bench/results.sh` (yosys part) on {datetime.date.today()} ({model}, "
            f"{os.cpu_count()} hardware threads; load average {float(load):.1f} at the start)._\n\n")
    f.write("| MF | PF | MW | PW | LUT4 | FFs | MULT18X18D | CCU2C (carry) | DP16KD | disagreement, shell points "
            "| disagreement, any points |\n|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|\n")
    for mf, pf, lut, ff, mul, ccu, bram in rows:
        rate = rates.get((mf, pf), {})
        fmt = lambda x: f"{float(x):.2e}" if x not in ("", None) else "-"
        f.write(f"| {mf} | {pf} | {int(mf) + 2} | {int(pf) + 16} | {lut} | {ff} | {mul} | {ccu} | {bram} | "
                f"{fmt(rate.get('shell_rate'))} | {fmt(rate.get('any_rate'))} |\n")
    f.write(f"\nvoxcd_device with LANES=1, SAW=MAW=12 (memory depths cut as in docs/hardware.md), MW = MF + 2, "
            f"PW = PF + 16, other widths the defaults; `yosys -p \"read_verilog -sv voxcd_pkg.sv voxcd_ram.sv "
            f"voxcd_lane.sv voxcd_device.sv; chparam ... voxcd_device; synth_ecp5 -top voxcd_device; stat -json\"` "
            f"({version}). One synthesis per configuration: the counts are deterministic. Disagreement rates from "
            f"the table above (the same run).\n")
EOF

# ---- plots ----
echo "results.sh: plots ($((SECONDS - start)) s)" >&2
for gp in bench/plot/*.gp; do
  gnuplot -e "data='$data'; out='$plots'; voxels='${voxels//,/ }'" "$gp"
done

# ---- the document ----
for block in pairs error fixed cost nbody nbody_mid large peers_pair peers_bp; do
  bash bench/splice.sh docs/results.md "results-$block" "$data/$block.md" >/dev/null
done
echo "results.sh: wrote docs/results.md and $(ls "$plots"/*.png | wc -l) plots in $plots in $((SECONDS - start)) s" >&2
