#!/usr/bin/env bash
# bench/frame_stages.sh: where a frame of `voxcd simulate --objects N` goes, the first frame apart from the later
# ones (docs/simulate.md, "Against the goals"): for each built `voxcd` given, runs of 1 and of F frames (ROUNDS
# rounds, each running every tool in turn; medians), stage seconds as the tool reports them; a later frame is
# (F frames - 1 frame) / (F - 1). The first frame pays for the memory first touched (page faults) and for a grid
# with no last order to follow. Prints a Markdown table.
# Usage: N=1000000 F=6 ROUNDS=3 THREADS=2 bash bench/frame_stages.sh VOXCD [VOXCD...]
set -euo pipefail
N="${N:-1000000}" F="${F:-6}" ROUNDS="${ROUNDS:-3}" THREADS="${THREADS:-2}"
(($# >= 1)) || { echo "usage: bash bench/frame_stages.sh VOXCD [VOXCD...]" >&2; exit 2; }
tmp="$(mktemp)"
trap 'rm -f "$tmp"' EXIT
for ((round = 0; round < ROUNDS; round++)); do
  for bin in "$@"; do
    for frames in 1 "$F"; do
      "$bin" simulate --objects "$N" --threads "$THREADS" --frames "$frames" --no-progress --json |
        python3 -c 'import json, sys; d = json.load(sys.stdin); s = d["stage_seconds"]
print(sys.argv[1], sys.argv[2], d["state_hash"], *(s[k] for k in ("integrate", "bounds", "broadphase", "narrow", "response")))' \
          "$bin" "$frames" >>"$tmp"
    done
  done
done
python3 - "$tmp" "$F" "$N" "$THREADS" "$@" <<'PY'
import statistics, sys
path, F, N, T, bins = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4], sys.argv[5:]
rows = [l.split() for l in open(path)]
stages = ["integrate", "bounds", "broadphase", "narrow", "response"]
print("| voxcd | frame | " + " | ".join(stages) + " | frame (ms) |")
print("|---|---|" + "--:|" * (len(stages) + 1))
for b in bins:
    def med(frames):
        return [statistics.median(float(r[3 + i]) for r in rows if r[0] == b and r[1] == str(frames)) for i in range(5)]
    one, many = med(1), med(F)
    later = [(m - o) / (F - 1) for m, o in zip(many, one)]
    for what, v in (("first", one), ("later (mean of %d)" % (F - 1), later)):
        print("| %s | %s | " % (b, what) + " | ".join("%.1f" % (1000 * x) for x in v) + " | %.1f |" % (1000 * sum(v)))
hashes = {r[2] for r in rows if r[1] == str(F)}
print()
print("Milliseconds a frame by stage, `voxcd simulate --objects %s --threads %s` (medians of the rounds' runs of 1 and %d frames); state hash after %d frames: %s." % (N, T, F, F, ", ".join(sorted(hashes))))
PY
