"""Buffer trees on the high-fanout nets of a mapped netlist (the ASIC flow of bench/timing.sh).

ABC sizes and buffers the logic it maps, but it sees every flip-flop output and every input port as a primary input
of its network and leaves their fanout alone: a pipeline enable or a register read by every lane then drives
hundreds of pins from one X1 flip-flop, which static timing turns into paths 10 to 1000 times too long. A physical
flow builds buffer trees there; this does the same before timing: every net (but the clock, which is ideal in the
analysis, as before clock tree synthesis) with more than LIMIT loads gets a balanced tree of BUF cells, each driving
at most LIMIT loads, the root driving at most LIMIT buffers.

Reads a yosys JSON whose cells carry port directions (the liberty cells read with `read_liberty -lib`), writes it
back with the buffers. Usage: python3 fanout_buffers.py IN.json OUT.json TOP BUF IN_PIN OUT_PIN LIMIT CLOCK_PORT
Prints one line: the buffers added and the largest fanout before.
"""
import json
import sys


def loads_of(module):
    """{net bit: [(cell, port, index)]} over every cell input pin."""
    loads = {}
    for name, cell in module["cells"].items():
        directions = cell.get("port_directions")
        if directions is None:
            sys.exit(f"fanout_buffers.py: cell {name} of type {cell['type']} has no port directions "
                     "(read the liberty with read_liberty -lib before write_json)")
        for port, bits in cell["connections"].items():
            if directions.get(port) != "input":
                continue
            for i, bit in enumerate(bits):
                if isinstance(bit, int):
                    loads.setdefault(bit, []).append((name, port, i))
    return loads


def next_bit(module):
    bits = [b for c in module["cells"].values() for v in c["connections"].values() for b in v if isinstance(b, int)]
    bits += [b for p in module["ports"].values() for b in p["bits"] if isinstance(b, int)]
    return 1 + max(bits)


def build_tree(module, bit, loads, buf, pin_in, pin_out, limit, state):
    """Puts `loads` of `bit` behind a balanced tree of `buf` cells; returns how many it added."""
    cells = module["cells"]
    level = loads
    added = 0
    while len(level) > limit:
        parents = []
        for k in range(0, len(level), limit):
            out, placeholder = state["bit"], state["bit"] + 1
            state["bit"] += 2
            name = f"fanout_buf_{state['n']}"
            state["n"] += 1
            added += 1
            cells[name] = {"hide_name": 0, "type": buf, "parameters": {}, "attributes": {},
                           "port_directions": {pin_in: "input", pin_out: "output"},
                           "connections": {pin_in: [placeholder], pin_out: [out]}}
            for cell, port, i in level[k:k + limit]:
                cells[cell]["connections"][port][i] = out
            parents.append((name, pin_in, 0))
        level = parents
    for cell, port, i in level:
        cells[cell]["connections"][port][i] = bit
    return added


def main(src, dst, top, buf, pin_in, pin_out, limit, clock):
    limit = int(limit)
    with open(src) as f:
        design = json.load(f)
    module = design["modules"][top]
    skip = {b for b in module["ports"][clock]["bits"] if isinstance(b, int)}
    loads = loads_of(module)
    state = {"bit": next_bit(module), "n": 0}
    worst = max((len(v) for b, v in loads.items() if b not in skip), default=0)
    added = 0
    for bit, pins in sorted(loads.items()):
        if bit not in skip and len(pins) > limit:
            added += build_tree(module, bit, pins, buf, pin_in, pin_out, limit, state)
    with open(dst, "w") as f:
        json.dump(design, f)
    print(f"{added} {worst}")


if __name__ == "__main__":
    if len(sys.argv) != 9:
        sys.exit(__doc__)
    main(*sys.argv[1:])
