#!/usr/bin/env python3
"""A world that only detects (docs/python.md, "World"): no walls, no response, stepped in seconds; a static torus and
a probe passing through it, their contact events printed with the user data each body was given.

    PYTHONPATH=build/python python3 docs/examples/python/events.py
"""
import voxcd

torus = voxcd.voxelize("torus", voxel=0.25)
tetra = voxcd.voxelize(([[0, 0, 0], [4, 0, 0], [0, 4, 0], [0, 0, 4]], [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]),
                       voxel=0.25)

world = voxcd.World(walls=False, response=False)
world.add(torus, [50, 50, 50], kind="static", user_data="ring")
probe = world.add(tetra, [40, 49, 49], velocity=[6, 0, 0], user_data="probe")  # 6 units a second

for frame in range(240):
    world.step(1 / 60)
    for e in world.begin_events:
        print(f"{frame / 60:.2f} s: {e['user_data_a']} and {e['user_data_b']} began touching")
    for e in world.end_events:
        print(f"{frame / 60:.2f} s: {e['user_data_a']} and {e['user_data_b']} stopped touching")
    for t in world.touching:
        if frame % 30 == 0:
            print(f"  {t['contacts']} contacts, deepest {t['deepest']['depth']:.3f} at x = "
                  f"{t['deepest']['position'][0]:.2f}")
print(f"the probe is at x = {world.pose(probe)[0, 3]:.2f}")
