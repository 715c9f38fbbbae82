"""The device's RAMs as SRAM macros for the ASIC flow of bench/timing.sh.

Reads a yosys JSON of the elaborated device (after `hierarchy; proc`), finds every module derived from voxcd_ram
(its Width and AddrW) and writes, for each shape W x 2^A:
  - srams.v:   a Verilog black box `voxcd_sram_<W>x<2^A>` with voxcd_ram's ports (yosys keeps it as a cell);
  - srams.lib: a Liberty library with the same cells for OpenSTA: read data valid ACCESS ns after the clock edge
               (plus the load times the stated drive resistance), address, data and enables sampled with SETUP ns
               of setup and HOLD ns of hold, area 0 (the macros are listed apart from the standard cell area); and
               the wire load model of the flow (WIRE_UM micrometres of wire per net and per load, WIRE_FF_UM fF per
               micrometre);
  - srams.ys:  `chtype -map` lines that turn each derived voxcd_ram into its macro;
  - srams.json: the shapes and instance counts, for the report.

Usage: python3 sram_models.py PASS1.json ACCESS_NS SETUP_NS HOLD_NS WIRE_UM WIRE_FF_UM
"""
import json
import sys


def param(value):
    """A yosys JSON parameter: a binary string (or an int)."""
    return int(value, 2) if isinstance(value, str) else int(value)


def shapes(design):
    """{old module name: (width, addr_bits)} of every module derived from voxcd_ram."""
    out = {}
    for name, module in design["modules"].items():
        if name.split("\\")[-1] != "voxcd_ram":
            continue
        p = module.get("parameter_default_values", {})
        out[name] = (param(p["Width"]), param(p["AddrW"]))
    return out


def instances(design, old_names):
    """How many cells of each derived voxcd_ram type the top module holds, through every level of the hierarchy."""
    modules = design["modules"]
    top = next(name for name, m in modules.items() if m.get("attributes", {}).get("top"))
    count = {n: 0 for n in old_names}

    def walk(name, times):
        for cell in modules[name].get("cells", {}).values():
            if cell["type"] in count:
                count[cell["type"]] += times
            elif cell["type"] in modules:
                walk(cell["type"], times)

    walk(top, 1)
    return count


def macro_name(width, addr):
    return f"voxcd_sram_{width}x{1 << addr}"


def verilog(width, addr):
    return (f"(* blackbox *) module {macro_name(width, addr)} (input clk_i, input we_i, input [{addr - 1}:0] waddr_i, "
            f"input [{width - 1}:0] wdata_i, input re_i, input [{addr - 1}:0] raddr_i, "
            f"output [{width - 1}:0] rdata_o);\nendmodule\n")


def scalar(kind, value):
    return f'{kind}(scalar) {{ values("{value}"); }}'


def liberty_cell(width, addr, access, setup, hold):
    cap = 0.01  # pF on every input pin: an SRAM macro's input buffer
    drive = 2.0  # ns per pF on the read data: a strong output driver
    checks = "".join(
        f'      timing() {{ related_pin : "clk_i"; timing_type : {kind}; {scalar("rise_constraint", v)} '
        f'{scalar("fall_constraint", v)} }}\n' for kind, v in (("setup_rising", setup), ("hold_rising", hold)))

    def pin(name, bits=None):
        head = f"    bus({name}) {{ bus_type : b{bits};" if bits else f"    pin({name}) {{"
        return f"{head} direction : input; capacitance : {cap};\n{checks}    }}\n"

    read = (f'    bus(rdata_o) {{ bus_type : b{width}; direction : output;\n'
            f'      timing() {{ related_pin : "clk_i"; timing_type : rising_edge;\n'
            f'        cell_rise(load_2) {{ values("{access}, {access + drive}"); }} '
            f'cell_fall(load_2) {{ values("{access}, {access + drive}"); }}\n'
            f'        rise_transition(load_2) {{ values("0.2, {0.2 + 2 * drive}"); }} '
            f'fall_transition(load_2) {{ values("0.2, {0.2 + 2 * drive}"); }} }}\n    }}\n')
    return (f"  cell({macro_name(width, addr)}) {{\n    area : 0;\n"
            f"    pin(clk_i) {{ direction : input; capacitance : {2 * cap}; clock : true; }}\n"
            + pin("we_i") + pin("waddr_i", addr) + pin("wdata_i", width) + pin("re_i") + pin("raddr_i", addr)
            + read + "  }\n")


def liberty(shape_list, access, setup, hold, wire_um, wire_ff_um):
    widths = sorted({w for w, _ in shape_list} | {a for _, a in shape_list})
    types = "".join(f"  type (b{w}) {{ base_type : array; data_type : bit; bit_width : {w}; bit_from : {w - 1}; "
                    f"bit_to : 0; downto : true; }}\n" for w in widths)
    head = f"""library(voxcd_sram) {{
  delay_model : table_lookup;
  time_unit : "1ns";
  voltage_unit : "1V";
  current_unit : "1uA";
  capacitive_load_unit (1,pf);
  pulling_resistance_unit : "1kohm";
  leakage_power_unit : "1nW";
  slew_upper_threshold_pct_rise : 80;
  slew_lower_threshold_pct_rise : 20;
  slew_upper_threshold_pct_fall : 80;
  slew_lower_threshold_pct_fall : 20;
  input_threshold_pct_rise : 50;
  input_threshold_pct_fall : 50;
  output_threshold_pct_rise : 50;
  output_threshold_pct_fall : 50;
  nom_process : 1;
  nom_voltage : 1.8;
  nom_temperature : 25;
  wire_load("voxcd_wire") {{
    resistance : 0;
    capacitance : {wire_ff_um / 1000};
    area : 0;
    slope : {wire_um};
    fanout_length(1, {wire_um});
  }}
  lu_table_template(load_2) {{
    variable_1 : total_output_net_capacitance;
    index_1 ("0.0, 1.0");
  }}
"""
    return head + types + "".join(liberty_cell(w, a, access, setup, hold) for w, a in shape_list) + "}\n"


def main(pass1, access, setup, hold, wire_um, wire_ff_um):
    with open(pass1) as f:
        design = json.load(f)
    found = shapes(design)
    if not found:
        sys.exit(f"sram_models.py: {pass1} has no module derived from voxcd_ram")
    count = instances(design, found)
    shape_list = sorted(set(found.values()))
    with open("srams.v", "w") as f:
        f.write("".join(verilog(w, a) for w, a in shape_list))
    with open("srams.lib", "w") as f:
        f.write(liberty(shape_list, float(access), float(setup), float(hold), float(wire_um), float(wire_ff_um)))
    with open("srams.ys", "w") as f:
        f.write("".join(f"chtype -map {old} {macro_name(*shape)}\n" for old, shape in sorted(found.items())))
    macros = {}
    for old, (w, a) in found.items():
        m = macros.setdefault(macro_name(w, a), {"width": w, "words": 1 << a, "count": 0})
        m["count"] += count[old]
    with open("srams.json", "w") as f:
        json.dump(macros, f, indent=1, sort_keys=True)


if __name__ == "__main__":
    if len(sys.argv) != 7:
        sys.exit(__doc__)
    main(*sys.argv[1:])
