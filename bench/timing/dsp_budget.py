"""Keeps a design's DSP use within a part's DSP blocks (the iCE40 UP5K rows of bench/timing.sh).

`synth_ice40 -dsp` maps every multiplier that suits an SB_MAC16 (both inputs at least 2 bits, the product at least 11
bits; 16 x 16 per block) into DSP blocks, whether or not the part has that many: a lane of the device has nine
matrix products and two index products, the UP5K 8 blocks. This reads a yosys JSON of the flattened design before
the DSP mapping (`synth_ice40 -dsp -run begin:coarse; wreduce t:$mul`), keeps the widest multipliers for the DSP
blocks until BUDGET are used, and marks the others `$__soft_mul`, which `synth_ice40 -dsp` leaves to logic cells
(it turns them back into $mul after its DSP mapping). Ties go by cell name, so the choice is the same every run.

The output holds the top module only: read the cell library first (`read_verilog -D ICE40_HX -lib -specify
+/ice40/cells_sim.v`, as synth_ice40 does), then the output with read_json, then `synth_ice40 -dsp -run coarse:`.

Usage: python3 dsp_budget.py IN.json OUT.json TOP BUDGET. Prints "<multipliers in DSPs> <DSP blocks> <in logic>".
"""
import json
import sys


def width(cell, port):
    v = cell["parameters"][port + "_WIDTH"]
    return int(v, 2) if isinstance(v, str) else int(v)


def blocks(cell):
    """SB_MAC16s a $mul takes under synth_ice40's rule (mul2dsp, 16 x 16 blocks, product at least 11 bits)."""
    a, b, y = width(cell, "A"), width(cell, "B"), width(cell, "Y")
    if a < 2 or b < 2 or y < 11:
        return 0
    return -(-a // 16) * -(-b // 16)


def main(src, dst, top, budget):
    budget = int(budget)
    with open(src) as f:
        design = json.load(f)
    cells = design["modules"][top]["cells"]
    muls = [(name, c) for name, c in cells.items() if c["type"] == "$mul" and blocks(c) > 0]
    muls.sort(key=lambda nc: (-width(nc[1], "A") * width(nc[1], "B"), nc[0]))
    used = kept = soft = 0
    for name, cell in muls:
        if used + blocks(cell) <= budget:
            used += blocks(cell)
            kept += 1
        else:
            cell["type"] = "$__soft_mul"
            soft += 1
    # Only the (flattened) design: the cell library's modules are read again from yosys's own files.
    design["modules"] = {top: design["modules"][top]}
    with open(dst, "w") as f:
        json.dump(design, f)
    print(f"{kept} {used} {soft}")


if __name__ == "__main__":
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    main(*sys.argv[1:])
