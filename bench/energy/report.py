"""Energy per lookup from OpenSTA's power report and the simulation's counts (bench/energy.sh): the Markdown block of
docs/hardware.md ("Energy per lookup", bench:energy) and host/sizing/energy.tsv.

Per scene: logic power (OpenSTA report_power: internal, switching, leakage, total) x the run's time (cycles / clock)
plus the SRAM macros' energy (reads and writes counted in the trace, each x the energy of an access of its shape,
plus their leakage x the run's time), over the run's lookups (shell points looked up) and over its pair queries.

SRAM energy: an ESTIMATE from an analytical model of a 6T SRAM macro at 0.18 um, 1.8 V (no published figure for a
macro of these shapes was found): the words in subarrays of 256 rows with a column mux of up to 8; a read swings
every active bitline pair by DV_READ, a write the written columns fully and the others of the row by DV_READ; the
word line, the sense amplifiers and output latches, and the address decoders add their capacitances at full swing;
leakage per cell LEAK_CELL_A. The constants are below; they are assumptions in the range of 0.18 um processes, and
the block states them.

Projection: Stillmaker and Baas, "Scaling equations for the accurate prediction of CMOS device performance from
180 nm to 7 nm", Integration, the VLSI Journal 58 (2017) 74-81: energy scales by the ratio of the nodes' energy
factors E(V) = a V^2 + b V + c (their fitted coefficients, 180 nm bulk and the PTM high-performance models below 65
nm, as transcribed in github.com/wromaszkan/nodeScale; the 32 nm HP and 65 nm rows agree with the paper's published
erratum example), each node at its nominal supply. A projection, not a measurement: it scales the whole energy per
lookup (logic and SRAM) as dynamic energy.
"""
import argparse
import json
import math
import re

VDD = 1.8
ROWS = 256               # rows per subarray
MAX_MUX = 8              # column mux
C_BL_CELL = 1.5e-15      # F of bitline per cell (drain junction and wire, 0.18 um)
C_BL_FIXED = 20e-15      # F per bitline: precharge, column mux, sense amplifier
DV_READ = 0.2            # V: read swing of a bitline
C_WL_CELL = 2.8e-15      # F of word line per column (two access gates and wire)
C_SENSE_BIT = 50e-15     # F per output bit: sense amplifier, latch, output driver
C_DEC_BIT = 200e-15      # F per address bit: predecoders and decoder lines
LEAK_CELL_A = 20e-12     # A of leakage per 6T cell at 25 C

# Stillmaker and Baas 2017, energy factor coefficients (a, b, c) and the nominal supply used for each node.
SCALING = {
    "180 nm": ((0.0, 24.64, -17.98), 1.8),
    "45 nm (HP)": ((1.018, -0.3107, 0.1539), 1.0),
    "16 nm (HP)": ((0.2958, -0.1241, 0.03024), 0.7),
    "7 nm (HP)": ((0.1776, -0.09097, 0.02447), 0.7),
}


def energy_factor(node):
    (a, b, c), v = SCALING[node]
    return a * v * v + b * v + c


def sram(width, words):
    """(read J, write J, leakage W) of one access of a width x words macro: the model above."""
    rows = min(words, ROWS)
    mux = max(1, min(MAX_MUX, words // rows))
    cols = width * mux
    addr = max(1, math.ceil(math.log2(words)))
    c_bl = rows * C_BL_CELL + C_BL_FIXED
    wordline = cols * C_WL_CELL * VDD * VDD
    decode = addr * C_DEC_BIT * VDD * VDD
    sense = width * C_SENSE_BIT * VDD * VDD
    read = cols * c_bl * VDD * DV_READ + wordline + decode + sense
    write = width * c_bl * VDD * VDD + (cols - width) * c_bl * VDD * DV_READ + wordline + decode
    leak = width * words * LEAK_CELL_A * VDD
    return read, write, leak


def power_totals(text):
    """(internal, switching, leakage, total) in W of the standard cells, and the instances left out, from
    bench/energy/power_sum.tcl's lines: the flip-flops and the other cells whole; of the buffers at the cut register
    and SRAM outputs only their switching power (the cut nets'), not their own internal power and leakage."""
    groups, nan = {}, None
    for line in text.splitlines():
        t = line.split()
        if len(t) == 5 and t[0] == "group":
            groups[t[1]] = tuple(float(x) for x in t[2:5])
        elif t[:1] == ["instances"]:
            nan = (int(t[3]), t[4:])
    if not {"seq", "comb", "cut"} <= set(groups) or nan is None:
        raise SystemExit("report.py: the power report lacks power_sum.tcl's lines")
    internal = groups["seq"][0] + groups["comb"][0]
    switching = groups["seq"][1] + groups["comb"][1] + groups["cut"][1]
    leakage = groups["seq"][2] + groups["comb"][2]
    return internal, switching, leakage, internal + switching + leakage, groups, nan


def scene_figures(name, info, tog, match, power_text, mhz, shapes):
    cycles = tog["cycles"]
    seconds = cycles / (mhz * 1e6)
    internal, switching, leakage, total, groups, nan = power_totals(power_text)
    reads = writes = 0
    e_sram = leak_sram = 0.0
    for m in match["macros"].values():
        shape = shapes[m["cell"]]
        er, ew, pl = sram(shape["width"], shape["words"])
        sig = tog["signals"]
        r = sig.get(m["rtl"] + ".re_i", {"high": [0]})["high"][0]
        w = sig.get(m["rtl"] + ".we_i", {"high": [0]})["high"][0]
        reads += r
        writes += w
        e_sram += r * er + w * ew
        leak_sram += pl
    e_logic = total * seconds
    e_leak = (leakage + leak_sram) * seconds
    e_all = e_logic + e_sram + leak_sram * seconds
    lookups, jobs, pairs = info["lookups"], info["jobs"], info["pairs"]
    return {
        "scene": name, "frames": info.get("frames", 0), "shell_words": info.get("shell_words"),
        "map_words": info.get("map_words"), "cycles": cycles, "lookups": lookups, "jobs": jobs, "pairs": pairs, "voxel": info["voxel"],
        "internal_mw": internal * 1e3, "switching_mw": switching * 1e3, "leakage_mw": leakage * 1e3,
        "logic_mw": total * 1e3, "sram_reads": reads, "sram_writes": writes, "sram_nj": e_sram * 1e9,
        "sram_leak_uw": leak_sram * 1e6, "total_nj": e_all * 1e9,
        "pj_per_lookup": e_all / lookups * 1e12, "logic_pj_per_lookup": e_logic / lookups * 1e12,
        "sram_pj_per_lookup": (e_sram + leak_sram * seconds) / lookups * 1e12,
        "nj_per_pair": e_all / pairs * 1e9, "leakage_share": e_leak / e_all,
        "lookups_per_cycle": lookups / cycles, "match": match, "nan": nan,
        "seq_internal_mw": groups["seq"][0] * 1e3, "cut_internal_mw": groups["cut"][0] * 1e3,
    }


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--scenes", nargs="+", required=True, help="NAME:DIR, each with info.json, toggles.json, "
                    "match.json and power.txt")
    ap.add_argument("--srams", required=True)
    ap.add_argument("--mhz", type=float, required=True)
    ap.add_argument("--clock-source", required=True)
    ap.add_argument("--config", required=True)
    ap.add_argument("--depth", type=int, required=True)
    ap.add_argument("--command", required=True)
    ap.add_argument("--date", required=True)
    ap.add_argument("--versions", required=True)
    ap.add_argument("--model", required=True)
    ap.add_argument("--sta", required=True, help="the netlist's static timing report (its wns line)")
    ap.add_argument("--goal-mhz", type=float, required=True)
    ap.add_argument("--markdown", required=True)
    ap.add_argument("--table", required=True)
    a = ap.parse_args()
    with open(a.srams) as f:
        shapes = json.load(f)
    rows = []
    for spec in a.scenes:
        name, d = spec.split(":", 1)
        with open(f"{d}/info.json") as f:
            info = json.load(f)
        with open(f"{d}/toggles.json") as f:
            tog = json.load(f)
        with open(f"{d}/match.json") as f:
            match = json.load(f)
        with open(f"{d}/power.txt") as f:
            power_text = f.read()
        rows.append(scene_figures(name, info, tog, match, power_text, a.mhz, shapes))
    md = []
    md.append(f"Made by `{a.command}` on {a.date}. {a.versions}.\n")
    md.append(f"Configuration (synthesised): `{a.config}`, depth {a.depth}; clock {a.mhz:g} MHz ({a.clock_source}). "
              f"The netlist is bench/timing.sh's ASIC flow (bench/timing/asic.sh) for this configuration; the "
              f"activity comes from the rtl backend's Verilated model `{a.model}` (the same logic with the rtl "
              f"backend's memory depths; every scene's memories fit the synthesised SAW and MAW, so the upper address "
              f"bits stay 0).\n")
    wns = next(float(line.split()[1]) for line in open(a.sta) if line.startswith("wns"))
    fmax = 1e3 / (1e3 / a.goal_mhz - wns)
    md.append(f"This netlist's own static timing (the flow's OpenSTA run at the {a.goal_mhz:g} MHz goal): worst slack "
              f"{wns:g} ns, so {fmax:.1f} MHz; the figures below are at {a.mhz:g} MHz as the clock's source says.\n")
    m0 = rows[0]["match"]
    md.append(f"Activity: register bits of the netlist found in the trace {m0['registers_found']} of "
              f"{m0['registers']}, input port bits {m0['inputs_found']} of {m0['inputs']}, SRAM read data bits "
              f"{m0['macro_bits_found']} of {m0['macro_bits']} (the rest, and all combinational nets, take "
              f"OpenSTA's propagated activity). OpenSTA keeps user activities only on input ports, so the "
              f"registers' and the SRAMs' outputs are cut and driven from input ports through buffers whose internal "
              f"power is left out (bench/energy/activity.py); the power is the sum of sta::instance_power over the "
              f"instances (what report_power adds up), since report_power stops at an instance whose power OpenSTA "
              f"2.0.17 computes as NaN; left out as NaN: "
              + ", ".join(f"{r['scene']} {r['nan'][0]}" for r in rows) + " instance(s). The clock is ideal (no "
              f"clock tree); the flip-flops' internal power, their clock pins' included, is "
              f"{rows[0]['seq_internal_mw']:.1f} mW of the first scene's internal power.\n")
    md.append("Scenes: " + "; ".join(
        f"{r['scene']}: voxel {r['voxel']:.4g}, {r['shell_words']} shell words and {r['map_words']} voxmap words"
        + (f", {r['frames']} frames" if r["frames"] else "") for r in rows) + ".\n")
    md.append("| scene | voxel | cycles | lookups | jobs | pair queries | lookups per cycle | logic internal mW | "
              "logic switching mW | logic leakage mW | logic total mW | SRAM reads | SRAM energy nJ (estimate) | "
              "pJ per lookup | of which logic | of which SRAM (estimate) | nJ per pair query | leakage share |")
    md.append("|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|")
    for r in rows:
        md.append(f"| {r['scene']} | {r['voxel']:.4g} | {r['cycles']} | {r['lookups']} | {r['jobs']} | {r['pairs']} | "
                  f"{r['lookups_per_cycle']:.2f} | {r['internal_mw']:.2f} | {r['switching_mw']:.2f} | "
                  f"{r['leakage_mw']:.4f} | {r['logic_mw']:.2f} | {r['sram_reads']} | {r['sram_nj']:.1f} | "
                  f"{r['pj_per_lookup']:.1f} | {r['logic_pj_per_lookup']:.1f} | {r['sram_pj_per_lookup']:.1f} | "
                  f"{r['nj_per_pair']:.2f} | {100 * r['leakage_share']:.3f}% |")
    md.append("")
    shape_text = ", ".join(f"{s['count']} x {s['width']} x {s['words']}" for s in shapes.values())
    access = "; ".join(f"{s['width']} x {s['words']}: read {sram(s['width'], s['words'])[0] * 1e12:.1f} pJ, write "
                       f"{sram(s['width'], s['words'])[1] * 1e12:.1f} pJ, leakage "
                       f"{sram(s['width'], s['words'])[2] * 1e6:.1f} uW" for s in shapes.values())
    md.append(f"SRAM macros ({shape_text}, width x words): an **estimate**, not a measurement: an analytical model of "
              f"a 6T macro at 0.18 um, 1.8 V (bench/energy/report.py: subarrays of {ROWS} rows, column mux up to "
              f"{MAX_MUX}, {C_BL_CELL * 1e15:g} fF of bitline per cell, {DV_READ:g} V read swing, "
              f"{LEAK_CELL_A * 1e12:g} pA leakage per cell), since no published energy figure for 0.18 um macros "
              f"of these shapes was found: {access}. Reads and writes are the cycles each macro's read and write "
              f"enables are high in the trace ("
              + ", ".join(f"{r['scene']} {r['sram_reads'] / r['cycles']:.2f}" for r in rows)
              + " reads per cycle: the RTL's read enables are high on almost every cycle of a run, whether or not a "
              f"lane has a point).\n")
    md.append("Projection (**projection**, not measured): the 0.18 um energy per lookup scaled by the energy "
              "factors of Stillmaker and Baas 2017 (Integration 58, 74-81; coefficients as transcribed in "
              "github.com/wromaszkan/nodeScale, rows checked against the paper's erratum; each node at its nominal "
              "supply, logic and SRAM alike as dynamic energy):\n")
    nodes = list(SCALING)
    md.append("| scene | " + " | ".join(f"{n} at {SCALING[n][1]:g} V, pJ per lookup" for n in nodes) + " |")
    md.append("|---|" + "--:|" * len(nodes))
    e0 = energy_factor("180 nm")
    for r in rows:
        vals = [r["pj_per_lookup"] * energy_factor(n) / e0 for n in nodes]
        md.append(f"| {r['scene']} | " + " | ".join(
            (f"{v:.1f} (measured)" if n == "180 nm" else f"{v:.2f} (projection)") for n, v in zip(nodes, vals)) + " |")
    with open(a.markdown, "w") as f:
        f.write("\n".join(md) + "\n")
    tsv = ["# Energy per lookup of the device, per scene (docs/hardware.md, \"Energy per lookup\"): made by "
           f"`{a.command}` on {a.date}.",
           "# target, depth, config: the synthesised device; mhz: its clock; scene: the stimulus (bench/bench_energy);",
           "# cycles, lookups, jobs, pairs: the run; logic_mw: OpenSTA's power of the standard cells (the sum of",
           "# sta::instance_power, internal_mw + switching_mw + leakage_mw); sram_nj: the SRAM macros' access energy over",
           "# the run (estimate:",
           "# bench/energy/report.py); pj_per_lookup = (logic power x run time + SRAM energy and leakage) / lookups;",
           "# logic_pj and sram_pj its parts; nj_per_pair: the same over the pair queries; leakage_share: of the energy;",
           "# pj_45nm, pj_16nm, pj_7nm: projections (Stillmaker and Baas 2017), not measurements.",
           "target\tdepth\tmhz\tscene\tcycles\tlookups\tjobs\tpairs\tinternal_mw\tswitching_mw\tleakage_mw\tlogic_mw\t"
           "sram_nj\tpj_per_lookup\tlogic_pj\tsram_pj\tnj_per_pair\tleakage_share\tpj_45nm\tpj_16nm\tpj_7nm\tconfig"]
    for r in rows:
        proj = [r["pj_per_lookup"] * energy_factor(n) / e0 for n in nodes[1:]]
        tsv.append("\t".join(str(x) for x in [
            "asic-osu018", a.depth, f"{a.mhz:g}", r["scene"], r["cycles"], r["lookups"], r["jobs"], r["pairs"],
            f"{r['internal_mw']:.3f}", f"{r['switching_mw']:.3f}", f"{r['leakage_mw']:.5f}", f"{r['logic_mw']:.3f}",
            f"{r['sram_nj']:.2f}", f"{r['pj_per_lookup']:.2f}", f"{r['logic_pj_per_lookup']:.2f}",
            f"{r['sram_pj_per_lookup']:.2f}", f"{r['nj_per_pair']:.3f}", f"{r['leakage_share']:.5f}",
            *(f"{v:.3f}" for v in proj), a.config]))
    with open(a.table, "w") as f:
        f.write("\n".join(tsv) + "\n")
    for r in rows:
        print(f"{r['scene']}: {r['pj_per_lookup']:.1f} pJ per lookup (logic {r['logic_pj_per_lookup']:.1f}, SRAM "
              f"{r['sram_pj_per_lookup']:.1f} estimate), {r['nj_per_pair']:.2f} nJ per pair query; logic "
              f"{r['logic_mw']:.2f} mW (internal {r['internal_mw']:.2f}, switching {r['switching_mw']:.2f}, leakage "
              f"{r['leakage_mw']:.4f}); leakage share {100 * r['leakage_share']:.3f}%")


if __name__ == "__main__":
    main()
