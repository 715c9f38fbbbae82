#!/usr/bin/python3
# run.py: runs the mutants of a schema build through the suite's stages (bench/mutation/stages.py), two at a time,
# each stopping at its first failing command, and writes one row per mutant (bench/mutation.sh).
# First mutant 0 (the RTL as it is) must pass every stage: it also records which mutants' sites the suite reaches
# (a mutant never reached is in code no configuration built elaborates), and the module must offer exactly the
# configurations of the list, so that no test silently runs fewer models.
#   run.py --mutants DIR/mutants.tsv --configs configs.txt --module M.so --voxcd V --test-rtl T [--test-axi A]
#          --models-check P --vectors tests/vectors --out results.tsv [--only 3,5] [--jobs 2]
import argparse
import os
import re
import resource
import signal
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import configs  # noqa: E402
import mutants  # noqa: E402
import stages  # noqa: E402

DETAIL = re.compile(r"FAIL|Failure|MISMATCH|expected|assertion|error|Error|mismatch|differ")


def limit_memory():
    os.setsid()
    resource.setrlimit(resource.RLIMIT_AS, (6 << 30, 6 << 30))


def run_command(cmd, env, timeout):
    """(ok, seconds, detail) of one command."""
    t0 = time.time()
    p = subprocess.Popen(cmd, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                         errors="replace", preexec_fn=limit_memory)
    try:
        out, _ = p.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGKILL)
        p.communicate()
        return False, time.time() - t0, f"ran past {timeout:.0f} s"
    if p.returncode == 0:
        return True, time.time() - t0, ""
    lines = [l.strip() for l in out.splitlines() if l.strip()]
    hits = [i for i, l in enumerate(lines) if DETAIL.search(l) and not l.startswith("[")]
    detail = " | ".join(lines[hits[0]:hits[0] + 2]) if hits else (lines[-1] if lines else f"exit {p.returncode}")
    if p.returncode < 0:
        detail = f"signal {-p.returncode}: " + detail
    return False, time.time() - t0, detail[:300]


def short(cmd):
    name = os.path.basename(cmd[0])
    sub = cmd[1] if name == "voxcd" else next((c.split("=", 1)[1][:40] for c in cmd if c.startswith("--gtest")), "")
    return f"{name} {sub}".strip()


def run_mutant(k, plan, env0, limits):
    """(result, stage, command, detail, seconds) of mutant k: killed at the first failing command, or survived."""
    env = dict(env0, VOXCD_MUTANT=str(k))
    total = 0.0
    for stage, cmds in plan:
        for i, cmd in enumerate(cmds):
            ok, sec, detail = run_command(cmd, env, limits[(stage, i)])
            total += sec
            if not ok:
                return "killed", stage, short(cmd), detail, total
    return "survived", "", "", "", total


def main():
    ap = argparse.ArgumentParser()
    for a in ("mutants", "configs", "module", "voxcd", "test-rtl", "models-check", "vectors", "out"):
        ap.add_argument("--" + a, required=True)
    ap.add_argument("--test-axi")
    ap.add_argument("--only")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--vector-jobs", type=int, default=300)
    ap.add_argument("--seeds", default="1-2")
    ap.add_argument("--quick", action="store_true", help="fewer vectors; fail unless every mutant is killed")
    a = ap.parse_args()
    if a.quick:
        a.vector_jobs, a.seeds = 100, "1"
    t_start = time.time()
    cfgs = configs.read(a.configs)
    paths = {"voxcd": a.voxcd, "test_rtl": a.test_rtl, "test_axi": a.test_axi, "vectors": a.vectors}
    plan = stages.stages(paths, cfgs, a.vector_jobs, a.seeds)
    env0 = dict(os.environ, VOXCD_RTL_MODULE=os.path.abspath(a.module), SYSTEMC_DISABLE_COPYRIGHT_MESSAGE="1")
    env0.pop("VOXCD_MUTANT_REACHED", None)

    # The module offers exactly the list's device configurations, family by family.
    want = sorted(f"{f}|{p}" for f, p in cfgs if f != "axi")
    got = subprocess.run([a.models_check, a.configs], env=env0, capture_output=True, text=True)
    have = sorted(l.strip() for l in got.stdout.splitlines() if l.strip())
    if got.returncode != 0 or have != want:
        sys.exit(f"mutation: the module offers {have}, not the configurations {want} ({got.stderr.strip()})")

    # Mutant 0 passes every command; each command's time sets its limit for the mutants.
    fd, reached_path = tempfile.mkstemp(prefix="voxcd_mut_reached")
    os.close(fd)
    env_reach = dict(env0, VOXCD_MUTANT="0", VOXCD_MUTANT_REACHED=reached_path)
    limits = {}
    for stage, cmds in plan:
        for i, cmd in enumerate(cmds):
            ok, sec, detail = run_command(cmd, env_reach, 3600)
            print(f"mutant 0: {stage}: {short(cmd)}: {'pass' if ok else 'FAIL'} in {sec:.1f} s", flush=True)
            if not ok:
                sys.exit(f"mutation: the RTL as it is fails {stage} ({' '.join(cmd)}): {detail}")
            limits[(stage, i)] = max(30.0, 4 * sec)
    with open(reached_path) as f:
        reached = {int(l) for l in f if l.strip()}
    os.remove(reached_path)

    ms = mutants.read(a.mutants)
    if a.only:
        keep = {int(x) for x in a.only.split(",")}
        ms = [m for m in ms if m.id in keep]
    rows = {}
    out = open(a.out, "w")  # rows as mutants finish, so that a stopped run keeps what it ran
    out.write("id\tfile\tline\twhat\toriginal\tmutated\tresult\tstage\tcommand\tdetail\tseconds\n")

    def one(m):
        if m.status:
            r = ("stillborn", "", "", m.status[len("stillborn: "):], 0.0)
        elif m.id not in reached:
            r = ("unreached", "", "", "no configuration of the list evaluates its site", 0.0)
        else:
            r = run_mutant(m.id, plan, env0, limits)
        rows[m.id] = r
        out.write("\t".join([str(m.id), m.file, str(m.line), m.what, m.original, m.mutated, r[0], r[1], r[2],
                             r[3].replace("\t", " "), f"{r[4]:.1f}"]) + "\n")
        out.flush()
        print(f"mutant {m.id} ({m.file}:{m.line} {m.what}): {r[0]} {r[1]} {r[2]} {r[4]:.1f} s", flush=True)

    with ThreadPoolExecutor(a.jobs) as pool:
        list(pool.map(one, ms))
    out.close()
    print(f"mutation: {len(ms)} mutants run in {time.time() - t_start:.0f} s; rows in {a.out}")
    if a.quick:
        missed = [k for k, r in rows.items() if r[0] != "killed"]
        if missed:
            sys.exit(f"mutation: mutants {missed} were not killed")
        print(f"mutation: all {len(rows)} mutants killed")


main()
