"""The report of bench/timing.sh: its configuration's section of docs/hardware.md's bench:timing block and its rows
of host/device/timing.tsv (the table every modelled rate's clock and `voxcd size --target` read), and their merge.

    report.py --depths ... --markdown RUN.md --table RUN.tsv
        Run by bench/timing.sh in its work directory, after the tools: reads asic-dD/ (sta.txt, area.txt,
        buffers.txt, srams.json), xilinx-dD.* (stat, ltp) and, with --ice40 1, hx8k-dD-S.report.json and
        up5k-dD-S.report.json (nextpnr; absent when the design does not fit) and up5k-dD.dsp.txt; writes the run's
        section (RUN.md) and its rows as a table of their own (RUN.tsv).
    report.py merge --run-markdown RUN.md --run-table RUN.tsv --doc DOC --table TABLE --out-markdown M --out-table T
        The bench:timing block of DOC with the run's section in place of the section of its configuration (or added
        after the others), and TABLE with the run's rows in place of the rows of the same target, configuration and
        depth (the others kept, new rows added at the end); M and T are written, DOC and TABLE left as they are.
"""
import argparse
import datetime
import json
import os
import re
import statistics
import sys

LUT_NS, CARRY_NS = 0.5, 0.1  # round per-cell figures of ours for a 7-series -1 part (not a vendor timing model)
GOALS = {"hx8k": 100, "up5k": 45, "levels": 5, "asic": 200}
TARGETS = ("asic-osu018", "ice40-hx8k", "ice40-up5k", "xilinx-7")


# DeviceConfig's parameters and defaults (ref/config.h), in DeviceConfig::to_string's order: the widths always, then
# SB and WB on a distance device (SB > 2), BANKS when banked, BL on a sparse device (DEPTH is the table's depth column).
WIDTHS = {"PW": 24, "PF": 8, "MW": 18, "MF": 16, "TW": 48, "DW": 10, "MEMW": 64, "LANES": 4, "SAW": 16, "MAW": 18,
          "TAGW": 16}
EXTRAS = {"SB": 2, "WB": 8, "BANKS": 0, "BL": 0}
TABLE_COLUMNS = "target\tdepth\tmhz\tsource\tlanes\tarea_mm2\tluts\tffs\tdsps\tbrams\tlut_levels\tconfig"
SECTION = re.compile(r"^<!-- timing config: (.*) -->$")  # the first line of a configuration's section of the block
MEASURED = re.compile(r"^# measured: (.*) by `(.*)` on (\S+)$")  # a table's line naming a configuration's last run


def params_text(params):
    return " ".join(f"{k} {v}" for k, v in re.findall(r"-set (\w+) (\S+)", params))


def config_values(pairs):
    """{name: value} of every parameter, the defaults replaced by the NAME VALUE pairs given (DEPTH left out)."""
    cfg = {**WIDTHS, **EXTRAS}
    for k, v in pairs:
        if k != "DEPTH":
            cfg[k] = int(v)
    return cfg


def canonical(cfg):
    """The DeviceConfig::to_string text of {name: value} (the depth apart)."""
    text = " ".join(f"{k} {cfg[k]}" for k in WIDTHS)
    if cfg["SB"] > 2:
        text += f" SB {cfg['SB']} WB {cfg['WB']}"
    if cfg["BANKS"]:
        text += f" BANKS {cfg['BANKS']}"
    if cfg["BL"]:
        text += f" BL {cfg['BL']}"
    return text


def config_text(params):
    """The DeviceConfig text of a chparam list (the depth apart): every width, the given ones replaced."""
    return canonical(config_values(re.findall(r"-set (\w+) (\S+)", params)))


def same_config(text):
    """A table's or a section's configuration text as DeviceConfig::to_string writes it, for comparing."""
    words = text.split()
    return canonical(config_values(zip(words[::2], words[1::2])))


def lanes_of(params):
    return config_values(re.findall(r"-set (\w+) (\S+)", params))["LANES"]


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


def summary_tables(a, res, p):
    """The run's summary per depth and its goals: ASIC, the iCE40 parts when measured, the 7-series estimate."""
    depths, lanes = res["depths"], lanes_of(a.default)
    ice = lambda r: f"{fmt_mhz(r['mhz'])} [{', '.join(fmt_mhz(v) for v in r['seeds'])}]" if r["fits"] else \
        f"does not fit ({r['lcs']} cells)"
    ice_head, ice_rule = ("| iCE40 HX8K Fmax (MHz) | iCE40 UP5K Fmax (MHz) ", "--:|--:|") if a.ice40 else ("", "")
    p(f"| depth | latency (cycles) | ASIC Fmax (MHz) | ASIC area (mm^2) | lookups/s per mm^2 {ice_head}"
      "| 7-series LUT levels (+ CARRY4) | LUTs | FFs | DSP48E1 | RAMB36 |")
    p(f"|--:|--:|--:|--:|--:|{ice_rule}--:|--:|--:|--:|--:|")
    for d in depths:
        s, x = res["asic"][d], res["xilinx"][d]
        lookups = s["mhz"] * 1e6 * lanes / s["area_mm2"]
        ice_cells = f" {ice(res['hx8k'][d])} | {ice(res['up5k'][d])} |" if a.ice40 else ""
        p(f"| {d} | {8 + d} | {fmt_mhz(s['mhz'])} | {s['area_mm2']:.3f} | {lookups / 1e6:.1f} M |{ice_cells} "
          f"{x['levels']} (+ {x['carry']}) | {x['luts']} | {x['ffs']} | {x['dsps']} | {x['brams']:g} |")
    p("")
    ice_goals = f"iCE40 HX8K at LANES 1 >= {GOALS['hx8k']} MHz, UP5K >= {GOALS['up5k']} MHz, " if a.ice40 else ""
    p(f"Goals: {ice_goals}7-series at most {GOALS['levels']} LUT levels between registers, the ASIC configuration "
      f">= {GOALS['asic']} MHz at 0.18 um:")
    p("")
    ice_head, ice_rule = ("| HX8K >= 100 MHz | UP5K >= 45 MHz ", "---|---|") if a.ice40 else ("", "")
    p(f"| depth {ice_head}| 7-series <= 5 LUT levels | ASIC >= 200 MHz |")
    p(f"|--:|{ice_rule}---|---|")
    for d in depths:
        s, x = res["asic"][d], res["xilinx"][d]
        goal = lambda r, g: (f"{met(r['mhz'] >= g)} ({fmt_mhz(r['mhz'])})" if r["fits"] else "not met (does not fit)")
        ice_cells = f" {goal(res['hx8k'][d], GOALS['hx8k'])} | {goal(res['up5k'][d], GOALS['up5k'])} |" if a.ice40 \
            else ""
        p(f"| {d} |{ice_cells} {met(x['levels'] <= GOALS['levels'])} ({x['levels']}) | "
          f"{met(s['mhz'] >= GOALS['asic'])} ({fmt_mhz(s['mhz'])}) |")
    p("")


def asic_markdown(a, res, p):
    """The ASIC method, its worst paths and the register groups that arrive latest."""
    depths = res["depths"]
    d0 = depths[0]
    s0 = res["asic"][d0]
    macros = ", ".join(f"{m['count']} x {name} ({m['words']} words of {m['width']} bits)"
                       for name, m in sorted(s0["srams"].items()))
    p(f"**ASIC** (OSU 0.18 um, `osu018_stdcells.lib` of Debian's qflow-tech-osu018; OpenSTA {a.sta_version}): voxcd_device at "
      f"{params_text(a.default)} ({config_text(a.default)}). Its RAMs are SRAM macros, "
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
      f"Lookups per second per mm^2: Fmax x LANES ({lanes_of(a.default)}) over that area.")
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


def ice40_markdown(a, res, p):
    """The iCE40 method and its place and route per depth and part."""
    depths = res["depths"]
    d0 = depths[0]
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


def xilinx_markdown(a, res, p):
    """The 7-series synthesis and its logic-depth estimate per depth."""
    p(f"**7-series**: the configuration ({params_text(a.default)}) after `synth_xilinx -flatten -noiopad`; the "
      f"counts are of that run (bench/rtl_cost.sh's table synthesises without -flatten, so its LUT counts differ a "
      f"little). Logic depth: the longest path between state-holding cells (flip-flops, block RAMs, SRLs, LUT RAMs and "
      f"DSP48E1s, which hold the multipliers' pipeline registers), yosys `ltp`. yosys has no 7-series delays; the "
      f"`xilinx-7` clocks of host/device/timing.tsv are an estimate from it, {LUT_NS} ns per LUT level (the LUT and its "
      f"routing) and {CARRY_NS} ns per CARRY4, not a vendor timing analysis.")
    p("")
    p("| depth | longest path | estimate (ns) | estimate (MHz) |")
    p("|--:|---|--:|--:|")
    for d in res["depths"]:
        x = res["xilinx"][d]
        other = "".join(f", {v} {k}" for k, v in sorted(x["other"].items()))
        p(f"| {d} | {x['levels']} LUT levels, {x['carry']} CARRY4{other} | {x['ns']:.1f} | {fmt_mhz(x['mhz'])} |")
    p("")


def markdown(a, res):
    """The run's section of the bench:timing block: its configuration's marker and heading, then every table."""
    depths = res["depths"]
    out = []
    p = out.append
    p(f"<!-- timing config: {config_text(a.default)} -->")
    p(f"#### voxcd_device at {params_text(a.default)}")
    p("")
    p(f"_Generated by `{a.command}` on {datetime.date.today().isoformat()}; depths {', '.join(map(str, depths))} "
      f"(every depth the RTL offers unless `--depths` says otherwise)._")
    p("")
    summary_tables(a, res, p)
    p("Latency: the cycles from a one-point job's acceptance to its hit record on the output pins with an always-ready "
      "consumer, 1 + 6 + depth slot registers + the output register (ref/timing.h, kFirstSlotLatency + depth, plus one).")
    p("")
    asic_markdown(a, res, p)
    if a.ice40:
        ice40_markdown(a, res, p)
    xilinx_markdown(a, res, p)
    cpu = sum(int(m) * 60 + float(s) for m, s in re.findall(r"(\d+)m([\d.]+)s", a.cpu))
    pnr = f"; {a.nextpnr}" if a.ice40 else ""
    p(f"Made by `{a.command}` ({a.secs[1]} s wall, {a.secs[0]} s of it synthesis; {cpu:.0f} s CPU; {a.jobs} tool runs "
      f"at a time); {a.yosys}{pnr}; OpenSTA {a.sta_version}. The same run merged its rows into host/device/timing.tsv, "
      f"the table every modelled rate's clock and `voxcd size --target` read.")
    return "\n".join(out) + "\n"


def table(a, res):
    """The run's rows as a table of their own: a line naming each configuration measured, the header, the rows."""
    today = datetime.date.today().isoformat()
    configs = [config_text(a.default)] + ([config_text(a.small)] if a.ice40 else [])
    rows = [f"# measured: {c} by `{a.command}` on {today}" for c in configs] + [TABLE_COLUMNS]
    lanes = lanes_of(a.default)
    for d in res["depths"]:
        s, x = res["asic"][d], res["xilinx"][d]
        macros = sum(m["count"] for m in s["srams"].values())
        rows.append(f"asic-osu018\t{d}\t{fmt_mhz(s['mhz'])}\tOpenSTA, OSU 0.18 um\t{lanes}\t{s['area_mm2']:.3f}\t-\t"
                    f"{s['ffs']}\t-\t{macros}\t-\t{config_text(a.default)}")
        for dev in ("hx8k", "up5k") if a.ice40 else ():
            r = res[dev][d]
            if r["fits"]:
                rows.append(f"ice40-{dev}\t{d}\t{fmt_mhz(r['mhz'])}\tnextpnr-ice40, median of 3 seeds\t"
                            f"{lanes_of(a.small)}\t-\t{r['lc_used']}\t-\t{r['dsps']}\t{r['rams']}\t-\t{config_text(a.small)}")
        rows.append(f"xilinx-7\t{d}\t{fmt_mhz(x['mhz'])}\testimate: synth_xilinx logic depth, {x['levels']} LUT levels x "
                    f"{LUT_NS} ns + {x['carry']} CARRY4 x {CARRY_NS} ns\t{lanes}\t-\t{x['luts']}\t{x['ffs']}\t{x['dsps']}\t"
                    f"{x['brams']:g}\t{x['levels']}\t{config_text(a.default)}")
    return "\n".join(rows) + "\n"


# ---- merge ----

TABLE_HEAD = [
    "# The measured clock and area of each depth, per target and configuration (docs/hardware.md, \"Timing and area "
    "per depth\").",
    "# bash bench/timing.sh merges its rows in (bench/timing/report.py merge): a run replaces the rows of its targets, "
    "configurations and depths and keeps the others. Every modelled rate's clock and voxcd size --target read it "
    "(host/device/timing_table.h).",
]


def read_table(text, where):
    """(the '# measured:' lines by configuration, the rows as cell lists) of a table; SystemExit naming `where` for a
    table without the header or with a row of another number of columns."""
    measured, rows, header = {}, [], False
    for n, line in enumerate(text.splitlines(), 1):
        m = MEASURED.match(line)
        if m:
            measured[same_config(m.group(1))] = line
        if not line or line.startswith("#"):
            continue
        if not header:
            if line != TABLE_COLUMNS:
                raise SystemExit(f"report.py merge: {where}:{n}: the header is not '{TABLE_COLUMNS}'")
            header = True
            continue
        cells = line.split("\t")
        if len(cells) != TABLE_COLUMNS.count("\t") + 1:
            raise SystemExit(f"report.py merge: {where}:{n}: {len(cells)} columns, expected 12")
        rows.append(cells)
    if not header:
        raise SystemExit(f"report.py merge: {where}: no header line")
    return measured, rows


def row_key(cells):
    return cells[0], same_config(cells[11]), int(cells[1])


def merge_table(old_text, run_text, old_where="the table", run_where="the run's table"):
    """The table with the run's rows in place of those of the same target, configuration and depth, the others kept
    in their order and new rows after them; the '# measured:' line of each configuration the run measured
    replaced."""
    old_measured, old_rows = read_table(old_text, old_where)
    run_measured, run_rows = read_table(run_text, run_where)
    fresh = {row_key(r): r for r in run_rows}
    rows = [fresh.pop(row_key(r), r) for r in old_rows]
    rows += [r for r in run_rows if row_key(r) in fresh]
    measured = {**old_measured, **run_measured}
    lines = TABLE_HEAD + list(measured.values()) + [TABLE_COLUMNS] + ["\t".join(r) for r in rows]
    return "\n".join(lines) + "\n"


def doc_block(doc, name="timing"):
    """The lines between docs' `<!-- bench:NAME:begin -->` and `<!-- bench:NAME:end -->`."""
    begin, end = f"<!-- bench:{name}:begin -->", f"<!-- bench:{name}:end -->"
    lines = doc.splitlines()
    if begin not in lines or end not in lines:
        raise SystemExit(f"report.py merge: the document has no {begin} ... {end} block")
    return lines[lines.index(begin) + 1:lines.index(end)]


def sections(lines):
    """(the lines before the first section, [(configuration, its lines)]) of a block."""
    head, parts = [], []
    for line in lines:
        m = SECTION.match(line)
        if m:
            parts.append((same_config(m.group(1)), []))
        (parts[-1][1] if parts else head).append(line)
    return head, parts


def merge_block(block_lines, run_markdown):
    """The block with the run's section in place of its configuration's, or after the others."""
    head, parts = sections(block_lines)
    run_head, run_parts = sections(run_markdown.splitlines())
    if run_head or len(run_parts) != 1:
        raise SystemExit("report.py merge: the run's Markdown is not one configuration's section")
    config, run_lines = run_parts[0]
    while run_lines and not run_lines[-1]:
        run_lines.pop()
    replaced = False
    for i, (c, lines) in enumerate(parts):
        if c == config:
            parts[i], replaced = (c, run_lines + [""]), True
    if not replaced:
        if parts and parts[-1][1] and parts[-1][1][-1]:
            parts[-1][1].append("")
        parts.append((config, run_lines + [""]))
    lines = head + [line for _, part in parts for line in part]
    while lines and not lines[-1]:
        lines.pop()
    return "\n".join(lines) + "\n"


def merge_main(argv):
    ap = argparse.ArgumentParser(prog="report.py merge")
    ap.add_argument("--run-markdown", required=True)
    ap.add_argument("--run-table", required=True)
    ap.add_argument("--doc", required=True)
    ap.add_argument("--table", required=True)
    ap.add_argument("--out-markdown", required=True)
    ap.add_argument("--out-table", required=True)
    a = ap.parse_args(argv)

    def read(path):
        with open(path) as f:
            return f.read()

    block = merge_block(doc_block(read(a.doc)), read(a.run_markdown))
    merged = merge_table(read(a.table), read(a.run_table), a.table, a.run_table)
    with open(a.out_markdown, "w") as f:
        f.write(block)
    with open(a.out_table, "w") as f:
        f.write(merged)


def main():
    if sys.argv[1:2] == ["merge"]:
        return merge_main(sys.argv[2:])
    ap = argparse.ArgumentParser()
    ap.add_argument("--depths", required=True)
    ap.add_argument("--goal-mhz", type=float, required=True)
    ap.add_argument("--sram", nargs=3, required=True)
    ap.add_argument("--wire", nargs=2, required=True)
    ap.add_argument("--fanout", required=True)
    ap.add_argument("--small", required=True)
    ap.add_argument("--default", required=True)
    ap.add_argument("--ice40", type=int, choices=(0, 1), default=1)
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
        if a.ice40:
            res["hx8k"][d] = ice40("hx8k", d)
            res["up5k"][d] = ice40("up5k", d)
            res["up5k_dsp"][d] = [int(x) for x in open(f"up5k-d{d}.dsp.txt").read().split()]
    with open(a.markdown, "w") as f:
        f.write(markdown(a, res))
    with open(a.table, "w") as f:
        f.write(table(a, res))


if __name__ == "__main__":
    main()
