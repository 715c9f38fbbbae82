"""Toggle counts per signal bit from a VCD of the rtl backend (bench/energy.sh).

Reads a VCD on standard input (`fst2vcd TRACE.fst | python3 toggles.py ...`), written by the rtl backend's
`--trace`: every tick dumps the rising edge at an even time 2c and the falling edge at 2c + 1, so time // 2 is the
cycle. The run's window is the jobs' part of the trace: from the first cycle the job stream's valid (job_valid_i)
is high to the last cycle a completion (done_valid_o) is high, both included; the memory loads before it and the
idle cycles after it are left out. Over the window, for every bit of every signal whose name (the hierarchical name
below the device, e.g. `g_lane[0].u_lane.g_row[0].px_q`) is listed in NAMES (one a line; all signals when NAMES is
"-"), it counts the toggles and the cycles the bit is high (sampled on the rising edges). The first pass finds the
window (fst2vcd runs twice: pass the FST, not a VCD).

Writes JSON: {"cycles": N, "first": C0, "last": C1, "signals": {name: {"width": W, "toggles": [...], "high": [...]}}}
(bit 0 first). Usage: python3 toggles.py TRACE.fst NAMES OUT.json
"""
import json
import subprocess
import sys

TOP = ("voxcd", "voxcd_device")  # the scopes above the device's own names (the Verilated top, then the device)


def vcd_lines(fst):
    proc = subprocess.Popen(["fst2vcd", fst], stdout=subprocess.PIPE, text=True, bufsize=1 << 20)
    yield from proc.stdout
    if proc.wait() != 0:
        sys.exit(f"toggles.py: fst2vcd {fst} failed")


def header(lines):
    """{id: [(name, width)]} and the iterator positioned after $enddefinitions."""
    scopes, ids = [], {}
    for line in lines:
        t = line.split()
        if not t:
            continue
        if t[0] == "$scope":
            scopes.append(t[2])
        elif t[0] == "$upscope":
            scopes.pop()
        elif t[0] == "$var":
            width, ident, name = int(t[2]), t[3], t[4]
            path = scopes[:]
            path = path[len(TOP):] if tuple(path[:len(TOP)]) == TOP else (path[1:] if path[:1] == ["voxcd"] else path)
            full = ".".join(path + [name])
            ids.setdefault(ident, []).append((full, width))
        elif t[0] == "$enddefinitions":
            return ids
    sys.exit("toggles.py: no $enddefinitions in the VCD")


def changes(lines):
    """(time, id, value) of every value change after the header."""
    time = 0
    for line in lines:
        c = line[0] if line else ""
        if c == "#":
            time = int(line[1:])
        elif c == "b":
            v, ident = line[1:].split()
            yield time, ident, int(v.replace("x", "0").replace("z", "0"), 2)
        elif c in "01xz":
            yield time, line[1:].strip(), 1 if c == "1" else 0
        elif c == "r" or c == "$" or c == "\n":
            continue


def window(fst):
    lines = vcd_lines(fst)
    ids = header(lines)
    want = {}
    for ident, names in ids.items():
        for n, _ in names:
            if n in ("job_valid_i", "done_valid_o"):
                want[ident] = n
    if len(set(want.values())) != 2:
        sys.exit("toggles.py: the VCD lacks job_valid_i or done_valid_o at the device's top")
    first = last = None
    for time, ident, v in changes(lines):
        n = want.get(ident)
        if n is None or not v:
            continue
        c = time // 2
        if n == "job_valid_i" and first is None:
            first = c
        if n == "done_valid_o":
            last = c
    # done_valid_o may stay high over several cycles after its last change: the caller checks the completions count.
    return first, last


def main(fst, names_path, out):
    first, last = window(fst)
    if first is None or last is None:
        sys.exit("toggles.py: no job or no completion in the trace")
    wanted = None
    if names_path != "-":
        with open(names_path) as f:
            wanted = {line.strip() for line in f if line.strip()}
    lines = vcd_lines(fst)
    ids = header(lines)
    track = {}  # id -> [value, last cycle, toggles list, high list, names]
    for ident, names in ids.items():
        keep = [(n, w) for n, w in names if wanted is None or n in wanted]
        if keep:
            w = keep[0][1]
            track[ident] = [0, first, [0] * w, [0] * w, [n for n, _ in keep]]
    end = last + 1
    for time, ident, v in changes(lines):
        s = track.get(ident)
        if s is None:
            continue
        c = time // 2
        if c < first:
            s[0] = v
            continue
        if c >= end:
            continue
        old = s[0]
        if old == v:
            continue
        high = s[3]
        span = c - s[1]
        b = old
        while b:
            low = b & -b
            high[low.bit_length() - 1] += span
            b ^= low
        tog = s[2]
        x = old ^ v
        while x:
            low = x & -x
            tog[low.bit_length() - 1] += 1
            x ^= low
        s[0], s[1] = v, c
    signals = {}
    for s in track.values():
        span = end - s[1]
        b = s[0]
        while b:
            low = b & -b
            s[3][low.bit_length() - 1] += span
            b ^= low
        for n in s[4]:
            signals[n] = {"width": len(s[2]), "toggles": s[2], "high": s[3]}
    with open(out, "w") as f:
        json.dump({"cycles": end - first, "first": first, "last": last, "signals": signals}, f)


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    main(*sys.argv[1:])
