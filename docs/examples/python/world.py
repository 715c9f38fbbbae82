#!/usr/bin/env python3
"""A world stepped by its caller (docs/python.md, "World"): docs/examples/cpp/world.cpp in Python, the same names and
defaults. A row of objects made from arrays and a shape, 100 frames with the walls and the response; then a world
that only detects, stepped in seconds, its contact events printed.

    PYTHONPATH=build/python python3 docs/examples/python/world.py
"""
import sys

import numpy as np

import voxcd

# A tetrahedron given as arrays (any mesh a program holds), and a built-in torus.
vertices = np.array([[0, 0, 0], [4, 0, 0], [0, 4, 0], [0, 0, 4]], dtype=np.float64)
triangles = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]], dtype=np.uint32)
tetra = voxcd.Object.from_arrays(vertices, triangles)
torus = voxcd.Object.load("torus", voxel=0.25)

world = voxcd.World()   # a cube of side 100 with walls, the response, the grid broadphase, the cpu backend
for i in range(8):
    world.add(tetra if i % 2 else torus, [10.0 + 9 * i, 50, 50],
              velocity=[-0.5 if i % 2 else 0.5, 0, 0])   # world units per frame: step() steps a frame
touching = sum(world.step()["touching"] for _ in range(100))
print(f"{len(world)} bodies, {touching} touching pairs over 100 frames, state hash {world.state_hash}")

# Detection only: no walls, no response; velocities per second, stepped at 60 Hz; a static torus in the middle.
sensor = voxcd.World(walls=False, response=False)
sensor.add(torus, [50, 50, 50], kind="static", user_data=1)
probe = sensor.add(tetra, [40, 49, 49], velocity=[6, 0, 0], user_data=2)   # 6 units a second through the ring
begun = ended = 0
for f in range(240):
    sensor.step(1 / 60)
    for e in sensor.begin_events:
        print(f"{f / 60:.2f} s: bodies {e['user_data_a']} and {e['user_data_b']} began touching")
        begun += 1
    for e in sensor.end_events:
        print(f"{f / 60:.2f} s: bodies {e['user_data_a']} and {e['user_data_b']} stopped touching")
        ended += 1
    for c in sensor.touching:
        if c["contacts"] > 0 and f % 30 == 0:
            print(f"  {c['contacts']} contacts, deepest {c['deepest']['depth']:.3f} at x = "
                  f"{c['deepest']['position'][0]:.2f}")
print(f"the probe is at x = {sensor.pose(probe)[0, 3]:.2f}")
sys.exit(0 if touching > 0 and begun > 0 and ended > 0 else 1)
