#!/usr/bin/env python3
"""Every error the API documents, caught by its class (docs/python.md, "Errors"); each is also a voxcd.Error.

    PYTHONPATH=build/python python3 docs/examples/python/errors.py
"""
import json
import math
import os
import tempfile

import voxcd


def expect(cls, f, *args, **kwargs):
    try:
        f(*args, **kwargs)
    except cls as e:
        assert isinstance(e, voxcd.Error) and isinstance(e, RuntimeError), type(e)
        print(f"{cls.__name__:16} {e} (where: {e.where})")
        return
    raise AssertionError(f"{cls.__name__} was not raised")


torus = voxcd.Object.load("torus")
sphere = voxcd.Object.load("sphere", voxel=torus.voxel / 4)   # 4 times finer: beyond the rtl models' widths
with tempfile.TemporaryDirectory() as d:
    bad_object = os.path.join(d, "bad.vxo")
    with open(bad_object, "wb") as f:
        f.write(b"VOXCDOBJ but nothing else")
    bad_scene = os.path.join(d, "bad.json")
    with open(bad_scene, "w") as f:
        json.dump({"types": [{"shape": "cube", "voxel": -1}]}, f)
    expect(voxcd.MeshError, voxcd.Object.load, "no-such-file-or-shape")
    expect(voxcd.ObjectFileError, voxcd.Object.load, bad_object)
    expect(voxcd.RangeError, voxcd.collide, torus, None, torus, [1e9, 0, 0])   # beyond the fixed point
    expect(voxcd.OptionError, voxcd.collide, torus, None, torus, [math.nan, 0, 0])   # not a pose
    expect(voxcd.CapacityError, voxcd.collide, torus, None, sphere, None, backend="rtl")
    expect(voxcd.DeviceError, voxcd.collide, torus, None, torus, None, backend="no-such-backend")
    expect(voxcd.SceneFileError, voxcd.World.scene, bad_scene)
    expect(voxcd.OptionError, voxcd.World, side=-1.0)
    expect(voxcd.SizeError, voxcd.size, {"types": [{"shape": "cube", "count": 8, "voxel": 0.1}]}, accuracy=1e-12)
    world = voxcd.World()
    body = world.add(torus)
    world.remove(body)
    expect(voxcd.BodyError, world.pose, body)                # a removed body's id
    expect(voxcd.Error, voxcd.Object.load, "no-such-file-or-shape")
