# shellcheck shell=bash
# bench/energy/netlist.sh: the mapped 0.18 um netlist of one configuration for bench/energy.sh, made by
# bench/timing/asic.sh's asic_flow (the flow of bench/timing.sh) once and kept under build/energy/ for reruns.
# Source it after bench/timing/asic.sh; then
#   energy_netlist ROOT CFG D  prints the directory (build/energy/netlist-KEY/asic-dD) that holds netlist.v,
#                              srams.lib and srams.json of the chparam settings CFG at depth D, synthesising it when
#                              it is missing; KEY hashes CFG, D, the RTL and the flow's scripts, so a change to any of
#                              them makes a new netlist.
energy_netlist() {
  local root=$1 cfg=$2 d=$3 key dir f
  local -a files
  mapfile -t files < <(grep -v -e "^[[:space:]]*//" -e "^[[:space:]]*$" -e "\.vlt[[:space:]]*$" "$root/rtl/voxcd.f")
  key=$( (echo "$cfg depth $d"; cd "$root/rtl" && cat "${files[@]}"; cd "$root" && cat bench/timing/asic.sh \
         bench/timing/sram_models.py bench/timing/fanout_buffers.py host/sizing/kogge_stone.v) | sha1sum | cut -c1-12)
  dir="$root/build/energy/netlist-$key"
  if [ ! -s "$dir/asic-d$d/netlist.v" ] || [ ! -s "$dir/asic-d$d/sta.txt" ]; then
    echo "energy: synthesising '$cfg' at depth $d into $dir (10 to 30 minutes; kept for reruns)" >&2
    rm -rf "$dir"
    mkdir -p "$dir"
    for f in "${files[@]}"; do cp "$root/rtl/$f" "$dir/$f"; done
    cp "$root/bench/timing/"*.py "$root/host/sizing/kogge_stone.v" "$dir/"
    # shellcheck disable=SC2034  # asic_flow reads it
    read_rtl="read_verilog -sv ${files[*]}"
    (cd "$dir" && asic_flow "$d" "$cfg") >"$dir/asic.log" 2>&1 || {
      echo "energy: synthesis failed, see $dir/asic.log:" >&2; tail -n 20 "$dir/asic.log" >&2; return 1; }
  fi
  echo "$dir/asic-d$d"
}
