"""The report of bench/timing.sh: docs/hardware.md's bench:timing block and the table `voxcd size --target` reads.

Run by bench/timing.sh in its work directory, after the tools: reads asic-dD/ (sta.txt, area.txt, buffers.txt,
srams.json), xilinx-dD.* (stat, ltp), hx8k-dD-S.report.json and up5k-dD-S.report.json (nextpnr; absent when the
design does not fit), up5k-dD.dsp.txt, and writes --markdown and --table.
"""
import argparse
import datetime
import json
import os
import re
import statistics

LUT_NS, CARRY_NS = 0.5, 0.1  # round per-cell figures of ours for a 7-series -1 part (not a vendor timing model)
GOALS = {"hx8k": 100, "up5k": 45, "levels": 5, "asic": 200}
TARGETS = ("asic-osu018", "ice40-hx8k", "ice40-up5k", "xilinx-7")


def params_text(params):
    return " ".join(f"{k} {v}" for k, v in re.findall(r"-set (\w+) (\S+)", params))


def config_text(params):
    """The DeviceConfig text of a chparam list (the depth apart): every width, the given ones replaced."""
    cfg = {"PW": 24, "PF": 8, "MW": 18, "MF": 16, "TW": 48, "DW": 10, "MEMW": 64, "LANES": 4, "SAW": 16, "MAW": 18,
           "TAGW": 16}
    for k, v in re.findall(r"-set (\w+) (\S+)", params):
        cfg[k] = int(v)
    return " ".join(f"{k} {v}" for k, v in cfg.items())


def cells_of(stat):
    if "design" in stat:
        return stat["design"]["num_cells_by_type"]
    (module,) = stat["modules"].values()
    return module["num_cells_by_type"]


def register_names(netlist):
    """{flip-flop instance: the register it holds}: the net on its Q pin, which keeps the RTL's register name."""
    names = {}
    text = open(netlist).read()
    for inst, body in re.findall(r"\n\s*DFF\w*\s+(\S+)\s*\((.*?)\);", text, re.S):
        q = re.search(r"\.Q\(\s*(\\?\S+?)\s*\)", body)
        if q:
            names[inst.lstrip("\\")] = q.group(1).lstrip("\\")
    return names


def slowest_groups(text, names, count=8):
    """The register groups whose inputs arrive latest: from the endpoint list (`report_checks -format end`), every
    setup endpoint named by its register with lane, bank and bit indices folded ("g_lane[*].u_lane.px_q[]"), the
    latest arrival of each group, latest first."""
    groups = {}
    for inst, pin, arrival in re.findall(r"^(\S+)/(\w+) \(\w+\)\s+[-\d.]+\s+([-\d.]+)\s+[-\d.]+ \((?:MET|VIOLATED)\)",
                                         text, re.M):
        if pin in ("S", "R"):  # asynchronous set and reset: recovery checks, not data
            continue
        name = names.get(inst, f"{inst}/{pin}")
        name = re.sub(r"\[\d+\]", "[]", re.sub(r"(g_lane|g_bank)\[\d+\]", r"\1[*]", name))
        groups[name] = max(groups.get(name, 0.0), float(arrival))
    return sorted(groups.items(), key=lambda kv: -kv[1])[:count]


def asic(d, goal_mhz):
    text = open(f"asic-d{d}/sta.txt").read()
    slacks = [float(x) for x in re.findall(r"(-?[\d.]+)\s+slack \((?:MET|VIOLATED)\)", text)]
    if not slacks:
        raise SystemExit(f"report.py: asic-d{d}/sta.txt has no slack: {text[-400:]}")
    period = 1e3 / goal_mhz
    worst = min(slacks)
    # The path whose slack is the worst: its start and end points, named by the register (or port, or macro) there.
    paths = re.split(r"\n(?=Startpoint:)", text)
    start = end = "?"
    names = register_names(f"asic-d{d}/netlist.v")
    for p in paths:
        m = re.search(r"(-?[\d.]+)\s+slack \(", p)
        if m and float(m.group(1)) == worst:
            start = re.search(r"Startpoint: (\S+)", p).group(1)
            end = re.search(r"Endpoint: (\S+)", p).group(1)
            start, end = names.get(start, start), names.get(end, end)
    area_text = open(f"asic-d{d}/area.txt").read()
    area = float(re.search(r"Chip area for module '\\voxcd_device': ([\d.]+)", area_text).group(1))
    counts = dict((k, int(v)) for k, v in re.findall(r"^\s+(\w+)\s+(\d+)$", area_text, re.M))
    added, before = (int(x) for x in open(f"asic-d{d}/buffers.txt").read().split())
    srams = json.load(open(f"asic-d{d}/srams.json"))
    return {"wns": worst, "mhz": 1e3 / (period - worst), "start": start, "end": end, "area_mm2": area / 1e6,
            "groups": slowest_groups(text, names),
            "cells": sum(v for k, v in counts.items() if not k.startswith("voxcd_sram")),
            "ffs": sum(v for k, v in counts.items() if k.startswith("DFF")), "buffers": added, "fanout_before": before,
            "srams": srams}


def xilinx(d):
    c = cells_of(json.load(open(f"xilinx-d{d}.stat.json")))
    names = {}
    mod = next(v for k, v in json.load(open(f"xilinx-d{d}.json"))["modules"].items()
               if k.split("\\")[-1] == "voxcd_device")
    for n, cell in mod["cells"].items():
        names[n] = cell["type"]
    ltp = open(f"xilinx-d{d}.ltp.txt").read()
    kinds = {}
    for v in re.findall(r"\(via (\S+)\)", ltp):
        t = names.get(v, names.get(v.lstrip("\\"), "?"))
        t = "LUT" if t.startswith("LUT") else t
        kinds[t] = kinds.get(t, 0) + 1
    levels, carry = kinds.get("LUT", 0), kinds.get("CARRY4", 0)
    ns = levels * LUT_NS + carry * CARRY_NS
    return {"luts": sum(c.get(f"LUT{i}", 0) for i in range(1, 7)), "ffs": sum(v for k, v in c.items() if k.startswith("FD")),
            "dsps": c.get("DSP48E1", 0), "brams": c.get("RAMB36E1", 0) + 0.5 * c.get("RAMB18E1", 0),
            "levels": levels, "carry": carry, "other": {k: v for k, v in kinds.items() if k not in ("LUT", "CARRY4")},
            "ns": ns, "mhz": 1e3 / ns if ns else 0}


def ice40(dev, d):
    fmax, util = [], None
    for seed in (1, 2, 3):
        path = f"{dev}-d{d}-{seed}.report.json"
        if not os.path.exists(path):
            continue
        r = json.load(open(path))
        fmax.append(min(v["achieved"] for v in r["fmax"].values()))
        util = r["utilization"]
    if len(fmax) < 3:
        log = open(f"pnr-{dev}-d{d}-1.log").read()
        m = re.search(r"ICESTORM_LC:\s+(\d+)/\s*(\d+)", log)
        return {"fits": False, "lcs": f"{m.group(1)} / {m.group(2)}" if m else "-"}
    u = lambda k: util.get(k, {"used": 0, "available": 0})
    return {"fits": True, "mhz": statistics.median(fmax), "seeds": fmax,
            "lcs": f"{u('ICESTORM_LC')['used']} / {u('ICESTORM_LC')['available']}", "lc_used": u("ICESTORM_LC")["used"],
            "rams": u("ICESTORM_RAM")["used"], "dsps": u("ICESTORM_DSP")["used"]}


def fmt_mhz(v):
    return f"{v:.1f}"


def met(ok):
    return "met" if ok else "not met"


def markdown(a, res):
    depths = res["depths"]
    out = []
    p = out.append
    p(f"_Generated by `{a.command}` on {datetime.date.today().isoformat()}; depths {', '.join(map(str, depths))} "
      f"(every depth the RTL offers unless `--depths` says otherwise)._")
    p("")
    p("| depth | latency (cycles) | ASIC Fmax (MHz) | ASIC area (mm^2) | lookups/s per mm^2 | iCE40 HX8K Fmax (MHz) "
      "| iCE40 UP5K Fmax (MHz) | 7-series LUT levels (+ CARRY4) | LUTs | FFs | DSP48E1 | RAMB36 |")
    p("|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|")
    for d in depths:
        s, x, h, u = res["asic"][d], res["xilinx"][d], res["hx8k"][d], res["up5k"][d]
        lookups = s["mhz"] * 1e6 * 4 / s["area_mm2"]
        ice = lambda r: f"{fmt_mhz(r['mhz'])} [{', '.join(fmt_mhz(v) for v in r['seeds'])}]" if r["fits"] else \
            f"does not fit ({r['lcs']} cells)"
        p(f"| {d} | {8 + d} | {fmt_mhz(s['mhz'])} | {s['area_mm2']:.3f} | {lookups / 1e6:.1f} M | {ice(h)} | {ice(u)} | "
          f"{x['levels']} (+ {x['carry']}) | {x['luts']} | {x['ffs']} | {x['dsps']} | {x['brams']:g} |")
    p("")
    p("Goals: iCE40 HX8K at LANES 1 >= "
      f"{GOALS['hx8k']} MHz, UP5K >= {GOALS['up5k']} MHz, 7-series at most {GOALS['levels']} LUT levels between "
      f"registers, the ASIC default configuration >= {GOALS['asic']} MHz at 0.18 um:")
    p("")
    p("| depth | HX8K >= 100 MHz | UP5K >= 45 MHz | 7-series <= 5 LUT levels | ASIC >= 200 MHz |")
    p("|--:|---|---|---|---|")
    for d in depths:
        s, x, h, u = res["asic"][d], res["xilinx"][d], res["hx8k"][d], res["up5k"][d]
        ice = lambda r, g: (f"{met(r['mhz'] >= g)} ({fmt_mhz(r['mhz'])})" if r["fits"] else "not met (does not fit)")
        p(f"| {d} | {ice(h, GOALS['hx8k'])} | {ice(u, GOALS['up5k'])} | {met(x['levels'] <= GOALS['levels'])} "
          f"({x['levels']}) | {met(s['mhz'] >= GOALS['asic'])} ({fmt_mhz(s['mhz'])}) |")
    p("")
    p("Latency: the cycles from a one-point job's acceptance to its hit record on the output pins with an always-ready "
      "consumer, 1 + 6 + depth slot registers + the output register (ref/timing.h, kFirstSlotLatency + depth, plus one).")
    p("")
    # ASIC method.
    d0 = depths[0]
    s0 = res["asic"][d0]
    macros = ", ".join(f"{m['count']} x {name} ({m['words']} words of {m['width']} bits)"
                       for name, m in sorted(s0["srams"].items()))
    p(f"**ASIC** (OSU 0.18 um, `osu018_stdcells.lib` of Debian's qflow-tech-osu018; OpenSTA {a.sta_version}): voxcd_device at "
      f"{params_text(a.default)} and the default widths ({config_text(a.default)}). Its RAMs are SRAM macros, "
      f"black boxes whose Liberty model (bench/timing/sram_models.py) has the read data valid {a.sram[0]} ns after "
      f"the clock edge (plus 2 ns/pF of load) and samples address, data and enables with {a.sram[1]} ns of setup and "
      f"{a.sram[2]} ns of hold: {macros} at depth {d0}; their area is not in the cell area (a macro's area is its "
      f"compiler's). The rest: yosys `synth -flatten` with adders and comparators as Kogge-Stone prefixes "
      f"(host/sizing/kogge_stone.v, as datapath synthesis builds them, not ripples), `dfflibmap`, then ABC mapping for a "
      f"{a.goal_mhz:g} MHz "
      f"period with `buffer -N 12; upsize; dnsize` (ABC_SCRIPT in bench/timing.sh). ABC sees flip-flop outputs and "
      f"input ports as the inputs of its network and does not buffer them (at depth {d0} one net had "
      f"{s0['fanout_before']} loads); bench/timing/fanout_buffers.py then builds a balanced BUFX4 tree on every net "
      f"with more than {a.fanout} loads, the clock excepted ({s0['buffers']} buffers at depth {d0}), as a physical "
      f"flow would before timing. OpenSTA checks the netlist at {a.goal_mhz:g} MHz with an ideal clock, inputs and "
      f"outputs at the clock edge, and a wire load model of {a.wire[0]} um of wire per net and per load at "
      f"{a.wire[1]} fF/um (no placement: the model stands in for the wires); Fmax = 1 / (period - worst slack), over "
      f"setup and recovery checks. Cell area: yosys `stat -liberty` of the buffered netlist (standard cells only). "
      f"Lookups per second per mm^2: Fmax x LANES (4) over that area.")
    p("")
    p(f"| depth | worst slack at {a.goal_mhz:g} MHz (ns) | Fmax (MHz) | worst path (from register to register) | cells | "
      f"flip-flops | buffers added |")
    p("|--:|--:|--:|---|--:|--:|--:|")
    for d in depths:
        s = res["asic"][d]
        p(f"| {d} | {s['wns']:.3f} | {fmt_mhz(s['mhz'])} | `{s['start']}` -> `{s['end']}` | {s['cells']} | "
          f"{s['ffs']} | {s['buffers']} |")
    p("")
    p(f"What else is slow: the {len(res['asic'][d0]['groups'])} register groups whose data arrive latest at each depth "
      f"(OpenSTA's every endpoint, `report_checks -group_count 100000 -format end`; lanes, banks and bits folded, the "
      f"latest arrival of each group, in ns after the clock edge; a group meets {a.goal_mhz:g} MHz when its arrival "
      f"plus the register's setup is within {1e3 / a.goal_mhz:g} ns):")
    p("")
    p("| depth | register group | latest arrival (ns) |")
    p("|--:|---|--:|")
    for d in depths:
        for name, arrival in res["asic"][d]["groups"]:
            p(f"| {d} | `{name}` | {arrival:.2f} |")
    p("")
    up = res["up5k"][d0]
    p(f"**iCE40**: voxcd_device at {params_text(a.small)} inside bench/voxcd_fmax_top.sv (a shift register drives "
      f"every device input, the registered outputs are XOR-reduced to one pin); nextpnr-ice40 seeds 1, 2, 3, the "
      f"median Max frequency [all three]. HX8K (ct256): `synth_ice40`, multipliers in logic cells (the part has no "
      f"DSP blocks). UP5K (sg48): `synth_ice40 -dsp`; a lane has more products than the part's 8 SB_MAC16, so the "
      f"widest go into the DSP blocks until all 8 are used and the rest stay in logic cells "
      f"(bench/timing/dsp_budget.py; at depth {d0}: {res['up5k_dsp'][d0][0]} products in "
      f"{res['up5k_dsp'][d0][1]} SB_MAC16, {res['up5k_dsp'][d0][2]} in logic cells); the same reduced configuration "
      f"as the HX8K, not a smaller one and not a lane that shares its multipliers over cycles.")
    p("")
    p("| depth | device | logic cells | RAMs (4 kbit) | SB_MAC16 | Fmax (MHz), median [seeds] |")
    p("|--:|---|--:|--:|--:|--:|")
    for d in depths:
        for dev, name in (("hx8k", "iCE40 HX8K (ct256)"), ("up5k", "iCE40 UP5K (sg48)")):
            r = res[dev][d]
            if r["fits"]:
                p(f"| {d} | {name} | {r['lcs']} | {r['rams']} | {r['dsps']} | {fmt_mhz(r['mhz'])} "
                  f"[{', '.join(f'{v:.2f}' for v in r['seeds'])}] |")
            else:
                p(f"| {d} | {name} | {r['lcs']} | - | - | does not fit |")
    p("")
    p(f"**7-series**: the default configuration ({params_text(a.default)}) after `synth_xilinx -flatten -noiopad`; the "
      f"counts are of that run (bench/rtl_cost.sh's table synthesises without -flatten, so its LUT counts differ a "
      f"little). Logic depth: the longest path between state-holding cells (flip-flops, block RAMs, SRLs, LUT RAMs and "
      f"DSP48E1s, which hold the multipliers' pipeline registers), yosys `ltp`. yosys has no 7-series delays; the "
      f"`xilinx-7` clocks of host/sizing/timing.tsv are an estimate from it, {LUT_NS} ns per LUT level (the LUT and its "
      f"routing) and {CARRY_NS} ns per CARRY4, not a vendor timing analysis.")
    p("")
    p("| depth | longest path | estimate (ns) | estimate (MHz) |")
    p("|--:|---|--:|--:|")
    for d in depths:
        x = res["xilinx"][d]
        other = "".join(f", {v} {k}" for k, v in sorted(x["other"].items()))
        p(f"| {d} | {x['levels']} LUT levels, {x['carry']} CARRY4{other} | {x['ns']:.1f} | {fmt_mhz(x['mhz'])} |")
    p("")
    cpu = sum(int(m) * 60 + float(s) for m, s in re.findall(r"(\d+)m([\d.]+)s", a.cpu))
    p(f"Made by `{a.command}` ({a.secs[1]} s wall, {a.secs[0]} s of it synthesis; {cpu:.0f} s CPU; {a.jobs} tool runs "
      f"at a time); {a.yosys}; {a.nextpnr}; OpenSTA {a.sta_version}. The same run wrote host/sizing/timing.tsv, the "
      f"table `voxcd size --target` chooses a depth from.")
    return "\n".join(out) + "\n"


def table(a, res):
    rows = [f"# The measured clock and area of each depth, per target (docs/hardware.md, \"Timing and area per depth\").",
            f"# Made by `{a.command}` on {datetime.date.today().isoformat()}; read by voxcd size --target "
            f"(host/sizing/timing_table.h).",
            "target\tdepth\tmhz\tsource\tlanes\tarea_mm2\tluts\tffs\tdsps\tbrams\tlut_levels\tconfig"]
    for d in res["depths"]:
        s, x = res["asic"][d], res["xilinx"][d]
        macros = sum(m["count"] for m in s["srams"].values())
        rows.append(f"asic-osu018\t{d}\t{fmt_mhz(s['mhz'])}\tOpenSTA, OSU 0.18 um\t4\t{s['area_mm2']:.3f}\t-\t{s['ffs']}\t-\t"
                    f"{macros}\t-\t{config_text(a.default)}")
        for dev in ("hx8k", "up5k"):
            r = res[dev][d]
            if r["fits"]:
                rows.append(f"ice40-{dev}\t{d}\t{fmt_mhz(r['mhz'])}\tnextpnr-ice40, median of 3 seeds\t1\t-\t"
                            f"{r['lc_used']}\t-\t{r['dsps']}\t{r['rams']}\t-\t{config_text(a.small)}")
        rows.append(f"xilinx-7\t{d}\t{fmt_mhz(x['mhz'])}\testimate: synth_xilinx logic depth, {x['levels']} LUT levels x "
                    f"{LUT_NS} ns + {x['carry']} CARRY4 x {CARRY_NS} ns\t4\t-\t{x['luts']}\t{x['ffs']}\t{x['dsps']}\t"
                    f"{x['brams']:g}\t{x['levels']}\t{config_text(a.default)}")
    return "\n".join(rows) + "\n"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--depths", required=True)
    ap.add_argument("--goal-mhz", type=float, required=True)
    ap.add_argument("--sram", nargs=3, required=True)
    ap.add_argument("--wire", nargs=2, required=True)
    ap.add_argument("--fanout", required=True)
    ap.add_argument("--small", required=True)
    ap.add_argument("--default", required=True)
    ap.add_argument("--secs", nargs=2, required=True)
    ap.add_argument("--cpu", required=True)
    ap.add_argument("--jobs", required=True)
    ap.add_argument("--yosys", required=True)
    ap.add_argument("--nextpnr", required=True)
    ap.add_argument("--sta", dest="sta_version", required=True)
    ap.add_argument("--command", required=True)
    ap.add_argument("--markdown", required=True)
    ap.add_argument("--table", required=True)
    a = ap.parse_args()
    depths = [int(x) for x in a.depths.split(",")]
    res = {"depths": depths, "asic": {}, "xilinx": {}, "hx8k": {}, "up5k": {}, "up5k_dsp": {}}
    for d in depths:
        res["asic"][d] = asic(d, a.goal_mhz)
        res["xilinx"][d] = xilinx(d)
        res["hx8k"][d] = ice40("hx8k", d)
        res["up5k"][d] = ice40("up5k", d)
        res["up5k_dsp"][d] = [int(x) for x in open(f"up5k-d{d}.dsp.txt").read().split()]
    with open(a.markdown, "w") as f:
        f.write(markdown(a, res))
    with open(a.table, "w") as f:
        f.write(table(a, res))


if __name__ == "__main__":
    main()
