#!/usr/bin/python3
# generate.py: the mutants of rtl/ and their schema (bench/mutation.sh). Scans every file of rtl/voxcd.f for sites,
# takes a seeded sample spread over the files (or the named mutants of a pick file: the quick subset), lints each
# mutant in every configuration of the configuration list (a failure makes it stillborn), then writes OUT/mutants.tsv
# and the schema copy of rtl/ in OUT/rtl.
#   generate.py --rtl rtl --configs configs.txt --out DIR (--count N --seed S --min M | --pick quick.txt)
import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import configs  # noqa: E402
import lint  # noqa: E402
import mutants  # noqa: E402
import schema  # noqa: E402


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--rtl", required=True)
    ap.add_argument("--configs", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--count", type=int, default=320)
    ap.add_argument("--seed", type=int, default=42)
    ap.add_argument("--min", type=int, default=10)
    ap.add_argument("--pick")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--verilator", default="verilator")
    ap.add_argument("--no-lint", action="store_true")
    a = ap.parse_args()
    cands = [m for m in mutants.candidates(a.rtl) if not m.lhs_unused]
    if a.pick:
        with open(a.pick) as f:
            spec = [l.rstrip("\n") for l in f if l.strip() and not l.startswith("#")]
        chosen = mutants.pick(mutants.attach_lines(cands, a.rtl), spec)
    else:
        chosen = mutants.sample(cands, a.count, a.seed, a.min)
    if not a.no_lint:
        lint.lint_all(a.rtl, chosen, configs.read(a.configs), a.jobs, a.verilator)
    os.makedirs(a.out, exist_ok=True)
    mutants.write(os.path.join(a.out, "mutants.tsv"), chosen)
    schema.write(a.rtl, os.path.join(a.out, "rtl"), chosen)
    born = sum(1 for m in chosen if not m.status)
    print(f"mutation: {len(cands)} candidate mutants, {len(chosen)} chosen, {len(chosen) - born} stillborn, "
          f"{born} in the schema {os.path.join(a.out, 'rtl')}")


main()
