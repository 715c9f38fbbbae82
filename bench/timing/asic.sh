# shellcheck shell=bash
# bench/timing/asic.sh: the ASIC flow of bench/timing.sh, shared with bench/energy.sh. Source it; it sets the flow's
# constants (the goal clock, the SRAM macros' timing, the wire load model, the fanout limit, the liberty file, the
# yosys and ABC scripts) and defines
#   asic_flow D [CFG]  synthesis onto the OSU 0.18 um standard cells of voxcd_device at depth D with the chparam
#                      settings CFG (default: $default_cfg) and static timing at the goal clock, in asic-dD/ of the
#                      current directory, which must hold the RTL (rtl/voxcd.f's files), kogge_stone.v and
#                      bench/timing/'s scripts; it leaves netlist.v, srams.lib, srams.json, area.txt and sta.txt there.
# The caller sets read_rtl ("read_verilog -sv FILES...").

GOAL_MHZ=200            # the ASIC goal (docs/hardware.md): the clock ABC maps for and OpenSTA checks
SRAM_ACCESS_NS=2.5      # an SRAM macro's read: data valid this long after the clock edge
SRAM_SETUP_NS=0.4       # ... its address, data and enables sampled with this setup
SRAM_HOLD_NS=0.1
WIRE_UM=25              # wire load model: micrometres of wire per net and per load on it
WIRE_FF_UM=0.2          # ... at this capacitance per micrometre (metal 2 at 0.18 um with fringe)
FANOUT=8                # largest fanout after the buffer trees
LIB=/usr/share/qflow/tech/osu018/osu018_stdcells.lib
# yosys `synth -flatten` with adders and comparators as Kogge-Stone prefixes (host/sizing/kogge_stone.v) rather than
# ripples, as datapath synthesis builds them; host/sizing/asic_cost.cpp (voxcd size --cost) runs the same commands.
ASIC_SYNTH="synth -top voxcd_device -flatten -run begin:fine; opt -fast -full; memory_map; opt -full;
  techmap -map +/techmap.v -map kogge_stone.v; opt -fast; abc -fast; opt -fast; synth -top voxcd_device -run check:"
# ABC's mapping onto the cells for the goal period ({D} is "-D <ps>"), then buffering (at most 12 loads on a net ABC
# sees), upsizing and downsizing for it; commas are blanks (yosys `abc -script +...`). voxcd size --cost uses the same.
ABC_SCRIPT="+strash;&get,-n;&fraig,-x;&put;dc2;strash;&get,-n;&dch,-f;&nf,{D};&put;buffer,-N,12;upsize,{D};dnsize,{D};stime,-p"
default_cfg="-set LANES 4 -set SAW 12 -set MAW 12"
depth_set() { if (($1 > 0)); then echo "-set Depth $1"; fi; }  # Depth 0 is every RTL's default

# asic_flow D [CFG]: synthesis onto OSU 0.18 um and static timing of the configuration CFG at depth D, in asic-dD/.
asic_flow() {
  local d=$1 cfg="${2:-$default_cfg}" dir="asic-d$1" period_ps
  period_ps=$(python3 -c "print(round(1e6 / $GOAL_MHZ))")
  mkdir -p "$dir"
  cp ./*.sv "$dir/"
  cp sram_models.py fanout_buffers.py kogge_stone.v "$dir/"
  cd "$dir"
  # Pass 1: the RAM shapes of this configuration.
  yosys -q -l pass1.log -p "$read_rtl; chparam $cfg $(depth_set "$d") voxcd_device;
    hierarchy -top voxcd_device; proc; write_json pass1.json"
  python3 sram_models.py pass1.json "$SRAM_ACCESS_NS" "$SRAM_SETUP_NS" "$SRAM_HOLD_NS" "$WIRE_UM" "$WIRE_FF_UM"
  # Pass 2: the RAMs become macros, the rest is mapped onto the standard cells for the goal period.
  yosys -q -l synth.log -p "read_verilog srams.v; $read_rtl; chparam $cfg $(depth_set "$d") voxcd_device;
    hierarchy -top voxcd_device; proc; rename -top voxcd_device; script srams.ys; hierarchy -top voxcd_device;
    $ASIC_SYNTH; dfflibmap -liberty $LIB;
    abc -liberty $LIB -D $period_ps -script \"$ABC_SCRIPT\"; opt_clean -purge; write_json mapped.json"
  yosys -q -p "read_liberty -lib $LIB; read_json mapped.json; write_json directions.json"
  python3 fanout_buffers.py directions.json buffered.json voxcd_device BUFX4 A Y "$FANOUT" clk_i >buffers.txt
  yosys -q -l netlist.log -p "read_json buffered.json; hierarchy -top voxcd_device; setundef -zero; splitnets -ports;
    insbuf -buf BUFX2 A Y; opt_clean -purge; tee -q -o area.txt stat -liberty $LIB;
    write_verilog -noattr -noexpr -nohex -nodec netlist.v"
  cat >sta.tcl <<STA
read_liberty $LIB
read_liberty srams.lib
read_verilog netlist.v
link_design voxcd_device
set_wire_load_model -name voxcd_wire -library voxcd_sram
create_clock -name clk -period $(python3 -c "print(1e3 / $GOAL_MHZ)") [get_ports clk_i]
set_input_delay 0 -clock clk [delete_from_list [all_inputs] [get_ports clk_i]]
set_output_delay 0 -clock clk [all_outputs]
report_checks -path_delay max -fields {fanout cap slew} -digits 3
report_wns
report_tns
report_checks -path_delay max -group_count 100000 -format end
STA
  sta -exit sta.tcl >sta.txt 2>&1
  grep -q "^wns" sta.txt || { cat sta.txt; return 1; }
}
