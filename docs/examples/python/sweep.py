#!/usr/bin/env python3
"""A sweep with the voxcd Python module (docs/python.md): one pair of objects loaded once, many poses in one batch.

Slides a cube, turned 45 degrees about z, along x through a torus lying in the xy plane, and prints at each step how
many shell points are inside the other object and the deepest penetration.

    PYTHONPATH=build/python python3 docs/examples/python/sweep.py
"""
import numpy as np

import voxcd

pair = voxcd.Pair("torus", "cube", resolution=48)  # voxelised at the larger one's longest side / 48, shared
xs = np.linspace(-3.0, 3.0, 25)
# B's pose in A's frame, one row per step: translation, then rotation in degrees about x, y and z.
poses = np.column_stack([xs, np.zeros((len(xs), 4)), np.full(len(xs), 45.0)])
results = pair.query(poses)  # both directions, the default

print(f"voxel {pair.voxel:.4f}, device {pair.device}")
for x, r in zip(xs, results):
    depth = r["depths"].max() if r["hits"] else 0.0
    print(f"x = {x:+.2f}: {r['hits']:5d} hits, deepest {depth:.3f}  " + "#" * (r["hits"] // 200))
# The torus reaches 1.35 from its centre and the turned cube sqrt(2): apart beyond 2.77, touching well within.
assert results[0]["hits"] == results[-1]["hits"] == 0
assert all(r["hits"] > 0 for x, r in zip(xs, results) if abs(x) < 2.5)
