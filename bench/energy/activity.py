"""Switching activity of a simulation as OpenSTA commands on the mapped netlist (bench/energy.sh).

OpenSTA 2.0.17 reads no VCD or SAIF, and of user activities it keeps only those of input ports: it computes every
register output from its D input's propagated activity (overwriting a user activity there), and `set_power_activity
-pins` calls an undefined get_pins_error. So the measured register activities enter as input ports: POWER.v is
NETLIST with every flip-flop and latch (the cells of LIBERTY with an ff or latch group) whose output net carries an
RTL register's name in the trace (yosys keeps `g_lane[0].u_lane.g_row[0].px_q[41]`) cut from its net (its Q drives
a new wire ffq_N) and the net driven instead by a BUFX2 (rqbuf_N) from a new input port rq_N; the same for every
read data bit of the SRAM macros (rsbuf_N_B from rs_N_B). ACTIVITY.tcl sets each such port, and every original input
port bit, to its bit's toggle rate (toggles per clock cycle) and duty (fraction of cycles high) from TOGGLES.json
(bench/energy/toggles.py), and OpenSTA propagates them through the combinational logic. The buffers' output
switching power is the cut nets' switching power (the register's load as before); their internal power is the
flow's own, and bench/energy/report.py subtracts it (report_power -instances of rqbuf_* and rsbuf_*). Registers
not found in the trace keep OpenSTA's propagated activity. Instances and ports get plain names (ff_N, sram_N, pi_N;
escaped identifiers are awkward in Tcl).

Writes POWER.v, ACTIVITY.tcl and MATCH.json (how many register bits, input bits and macro outputs were found in the
trace, the names of those that were not, and each macro instance's RTL name and shape).
Usage: python3 activity.py NETLIST.v LIBERTY TOGGLES.json POWER.v ACTIVITY.tcl MATCH.json
"""
import json
import re
import sys

INSTANCE = re.compile(r"^(\s*)([A-Za-z_][\w$]*)\s+(\\\S+|[A-Za-z_][\w$]*)\s*\((.*?)\);", re.S | re.M)
CONNECTION = re.compile(r"\.(\w+)\(\s*(.*?)\s*\)(?=\s*[,)]|\s*$)", re.S)


def sequential_cells(liberty):
    cells, current = set(), None
    with open(liberty) as f:
        for line in f:
            m = re.match(r"\s*cell\s*\(\s*\"?(\w+)\"?\s*\)", line)
            if m:
                current = m.group(1)
            elif current and re.match(r"\s*(ff|latch)\s*\(", line):
                cells.add(current)
    return cells


def bit_of(net):
    """(RTL name, bit) of a netlist net expression: `\\a.b[0].c [41]`, `name[3]`, `\\esc `, `name`."""
    net = net.strip()
    if net.startswith("\\"):
        m = re.match(r"\\(\S+)(?:\s+\[(\d+)\])?$", net)
        if not m:
            return None
        return m.group(1), int(m.group(2) or 0)
    m = re.match(r"([A-Za-z_][\w$]*)(?:\s*\[(\d+)\])?$", net)
    if not m:
        return None
    return m.group(1), int(m.group(2) or 0)


def trace_name(name):
    """A yosys name as the trace has it: without the scopes of unnamed generate blocks (`genblk1`), which
    Verilator leaves out."""
    return re.sub(r"\.genblk\d+(?=\.)", "", name)


def lookup(signals, b):
    """The trace's signal and bit of a netlist bit (name, bit): the name itself, or an escaped name that holds its
    index (`job_tag_i[3]`, a port after splitnets -ports)."""
    if b is None:
        return None, 0
    name, bit = b
    if name in signals:
        return signals[name], bit
    name = trace_name(name)
    if name in signals:
        return signals[name], bit
    m = re.match(r"(.*)\[(\d+)\]$", name)
    if m and m.group(1) in signals:
        return signals[m.group(1)], int(m.group(2))
    return None, 0


def rate(sig, bit, cycles):
    if sig is None or bit >= sig["width"]:
        return None
    return sig["toggles"][bit] / cycles, sig["high"][bit] / cycles


def main(netlist, liberty, toggles_path, power_v, tcl, match_path):
    seq = sequential_cells(liberty)
    with open(toggles_path) as f:
        tog = json.load(f)
    cycles, signals = tog["cycles"], tog["signals"]
    with open(netlist) as f:
        text = f.read()
    lines, match = [], {"registers": 0, "registers_found": 0, "inputs": 0, "inputs_found": 0, "macro_bits": 0,
                        "macro_bits_found": 0, "missing": [], "macros": {}}
    counter = {"ff": 0, "sram": 0}
    extra_ports, extra_wires, buffers = [], [], []

    def instance(m):
        indent, cell, name, body = m.groups()
        if cell in seq:
            new = f"ff_{counter['ff']}"
            counter["ff"] += 1
            conns = dict(CONNECTION.findall(body))
            q = conns.get("Q")
            match["registers"] += 1
            b = bit_of(q) if q else None
            r = rate(*lookup(signals, b), cycles)
            if r is None:
                match["missing"].append(q)
            else:
                match["registers_found"] += 1
                k = counter["ff"] - 1
                extra_ports.append(f"rq_{k}")
                extra_wires.append(f"ffq_{k}")
                buffers.append(f"  BUFX2 rqbuf_{k} ( .A(rq_{k}), .Y({q} ) );")
                lines.append(f"set_power_activity -input_ports [get_ports rq_{k}] -activity {r[0]:.6g} "
                             f"-duty {r[1]:.6g}")
                body = re.sub(r"\.Q\(\s*" + re.escape(q) + r"\s*\)", f".Q(ffq_{k})", body, count=1)
            return f"{indent}{cell} {new} ({body});"
        if cell.startswith("voxcd_sram_"):
            new = f"sram_{counter['sram']}"
            counter["sram"] += 1
            rtl = name.lstrip("\\")
            if rtl + ".rdata_o" not in signals:
                rtl = trace_name(rtl)
            match["macros"][new] = {"rtl": rtl, "cell": cell}
            sig = signals.get(rtl + ".rdata_o")
            width = int(re.match(r"voxcd_sram_(\d+)x", cell).group(1))
            match["macro_bits"] += width
            conns = dict(CONNECTION.findall(body))
            concat = re.match(r"\{(.*)\}$", conns.get("rdata_o", "").strip(), re.S)
            elems = [e.strip() for e in concat.group(1).split(",")] if concat else []
            if sig is None or len(elems) != width:
                return f"{indent}{cell} {new} ({body});"
            k = counter["sram"] - 1
            cut = []
            for i, e in enumerate(elems):
                bit = width - 1 - i  # a concatenation lists the most significant bit first
                r = rate(sig, bit, cycles)
                match["macro_bits_found"] += 1
                extra_ports.append(f"rs_{k}_{bit}")
                extra_wires.append(f"srq_{k}_{bit}")
                buffers.append(f"  BUFX2 rsbuf_{k}_{bit} ( .A(rs_{k}_{bit}), .Y({e} ) );")
                lines.append(f"set_power_activity -input_ports [get_ports rs_{k}_{bit}] -activity {r[0]:.6g} "
                             f"-duty {r[1]:.6g}")
                cut.append(f"srq_{k}_{bit}")
            body = body.replace(conns["rdata_o"], "{ " + " , ".join(cut) + " }", 1)
            return f"{indent}{cell} {new} ({body});"
        return m.group(0)

    text = INSTANCE.sub(instance, text)
    # The input ports: `input \job_tag_i[3] ;` after splitnets -ports (or a plain one-bit name).
    ports = re.findall(r"^\s*input\s+(\\\S+|\w+)\s*;", text, re.M)
    renames = {}
    for k, p in enumerate(ports):
        if p in ("clk_i", "\\clk_i"):
            continue
        renames[p] = f"pi_{k}"
        b = bit_of(p)
        match["inputs"] += 1
        r = rate(*lookup(signals, b), cycles)
        if r is None:
            match["missing"].append(p)
            continue
        match["inputs_found"] += 1
        lines.append(f"set_power_activity -input_ports [get_ports pi_{k}] -activity {r[0]:.6g} -duty {r[1]:.6g}")
    escaped = {p: n for p, n in renames.items() if p.startswith("\\")}
    plain = {p: n for p, n in renames.items() if not p.startswith("\\")}
    if escaped:
        text = re.sub(r"\\\S+(?=\s)", lambda m: escaped.get(m.group(0), m.group(0)), text)
    if plain:
        text = re.sub(r"\b(" + "|".join(re.escape(p) for p in plain) + r")\b", lambda m: plain[m.group(1)], text)
    # The new ports in the module's port list and declarations, the cut outputs' wires, and the buffers.
    head_end = text.index(");")
    text = text[:head_end] + "".join(f", {p}" for p in extra_ports) + text[head_end:]
    decl_at = text.index(";", head_end) + 1
    decls = "".join(f"\n  input {p};" for p in extra_ports) + "".join(f"\n  wire {w};" for w in extra_wires)
    text = text[:decl_at] + decls + text[decl_at:]
    end = text.rindex("endmodule")
    text = text[:end] + "\n".join(buffers) + "\n" + text[end:]
    with open(power_v, "w") as f:
        f.write(text)
    with open(tcl, "w") as f:
        f.write("\n".join(lines) + "\n")
    with open(match_path, "w") as f:
        json.dump(match, f, indent=1)


if __name__ == "__main__":
    if len(sys.argv) != 7:
        sys.exit(__doc__)
    main(*sys.argv[1:])
