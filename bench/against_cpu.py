#!/usr/bin/python3
"""docs/hardware.md "Against the CPU": the table bench/against_cpu.sh writes, and the check its ctest runs.

  against_cpu.py table --simulate SIM.jsonl --bench BENCH.jsonl --timing TSV --energy TSV --command C --seconds S
                       --revision R --machine M --load L
  against_cpu.py check FILE --lanes 4,8,16,32,64

SIM.jsonl: one line per configuration, {"lanes": L, "depth": D, "simulate": <voxcd simulate --json>}.
BENCH.jsonl: build/bench_against_cpu's lines (kind scene, cycles, cpu).
Debian's python3 only (no PyPI).
"""
import argparse
import datetime
import json
import os
import re
import sys

SCENES = ("builtin", "room", "tori")
IGNORED_IN_MATCH = ("SAW", "MAW", "LANES", "DEPTH")  # memories, lanes, depth: matched apart or not at all


def read_jsonl(path):
    with open(path) as f:
        return [json.loads(line) for line in f if line.strip()]


def read_tsv(path):
    """Rows of a tab-separated table whose first non-'#' line is the header, as dicts; [] when there is no file."""
    if not os.path.exists(path):
        return []
    with open(path) as f:
        lines = [l.rstrip("\n") for l in f if l.strip() and not l.startswith("#")]
    if not lines:
        return []
    header = lines[0].split("\t")
    return [dict(zip(header, l.split("\t"))) for l in lines[1:]]


def config_pairs(text):
    """'PW 24 PF 8 ... LANES 4' -> {'PW': '24', ...}."""
    words = text.split()
    return dict(zip(words[0::2], words[1::2]))


def widths(text):
    return {k: v for k, v in config_pairs(text).items() if k not in IGNORED_IN_MATCH}


def timing_row(rows, device, lanes, depth):
    """The asic-osu018 row of the timing table for this configuration (its widths, lanes and depth; the table's
    memories are reduced, and the area leaves the SRAM macros out), or None."""
    for r in rows:
        if (r.get("target") == "asic-osu018" and int(r["lanes"]) == lanes and int(r["depth"]) == depth
                and widths(r["config"]) == widths(device)):
            return r
    return None


def energy_cell(rows, device, lanes, depth):
    """pJ per lookup at 0.18 um from host/sizing/energy.tsv: the built-in scene's ('simulate') asic-osu018 row of this
    configuration (its widths and lanes, memories aside, as the timing row) and depth, with the tori's and the room's
    beside it in brackets; "not measured" where the table has no such row."""
    by_scene = {}
    for r in rows:
        if (r.get("target") == "asic-osu018" and int(r.get("depth", -1)) == depth
                and config_pairs(r.get("config", "")).get("LANES") == str(lanes)
                and widths(r.get("config", "")) == widths(device)):
            by_scene[r.get("scene")] = r.get("pj_per_lookup")
    if "simulate" not in by_scene:
        return "not measured"
    others = ", ".join("%s %s" % (k, v) for k, v in sorted(by_scene.items()) if k != "simulate")
    return by_scene["simulate"] + (" (%s)" % others if others else "")


def si(v):
    for scale, unit in ((1e12, "T"), (1e9, "G"), (1e6, "M"), (1e3, "k")):
        if v >= scale:
            return "%.2f %s" % (v / scale, unit)
    return "%.2f" % v


class Run:
    """What one run measured: simulate's JSON per configuration, the bench program's cycles and cpu times."""

    def __init__(self, sim_path, bench_path):
        self.sim = {(s["lanes"], s["depth"]): s["simulate"] for s in read_jsonl(sim_path)}
        lines = read_jsonl(bench_path)
        self.scenes = {l["scene"]: l for l in lines if l["kind"] == "scene"}
        self.cpu = {l["scene"]: l for l in lines if l["kind"] == "cpu"}
        self.cycles = {(l["scene"], l["lanes"], l["depth"]): l for l in lines if l["kind"] == "cycles"}
        self.configs = sorted(self.sim)

    def ppc(self, scene, lanes, depth):
        if scene == "builtin":
            s = self.sim[(lanes, depth)]
            return s["lookups"] / s["device_cycles"]
        c = self.cycles[(scene, lanes, depth)]
        return c["lookups"] / c["cycles"]

    def cpu_rate(self, scene, key):
        c = self.cpu[scene]
        return c["lookups"] / c[key]

    def check_same_jobs(self):
        """simulate's lookups at every configuration equal the bench program's for the built-in scene."""
        want = self.cpu["builtin"]["lookups"]
        for k, s in self.sim.items():
            if s["lookups"] != want:
                sys.exit("against_cpu.py: simulate at LANES %d DEPTH %d looked up %d points, bench_against_cpu's "
                         "built-in jobs %d: not the same jobs" % (k[0], k[1], s["lookups"], want))


def clock_cells(s):
    mhz = "%.1f" % s["clock_mhz"]
    return (mhz + " estimate" if s.get("clock_estimate") else mhz), s["clock_source"]


def device_row(run, timing, energy, lanes, depth):
    s = run.sim[(lanes, depth)]
    ppc = [run.ppc(sc, lanes, depth) for sc in SCENES]
    clock, source = clock_cells(s)
    rate = ppc[0] * s["clock_mhz"] * 1e6
    row = timing_row(timing, s["device"], lanes, depth)
    area = "%.3f" % float(row["area_mm2"]) if row else "-"
    per_mm2 = si(rate / float(row["area_mm2"])) if row else "-"
    one, every = run.cpu_rate("builtin", "one_core_s"), run.cpu_rate("builtin", "all_cores_s")
    cells = [str(lanes), str(depth)] + ["%.2f" % p for p in ppc] + [
        clock, source, area, si(rate), per_mm2, energy_cell(energy, s["device"], lanes, depth),
        "%.1f" % (rate / one), "%.1f" % (rate / every)]
    return "| " + " | ".join(cells) + " |"


def clock_notes(run, timing):
    """Where simulate's clock for a configuration is not the timing table's measured clock for it."""
    notes = []
    for lanes, depth in run.configs:
        s = run.sim[(lanes, depth)]
        row = timing_row(timing, s["device"], lanes, depth)
        if row and s["clock_source"].startswith("OpenSTA") and abs(float(row["mhz"]) - s["clock_mhz"]) > 0.05:
            notes.append("LANES %d DEPTH %d: simulate gives %.1f MHz, the timing table measured %s MHz" %
                         (lanes, depth, s["clock_mhz"], row["mhz"]))
    return notes


def device_table(run, timing, energy):
    threads = run.cpu["builtin"]["threads"]
    out = ["| LANES | DEPTH | points/cycle, built-in | points/cycle, room | points/cycle, tori | clock (MHz) | "
           "clock source | area (mm^2) | lookups/s (built-in) | lookups/s per mm^2 | pJ per lookup | "
           "x cpu, one core | x cpu, %d threads |" % threads,
           "|--:|--:|--:|--:|--:|--:|---|--:|--:|--:|---|--:|--:|"]
    out += [device_row(run, timing, energy, l, d) for l, d in run.configs]
    return out


def cpu_table(run):
    out = ["| scene | jobs | lookups | one core: lookups/s | every core (%d threads): lookups/s | every / one |"
           % run.cpu["builtin"]["threads"], "|---|--:|--:|--:|--:|--:|"]
    for sc in SCENES:
        c = run.cpu[sc]
        one, every = run.cpu_rate(sc, "one_core_s"), run.cpu_rate(sc, "all_cores_s")
        out.append("| %s | %d | %d | %s | %s | %.2f |" % (sc, c["jobs"], c["lookups"], si(one), si(every), every / one))
    return out


def provenance(a):
    today = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d")
    return ("_Generated by `%s` on %s at revision %s; %s, load average %s at the start; %d s wall._"
            % (a.command, today, a.revision, a.machine, a.load, a.seconds))


def notes(run, timing, a):
    first = run.configs[0]
    frames = run.sim[first]["frames"]
    lines = ["Scenes (every figure of a column on the same jobs):"]
    for sc in SCENES:
        lines.append("- **%s**: %s; %d pairs." % (sc, run.scenes[sc]["description"], run.scenes[sc]["pairs"]))
    lines += [
        "",
        "Points per cycle: lookups / device cycles of the exact timing model (the cpu backend returns the cycles of "
        "the configuration it is given, the RTL's cycle for cycle); at most LANES, less where hit records hold the "
        "output (one a cycle: the tori interpenetrate, so many of their lookups hit) and where short jobs leave lanes "
        "idle. built-in: `build/voxcd simulate --objects 1024 --frames %d --config \"LANES L DEPTH D\" --json` "
        "(`lookups` / `device_cycles`, per-frame streams); room and tori: build/bench_against_cpu, all pairs one "
        "stream." % frames,
        "Clock: simulate's `clock_mhz` and `clock_source` for the configuration; \"estimate\" where its "
        "`clock_estimate` is true. Area: the asic-osu018 row of %s for the configuration's widths, lanes and depth "
        "(standard cells only, the SRAM macros left out; memories reduced to SAW = MAW = 12), \"-\" where the table "
        "has no such row. lookups/s: points per cycle on the built-in scene x the clock. pJ per lookup: %s."
        % (a.timing, "from " + a.energy if os.path.exists(a.energy) else a.energy + " does not exist: not measured"),
        "cpu: the cpu backend (`Device::run` of the same jobs, ALL mode, the default configuration: its speed does "
        "not depend on LANES or depth), median of %d runs after a warm-up; one core by the thread's CPU time, every "
        "core by wall time. x cpu: the row's lookups/s over the cpu backend's on the built-in scene, same run. The "
        "built-in jobs are simulate's: their lookups equal simulate's at every configuration (checked)."
        % run.cpu["builtin"]["repeats"],
    ]
    mismatch = clock_notes(run, timing)
    if mismatch:
        lines.append("Clocks that do not yet follow the configuration (simulate's clock is not the timing table's "
                     "for it): " + "; ".join(mismatch) + ".")
    return lines


def table(a):
    run = Run(a.simulate, a.bench)
    run.check_same_jobs()
    timing, energy = read_tsv(a.timing), read_tsv(a.energy)
    out = [provenance(a), ""] + device_table(run, timing, energy) + [""] + cpu_table(run)
    out += [""] + notes(run, timing, a)
    print("\n".join(out))


def device_rows(text):
    """The device table's rows: lists of cells of lines starting with '| <int> | <int> |'."""
    rows = []
    for line in text.splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) >= 5 and cells[0].isdigit() and cells[1].isdigit():
            rows.append(cells)
    return rows


def check(a):
    with open(a.file) as f:
        text = f.read()
    rows = device_rows(text)
    errors = []
    for lanes in [int(x) for x in a.lanes.split(",")]:
        mine = [r for r in rows if int(r[0]) == lanes]
        if not mine:
            errors.append("no row for LANES %d" % lanes)
        for r in mine:
            for p in r[2:5]:
                if not 0 < float(p) <= lanes:
                    errors.append("LANES %d DEPTH %s: %s points per cycle is not in (0, %d]" % (lanes, r[1], p, lanes))
    if not re.search(r"_Generated by `bash bench/against_cpu.sh", text):
        errors.append("no provenance line")
    for e in errors:
        print("against_cpu.py check: " + e, file=sys.stderr)
    print("against_cpu.py check: %d rows, %s" % (len(rows), "failed" if errors else "ok"))
    return 1 if errors else 0


def main():
    p = argparse.ArgumentParser()
    sub = p.add_subparsers(dest="cmd", required=True)
    t = sub.add_parser("table")
    for k in ("simulate", "bench", "timing", "energy", "command", "revision", "machine", "load"):
        t.add_argument("--" + k, required=True)
    t.add_argument("--seconds", type=int, required=True)
    c = sub.add_parser("check")
    c.add_argument("file")
    c.add_argument("--lanes", default="4,8,16,32,64")
    a = p.parse_args()
    if a.cmd == "table":
        table(a)
        return 0
    return check(a)


if __name__ == "__main__":
    sys.exit(main())
