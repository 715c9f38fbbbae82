#!/usr/bin/env python3
"""Two meshes, their contacts at a pose, with the voxcd Python module (docs/api.md).

A mesh is anything with .vertices and .faces (a trimesh mesh), (vertices, faces) arrays, a mesh file or a shape.

    PYTHONPATH=build/python python3 docs/examples/python/collide.py
"""
from types import SimpleNamespace

import numpy as np

import voxcd

# A tetrahedron as a trimesh-style object (trimesh.load("part.stl") gives one the same way).
mesh = SimpleNamespace(vertices=np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float),
                       faces=np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]))

# The query itself.
a = voxcd.voxelize("torus", resolution=32)
b = voxcd.voxelize(mesh, resolution=32)
c = voxcd.collide(a, None, b, [0.9, 0, 0, 0, 0, 30])
print(c["hits"], "hits; deepest contact at", c["positions"][np.argmax(c["depths"])])
assert c["hits"] > 0
