#!/usr/bin/env python3
"""What each list of device models costs to build (docs/build.md, "What each list costs").

Every Verilated model of a configured build (BUILD, default build/), one at a time in a temporary directory:
Verilator with the build's own command, rtl/model_units.cmake, then the model's two units with the build's own
compile commands without ccache. Prints a Markdown table: per list of docs/build.md's options (read from the
build's CMakeCache.txt), its models and their cold cost in seconds; with --models, a row per model too.

Usage: python3 bench/model_cost.py [--build DIR] [--models] [--only LIST ...]
(--only: just the models of the lists named, e.g. --only VOXCD_RTL_SPARSE_MODELS VOXCD_RTL_LANES)
"""
import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def prefix(stem, pairs):
    """rtl/models.cmake's voxcd_model_prefix: "SB 8 WB 8 LANES 4" -> <stem>_sb8_wb8_lanes4."""
    name = re.sub(r"([a-z0-9]+) +(-?[0-9]+)", r"\1\2", pairs.strip().lower())
    return stem + "_" + re.sub(r" +", "_", name).replace("-", "m")


def cache(build):
    """The build's CMake cache as a dict of strings."""
    out = {}
    with open(os.path.join(build, "CMakeCache.txt")) as f:
        for line in f:
            m = re.match(r"^([A-Za-z0-9_]+):[A-Z]+=(.*)$", line.rstrip("\n"))
            if m:
                out[m.group(1)] = m.group(2)
    return out


def lists(c):
    """Each option list and the model names its entries make, in docs/build.md's order."""
    split = lambda k: [e for e in c.get(k, "").split(";") if e.strip()]
    derived = {}
    with open(os.path.join(ROOT, "tests/scenes/configs.txt")) as f:
        for line in f:
            if line.strip() and not line.startswith("#"):
                scene, pairs = line.split(None, 1)
                derived[scene] = pairs.strip()
    sysc_axi = c.get("VOXCD_SYSC_AXI_PAIRS", "LANES 4")
    return [
        ("VOXCD_RTL_LANES", [prefix("Vvoxcd", "LANES " + l) for l in split("VOXCD_RTL_LANES")]),
        ("VOXCD_RTL_CONFIGS", [prefix("Vvoxcd", derived[s]) for s in split("VOXCD_RTL_CONFIGS")]),
        ("VOXCD_RTL_DIST_MODELS", [prefix("Vvoxcd", p) for p in split("VOXCD_RTL_DIST_MODELS")]),
        ("VOXCD_RTL_BANKED_MODELS", [prefix("Vvoxcd", p) for p in split("VOXCD_RTL_BANKED_MODELS")]),
        ("VOXCD_RTL_DEPTH_MODELS", [prefix("Vvoxcd", p) for p in split("VOXCD_RTL_DEPTH_MODELS")]),
        ("VOXCD_RTL_SPARSE_MODELS", [prefix("Vvoxcd", p) for p in split("VOXCD_RTL_SPARSE_MODELS")]),
        ("VOXCD_AXI_MODELS", [prefix("Vvoxcd_axi", p) for p in split("VOXCD_AXI_MODELS")]),
        ("VOXCD_SYSC_LANES", [prefix("Vvoxcd_sc", "LANES " + l) for l in split("VOXCD_SYSC_LANES")]),
        ("VOXCD_SYSC_DIST_MODELS", [prefix("Vvoxcd_sc", p) for p in split("VOXCD_SYSC_DIST_MODELS")]),
        ("VOXCD_SYSC_BANKED_MODELS", [prefix("Vvoxcd_sc", p) for p in split("VOXCD_SYSC_BANKED_MODELS")]),
        ("VOXCD_SYSC_DEPTH_MODELS", [prefix("Vvoxcd_sc", p) for p in split("VOXCD_SYSC_DEPTH_MODELS")]),
        ("VOXCD_SYSC_SPARSE_MODELS", [prefix("Vvoxcd_sc", p) for p in split("VOXCD_SYSC_SPARSE_MODELS")]),
        ("VOXCD_SYSC_AXI_PAIRS (" + sysc_axi + ")", ["Vvoxcd_sc_axi"]),
        ("bench/cosim.cmake (fixed)", ["Vcosim_base", "Vcosim_notrace", "Vcosim_sized", "Vcosim_noassert"]),
    ]


def commands(build, target):
    return subprocess.run(["ninja", "-t", "commands", target], cwd=build, capture_output=True, text=True,
                          check=True).stdout.splitlines()


def measure(build, obj, name, work):
    """(Verilator seconds, compiler seconds) of model `name`, whose fast unit's object is `obj`."""
    out = os.path.join(work, name)
    os.makedirs(out)
    verilate = [c for c in commands(build, obj) if "--prefix " + name + " " in c][0]
    mdir = re.search(r"--Mdir (\S+)", verilate).group(1)
    t0 = time.monotonic()
    subprocess.run(verilate.replace(mdir, out), shell=True, check=True, stdout=subprocess.DEVNULL)
    t1 = time.monotonic()
    for unit in ("fast", "slow"):
        cc = commands(build, obj.replace("__fast.cpp.o", "__" + unit + ".cpp.o"))[-1]
        cc = re.sub(r"^\S*ccache ", "", cc)
        cc = re.sub(r" -MD -MT \S+ -MF \S+", "", cc)
        cc = re.sub(r" -o \S+", " -o " + os.path.join(out, unit + ".o"), cc)
        cc = re.sub(r" -c \S+", " -c " + os.path.join(out, name + "__" + unit + ".cpp"), cc)
        subprocess.run(cc, shell=True, check=True, cwd=build)
    t2 = time.monotonic()
    shutil.rmtree(out)
    return t1 - t0, t2 - t1


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--models", action="store_true", help="a row per model as well")
    ap.add_argument("--only", nargs="+", metavar="LIST", help="only the models of these lists")
    a = ap.parse_args()
    wanted = None
    if a.only:
        known = lists(cache(a.build))
        wanted = set(n for title, names in known if title.split(" ")[0] in a.only for n in names)
    ninja = open(os.path.join(a.build, "build.ninja")).read()
    found = re.findall(r"^build ([^\s:]+/(V[A-Za-z0-9_]+)__fast\.cpp\.o):", ninja, re.M)
    objs = dict((name, obj) for obj, name in found)
    testbenches = sum(1 for _, name in found if name.startswith("Vtb_"))
    cost = {}
    with tempfile.TemporaryDirectory(prefix="voxcd-model-cost-") as work:
        for name, obj in objs.items():
            if name.startswith("Vtb_"):
                continue  # tests/ref/dpi's testbenches: one prefix for several, not a list of docs/build.md
            if wanted is not None and name not in wanted:
                continue
            cost[name] = measure(a.build, obj, name, work)
            print(f"{name}: Verilator {cost[name][0]:.1f} s, compiler {cost[name][1]:.1f} s", file=sys.stderr)
    print("| list | models | seconds per model | seconds for the list |\n|---|--:|--:|--:|")
    total = 0.0
    for title, names in lists(cache(a.build)):
        names = list(dict.fromkeys(n for n in names if n in cost))
        if not names and wanted is not None:
            continue
        each = [sum(cost[n]) for n in names]
        total += sum(each)
        span = f"{min(each):.1f} - {max(each):.1f}" if len(each) > 1 else (f"{each[0]:.1f}" if each else "-")
        print(f"| `{title}` | {len(names)} | {span} | {sum(each):.0f} |")
        if a.models:
            for n, s in zip(names, each):
                print(f"| &nbsp;&nbsp;{n} | | {s:.1f} (Verilator {cost[n][0]:.1f}) | |")
    print(f"\n{len(cost)} models, {total:.0f} s in all; {testbenches} testbench "
          "builds of tests/ref/dpi not counted.")


if __name__ == "__main__":
    main()
