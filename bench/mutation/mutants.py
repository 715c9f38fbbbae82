# mutants.py: the mutants of rtl/ as rows (bench/mutation.sh): every candidate of every file of rtl/voxcd.f, a
# seeded sample spread over the files, and the mutant list's file format (mutants.tsv).
import os
import random
import re
from dataclasses import dataclass

import operators
import scan


@dataclass
class Mutant:
    id: int
    file: str
    line: int
    start: int
    end: int
    kind: str
    what: str      # the change, e.g. "operator + -> -"
    original: str  # the span's text
    mutated: str   # its replacement
    status: str = ""  # "" (to run), "stillborn: ..." after lint
    lhs_unused: bool = False  # assigns an unused_* signal (lint's sink for bits that are read nowhere by design)

    def row(self):
        esc = lambda s: s.replace("\t", " ")
        return "\t".join([str(self.id), self.file, str(self.line), str(self.start), str(self.end), self.kind,
                          esc(self.what), esc(self.original), esc(self.mutated), esc(self.status)])


HEADER = "id\tfile\tline\tstart\tend\tkind\twhat\toriginal\tmutated\tstatus"


def rtl_files(rtl_dir):
    """The SystemVerilog files of voxcd.f, in its order."""
    names = []
    with open(os.path.join(rtl_dir, "voxcd.f")) as f:
        for line in f:
            line = line.strip()
            if line and not line.startswith("//") and line.endswith(".sv"):
                names.append(line)
    return names


def candidates(rtl_dir):
    """Every mutant of every file, unnumbered, in file and line order."""
    out = []
    for name in rtl_files(rtl_dir):
        with open(os.path.join(rtl_dir, name)) as f:
            lines = f.read().split("\n")
        for site in scan.scan(name, "\n".join(lines)):
            expr = lines[site.line - 1][site.start:site.end]
            for what, mutated in operators.site_mutants(site, expr):
                out.append(Mutant(0, name, site.line, site.start, site.end, site.kind, what, expr, mutated,
                                  lhs_unused=site.lhs.startswith(("unused", "cov_"))))
    return out


def sample(cands, count, seed, minimum):
    """About `count` mutants: each file's share of the candidates, at least `minimum` (or all it has), numbered."""
    rng = random.Random(seed)
    by_file = {}
    for m in cands:
        by_file.setdefault(m.file, []).append(m)
    total = len(cands)
    chosen = []
    for name, ms in by_file.items():
        want = min(len(ms), max(minimum, round(count * len(ms) / total)))
        chosen += rng.sample(ms, want)
    chosen.sort(key=lambda m: (list(by_file).index(m.file), m.line, m.start, m.what))
    for k, m in enumerate(chosen, 1):
        m.id = k
    return chosen


def pick(cands, spec_lines):
    """Mutants named by spec lines "file<TAB>text of the line<TAB>change" (the quick subset), numbered in order."""
    out = []
    for spec in spec_lines:
        name, anchor, what = spec.split("\t")
        found = [m for m in cands if m.file == name and m.what == what and anchor in m.original_line]
        if len(found) != 1:
            raise SystemExit(f"mutation: '{spec}' names {len(found)} mutants, not one")
        out.append(found[0])
    for k, m in enumerate(out, 1):
        m.id = k
    return out


def write(path, mutants):
    with open(path, "w") as f:
        f.write(HEADER + "\n")
        for m in mutants:
            f.write(m.row() + "\n")


def read(path):
    out = []
    with open(path) as f:
        next(f)
        for line in f:
            c = line.rstrip("\n").split("\t")
            out.append(Mutant(int(c[0]), c[1], int(c[2]), int(c[3]), int(c[4]), c[5], c[6], c[7], c[8], c[9]))
    return out


def attach_lines(cands, rtl_dir):
    """Gives each candidate the text of its line (original_line), for pick()."""
    cache = {}
    for m in cands:
        if m.file not in cache:
            with open(os.path.join(rtl_dir, m.file)) as f:
                cache[m.file] = f.read().split("\n")
        m.original_line = cache[m.file][m.line - 1]
    return cands


def apply(text_lines, m, replacement):
    """The file's lines with mutant m's span replaced."""
    lines = list(text_lines)
    line = lines[m.line - 1]
    assert line[m.start:m.end] == m.original, f"mutant {m.id}: {m.file}:{m.line} no longer holds '{m.original}'"
    lines[m.line - 1] = line[:m.start] + replacement + line[m.end:]
    return lines


def strip_ws(s):
    return re.sub(r"\s+", " ", s).strip()
