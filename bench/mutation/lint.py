# lint.py: whether a mutant is lint-clean (bench/mutation.sh): its file mutated in a copy of rtl/, then
# `verilator --lint-only -Wall` over voxcd.f in every configuration the mutants are built in. A mutant that warns or
# does not elaborate in one of them is stillborn: it is not built or run, and is counted apart.
import os
import shutil
import subprocess
import tempfile
from concurrent.futures import ThreadPoolExecutor

import configs
import mutants


def lint_one(work, rtl_dir, m, cfgs, verilator):
    with open(os.path.join(rtl_dir, m.file)) as f:
        lines = f.read().split("\n")
    path = os.path.join(work, m.file)
    with open(path, "w") as f:
        f.write("\n".join(mutants.apply(lines, m, m.mutated)))
    try:
        for family, pairs in cfgs:
            cmd = [verilator, "--lint-only", "-Wall", *configs.gargs(pairs), "--top-module", configs.top(family),
                   "-F", "voxcd.f"]
            r = subprocess.run(cmd, cwd=work, capture_output=True, text=True)
            if r.returncode != 0:
                first = next((l for l in r.stderr.splitlines() if l.startswith("%")), "lint failed")
                return f"stillborn: {pairs}: {first.strip()[:160]}"
        return ""
    finally:
        shutil.copy(os.path.join(rtl_dir, m.file), path)


def lint_all(rtl_dir, ms, cfgs, jobs=2, verilator="verilator"):
    """Sets each mutant's status: '' when lint-clean in every configuration, else 'stillborn: why'."""
    works = [tempfile.mkdtemp(prefix="voxcd_mut_lint") for _ in range(jobs)]
    for w in works:
        shutil.rmtree(w)
        shutil.copytree(rtl_dir, w)
    free = list(works)

    def task(m):
        w = free.pop()
        try:
            m.status = lint_one(w, rtl_dir, m, cfgs, verilator)
        finally:
            free.append(w)

    with ThreadPoolExecutor(jobs) as pool:
        list(pool.map(task, ms))
    for w in works:
        shutil.rmtree(w)
