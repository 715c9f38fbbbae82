# schema.py: one copy of rtl/ that holds every mutant of a list at once (a mutant schema; bench/mutation.sh). Each
# mutated span becomes `(voxcd_mut(K) ? (mutant) : (original))`, with voxcd_mut a DPI-C import that is true for the
# one mutant the process runs (bench/mutation/mutant.cpp reads VOXCD_MUTANT), so one Verilated build runs them all.
import os
import shutil

import mutants

IMPORT = ('// bench/mutation: which mutant runs (bench/mutation/mutant.cpp).\n'
          'import "DPI-C" pure function bit voxcd_mut(input int unsigned k);\n')


def write(rtl_dir, out_dir, ms):
    """Writes the schema copy of rtl_dir (its voxcd.f and files) into out_dir for the mutants that are not stillborn."""
    os.makedirs(out_dir, exist_ok=True)
    live = [m for m in ms if not m.status]
    for name in os.listdir(rtl_dir):
        if not (name.endswith((".sv", ".svh", ".vlt")) or name == "voxcd.f"):
            continue
        with open(os.path.join(rtl_dir, name)) as f:
            lines = f.read().split("\n")
        spans = {}
        for m in live:
            if m.file == name:
                spans.setdefault((m.line, m.start, m.end), []).append(m)
        # Right to left on each line, so that earlier spans keep their columns.
        for (line, start, end) in sorted(spans, key=lambda s: (s[0], -s[1])):
            group = spans[(line, start, end)]
            text = f"({group[0].original})"
            for m in group:
                text = f"(voxcd_mut({m.id}) ? ({m.mutated}) : {text})"
            lines = mutants.apply(lines, group[0], text)
        if name == "voxcd_assert.svh":  # read once, before every module (rtl/voxcd.f)
            lines = IMPORT.split("\n") + lines
        new = "\n".join(lines)
        path = os.path.join(out_dir, name)
        old = open(path).read() if os.path.exists(path) else None
        if old != new:  # unchanged files keep their time: nothing is Verilated again for nothing
            with open(path, "w") as f:
                f.write(new)
