#!/usr/bin/python3
# report.py: the summary of a mutation run as Markdown (bench/mutation.sh): the score, the mutants by file and by
# the stage that killed them, and every survivor with its line and either the reason it is equivalent
# (equivalent.tsv: "file<TAB>line<TAB>change<TAB>mutated<TAB>why"), or why the suite misses a mutant that is not
# equivalent (explained.tsv, the same columns: it counts against the score), or "not explained".
#   report.py results.tsv equivalent.tsv [--explained explained.tsv] [--build-seconds N] [--run-seconds N]
import argparse
import collections

STAGES = ("vectors", "directed", "scoreboard")


def read_tsv(path):
    with open(path) as f:
        head = f.readline().rstrip("\n").split("\t")
        return [dict(zip(head, l.rstrip("\n").split("\t"))) for l in f if l.strip()]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("results")
    ap.add_argument("equivalent")
    ap.add_argument("--explained")
    ap.add_argument("--build-seconds", type=int, default=0)
    ap.add_argument("--run-seconds", type=int, default=0)
    a = ap.parse_args()
    rows = read_tsv(a.results)
    why = {(e["file"], e["line"], e["what"], e["mutated"]): e["why"] for e in read_tsv(a.equivalent)}
    missed = {(e["file"], e["line"], e["what"], e["mutated"]): e["why"]
              for e in (read_tsv(a.explained) if a.explained else [])}
    for r in rows:
        key = (r["file"], r["line"], r["what"], r["mutated"])
        alive = r["result"] == "survived"
        r["equivalent"] = why.get(key, "") if alive else ""
        r["explained"] = missed.get(key, "") if alive and not r["equivalent"] else ""
    count = collections.Counter(r["result"] for r in rows)
    by_stage = collections.Counter(r["stage"] for r in rows if r["result"] == "killed")
    equivalent = sum(1 for r in rows if r["equivalent"])
    killed, survived = count["killed"], count["survived"]
    non_equivalent = killed + survived - equivalent
    score = 100.0 * killed / non_equivalent if non_equivalent else 0.0
    p = print
    p(f"Mutants generated: {len(rows)}; stillborn (not lint-clean in every configuration): {count['stillborn']}; "
      f"not reached (their site is in code no configuration elaborates): {count['unreached']}; run: "
      f"{killed + survived}.")
    explained = sum(1 for r in rows if r["explained"])
    unexplained = survived - equivalent - explained
    p(f"Killed: {killed} ({', '.join(f'{s} {by_stage[s]}' for s in STAGES)}); survived: {survived}, of which "
      f"{equivalent} equivalent, {explained} not equivalent and explained, {unexplained} not explained. **Score: {killed} / {non_equivalent} = {score:.1f}%** of non-equivalent mutants.")
    if a.build_seconds or a.run_seconds:
        p(f"Wall time: {a.build_seconds // 60} min {a.build_seconds % 60} s to generate, lint and build, "
          f"{a.run_seconds // 60} min {a.run_seconds % 60} s to run (2 at a time).")
    p("")
    p("| file | mutants | stillborn | not reached | killed: vectors | directed | scoreboard | survived | equivalent |")
    p("|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    files = list(dict.fromkeys(r["file"] for r in rows))
    for f in files:
        rs = [r for r in rows if r["file"] == f]
        c = collections.Counter(r["result"] for r in rs)
        k = collections.Counter(r["stage"] for r in rs if r["result"] == "killed")
        e = sum(1 for r in rs if r["equivalent"])
        p(f"| `{f}` | {len(rs)} | {c['stillborn']} | {c['unreached']} | {k['vectors']} | {k['directed']} | "
          f"{k['scoreboard']} | {c['survived']} | {e} |")
    p("")
    surv = [r for r in rows if r["result"] == "survived"]
    if surv:
        p("Survivors:")
        p("")
        p("| mutant | line | change | equivalent | why it survives |")
        p("|---:|---|---|---|---|")
        for r in surv:
            change = f"{r['what']}: `{r['original']}` -> `{r['mutated']}`".replace("|", "\\|")
            reason = r["equivalent"] or r["explained"] or "**not explained**"
            p(f"| {r['id']} | `{r['file']}:{r['line']}` | {change} | {'yes' if r['equivalent'] else '**no**'} | "
              f"{reason.replace('|', chr(92) + '|')} |")


main()
