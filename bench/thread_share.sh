#!/usr/bin/env bash
# bench/thread_share.sh: how much of a `voxcd simulate` frame runs inside the thread pool's loops, counted in
# instructions (callgrind), so the largest speed-up a second thread can give whatever the machine's load
# (docs/simulate.md, "Against the goals"). For each N of --objects:
#   - callgrind of `voxcd simulate --objects N --threads 2` at F and 2F frames (VOXCD_SPIN_US=0: idle workers sleep
#     at once, so no spinning is counted); the difference over F is one frame's work, the set-up cancelling;
#   - instructions a frame in all; of them inside the pool's loops (ThreadPool::drain, on either thread: the loop
#     bodies and the taking of tasks); the pool's loops a frame (calls of ThreadPool::run_loop);
#   - Amdahl's bound for 2 threads: I / (I - P + P / 2), with P the instructions inside the loops;
#   - the same frames on one thread (--threads 1): its instructions a frame, so that what two threads add is seen.
# The bound counts instructions, not cycles: the cache lines that move between cores, the wake-ups and the loops'
# imbalance (a loop is as slow as its slowest thread) are what separate a measured speed-up from it.
# Usage: bash bench/thread_share.sh [VOXCD] [N:F ...]     (default build/voxcd 256:200 4096:20)
# Needs valgrind (Debian package).
set -euo pipefail
voxcd="${1:-build/voxcd}"
shift || true
cases=("$@")
((${#cases[@]})) || cases=(256:200 4096:20)
command -v valgrind >/dev/null || { echo "thread_share.sh: valgrind not found: apt-get install valgrind" >&2; exit 1; }
[ -x "$voxcd" ] || { echo "thread_share.sh: $voxcd is not a built voxcd (cmake --build build --target voxcd)" >&2; exit 1; }
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT

# counts FILE: "<total> <inside drain> <run_loop calls>" of a callgrind output file.
counts() {
  /usr/bin/python3 - "$1" <<'EOF'
import re, sys
names, fn, total, drain, loops = {}, None, 0, 0, 0
cfn, pending = None, False
def name(tok):
    m = re.match(r'\((\d+)\)(?: (.*))?', tok)
    if not m: return tok
    if m.group(2) is not None: names[m.group(1)] = m.group(2)
    return names.get(m.group(1), '')
for line in open(sys.argv[1], errors='replace'):
    line = line.rstrip('\n')
    if line.startswith('fn='): fn = name(line[3:])
    elif line.startswith('cfn='): cfn = name(line[4:])
    elif line.startswith('calls='):
        pending = True
        if 'ThreadPool::run_loop' in cfn and 'ThreadPool::parallel_for' in (fn or ''):
            loops += int(line[6:].split()[0])
    elif line and (line[0].isdigit() or line[0] in '+-*'):
        parts = line.split()
        cost = int(parts[1]) if len(parts) > 1 else 0
        if pending:  # the inclusive cost of a call
            pending = False
            if 'ThreadPool::drain' in cfn and 'ThreadPool::drain' not in (fn or ''): drain += cost
        else:
            total += cost
print(total, drain, loops)
EOF
}

echo "| objects | frames (F, 2F) | instructions a frame, 2 threads | inside the pool's loops | pool loops a frame | 2-thread bound (Amdahl) | instructions a frame, 1 thread | state hash |"
echo "|--:|--:|--:|--:|--:|--:|--:|---|"
for c in "${cases[@]}"; do
  n="${c%%:*}" f="${c##*:}"
  for threads in 2 1; do
    for k in 1 2; do
      VOXCD_SPIN_US=0 valgrind --tool=callgrind --callgrind-out-file="$tmp/cg$threads$k.out" "$voxcd" simulate \
        --objects "$n" --threads "$threads" --frames $((k * f)) --no-progress >"$tmp/out$threads$k.txt" \
        2>"$tmp/err$k.txt" || { cat "$tmp/err$k.txt" >&2; exit 1; }
    done
  done
  read -r t1 d1 l1 <<<"$(counts "$tmp/cg21.out")"
  read -r t2 d2 l2 <<<"$(counts "$tmp/cg22.out")"
  read -r s1 _ _ <<<"$(counts "$tmp/cg11.out")"
  read -r s2 _ _ <<<"$(counts "$tmp/cg12.out")"
  hash="$(awk '/^state hash/ {print $3}' "$tmp/out22.txt")"
  [ "$hash" = "$(awk '/^state hash/ {print $3}' "$tmp/out12.txt")" ] ||
    { echo "thread_share.sh: $n objects: the state hash differs between 1 and 2 threads" >&2; exit 1; }
  /usr/bin/python3 - "$n" "$f" "$t1" "$d1" "$l1" "$t2" "$d2" "$l2" "$s1" "$s2" "$hash" <<'EOF'
import sys
n, f, t1, d1, l1, t2, d2, l2, s1, s2 = map(int, sys.argv[1:11])
i, p, loops, one = (t2 - t1) / f, (d2 - d1) / f, (l2 - l1) / f, (s2 - s1) / f
print(f"| {n} | {f}, {2 * f} | {i:,.0f} | {p:,.0f} ({100 * p / i:.1f}%) | {loops:.1f} | {i / (i - p / 2):.2f}x | {one:,.0f} | {sys.argv[11]} |")
EOF
done
echo
echo "_Made by \`bash bench/thread_share.sh $voxcd ${cases[*]}\` on $(date +%F); $(valgrind --version)._"
