#!/usr/bin/env python3
"""Contacts of two objects at a pose with the voxcd Python module (docs/python.md).

Voxelises a torus and a cube, places the cube on the torus's ring, tilted, and prints the contacts the device
reports: where, the surface normal there, the voxel and its state, and the penetration depth.

    PYTHONPATH=build/python python3 docs/examples/python/pairs.py
"""
import numpy as np

import voxcd

torus = voxcd.voxelize("torus", voxel=0.05)
cube = voxcd.voxelize("cube", voxel=0.05)
print(f"voxcd {voxcd.__version__}, backends {', '.join(voxcd.backends())}")
for name, obj in (("torus", torus), ("cube", cube)):
    counts = obj.counts
    print(f"{name}: {obj.dims[0]}x{obj.dims[1]}x{obj.dims[2]} voxels of {obj.voxel:g} "
          f"({counts['surface']} surface, {counts['interior']} interior), {obj.shell_count} shell points")

# The cube (B) in the torus's frame (A): moved 2 units along x, turned 30 degrees about z; both directions are
# tested (the default; both_directions=False tests the cube's shell against the torus only).
pair = voxcd.Pair(torus, cube, backend="cpu")
result = pair.query([2.0, 0.0, 0.0, 0, 0, 30])
print(f"{result['hits']} hits, {result['lookups']} lookups, {result['device_cycles']} device cycles")

deepest = np.argsort(result["depths"])[::-1][:5]
for k in deepest:
    shell = "torus in cube" if result["a_in_b"][k] else "cube in torus"
    x, y, z = result["positions"][k]
    nx, ny, nz = result["normals"][k]
    state = {voxcd.SURFACE: "surface", voxcd.INTERIOR: "interior"}[int(result["states"][k])]
    print(f"  {shell}: point {result['points'][k]} at ({x:.3f}, {y:.3f}, {z:.3f}), normal ({nx:.2f}, {ny:.2f}, "
          f"{nz:.2f}), {state} voxel {tuple(int(v) for v in result['voxels'][k])}, depth {result['depths'][k]:.3f}")
assert result["hits"] > 0, "the cube sits on the ring: it must touch"
