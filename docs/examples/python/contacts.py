#!/usr/bin/env python3
"""Two meshes, their contacts at a pose (docs/python.md): docs/examples/cpp/contacts.cpp in Python, the same names and
defaults. contacts.py [A B] with mesh files or built-in shapes.

    PYTHONPATH=build/python python3 docs/examples/python/contacts.py
"""
import sys

import voxcd

a = voxcd.Object.load(sys.argv[1] if len(sys.argv) > 1 else "torus")   # 32 voxels along its longest side
b = voxcd.Object.load(sys.argv[2] if len(sys.argv) > 2 else "cube")
pose_b = [1.2, 0, 0]                                                     # a translation; None is the identity
c = voxcd.collide(a, None, b, pose_b)                                    # every contact, both directions
for position, depth in zip(c["positions"], c["depths"]):
    print(f"({position[0]:.3f}, {position[1]:.3f}, {position[2]:.3f}) depth {depth:.3f}")
sys.exit(0 if c["hits"] > 0 else 1)   # the cube reaches into the torus's ring
