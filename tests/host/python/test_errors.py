"""The library's errors as the module's classes (docs/python.md, "Errors"): one hierarchy under voxcd.Error, a
RuntimeError, each class also a ValueError where it is bad input; each raised for its C++ type, with `where`."""
import json
import math

import pytest

import voxcd

BAD_INPUT = ["RangeError", "ConfigError", "VectorError", "MeshError", "ObjectFileError", "CapacityError",
             "SceneFileError", "OptionError", "PlacementError", "RecordError", "SizeError", "BodyError"]
OTHERS = ["JobError", "DeviceError", "TimingTableError", "EnergyTableError"]


def test_the_hierarchy():
    assert issubclass(voxcd.Error, RuntimeError) and not issubclass(voxcd.Error, ValueError)
    assert voxcd.Error.__module__ == "voxcd"
    for name in BAD_INPUT + OTHERS:
        cls = getattr(voxcd, name)
        assert cls.__name__ == name and cls.__module__ == "voxcd"
        assert issubclass(cls, voxcd.Error) and issubclass(cls, RuntimeError), name
        assert issubclass(cls, ValueError) == (name in BAD_INPUT), name


def raised(cls, f, *args, **kwargs):
    with pytest.raises(cls) as e:
        f(*args, **kwargs)
    assert type(e.value) is cls, f"{type(e.value).__name__} raised, {cls.__name__} expected"
    return e.value


def test_each_error_is_raised_as_its_class(tmp_path):
    torus = voxcd.voxelize("torus", resolution=32)
    e = raised(voxcd.MeshError, voxcd.voxelize, "no-such-shape", resolution=32)
    assert e.where == "no-such-shape" and str(e).startswith("no-such-shape: no such file, and not a built-in shape")
    bad = tmp_path / "bad.vxo"
    bad.write_bytes(b"VOXCDOBJ and nothing else")
    assert raised(voxcd.ObjectFileError, voxcd.read_object, bad).where == str(bad)
    e = raised(voxcd.RangeError, voxcd.collide, torus, None, torus, [1e9, 0, 0])
    assert e.where == "pair 0 (shape:torus, shape:torus)" and "does not fit signed 48-bit" in str(e)
    e = raised(voxcd.OptionError, voxcd.collide, torus, None, torus, [math.nan, 0, 0])
    assert e.where == "pose_b" and str(e) == "pose_b: number 1 of 3 (nan) is not finite"
    sphere = voxcd.voxelize("sphere", voxel=torus.voxel * 4)  # coarse: quick to make, even under the sanitizers
    e = raised(voxcd.CapacityError, voxcd.collide, torus, None, sphere, None, backend="rtl")
    assert "voxels differ too much for the rtl backend" in str(e)
    raised(voxcd.DeviceError, voxcd.collide, torus, None, torus, None, backend="no-such-backend")
    scene = tmp_path / "bad.json"
    scene.write_text(json.dumps({"types": [{"shape": "cube", "voxel": -1}]}))
    e = raised(voxcd.SceneFileError, voxcd.World.scene, scene)
    assert e.where == f"{scene}: types[0].voxel" and str(e) == f"{scene}: types[0].voxel: -1 is outside (0, 1e+12]"
    e = raised(voxcd.OptionError, voxcd.World, side=-1.0)
    assert (str(e), e.where, e.options) == ("side: -1 is outside (0, 1e+12]", "side", ["side"])
    world = voxcd.World()
    body = world.add(torus)
    e = raised(voxcd.BodyError, world.set_velocity, body, [math.inf, 0, 0])
    assert (str(e), e.where, e.body, e.field) == ("body 0: velocity: (inf, 0, 0) is not finite", "body 0", body,
                                                  "velocity")
    e = raised(voxcd.OptionError, voxcd.simulate, frames=1, mode="SOME")
    assert (str(e), e.where, e.options) == ("mode: 'SOME' is not ALL, FIRST or COUNT", "mode", ["mode"])
    e = raised(voxcd.SizeError, voxcd.size, {"types": [{"shape": "cube", "count": 8, "voxel": 0.1}]}, accuracy=1e-12)
    assert e.constraint == "accuracy" and e.factor > 1 and str(e).startswith("scene: cannot be met: accuracy: ")
    recording = tmp_path / "x.vxr"
    recording.write_bytes(b"not a recording at all, not at all")
    raised(voxcd.RecordError, voxcd.read_recording, recording)
    e = raised(voxcd.ConfigError, voxcd.generate_vectors, tmp_path / "x.vec", lanes=100)
    assert "LANES = 100 is outside 1..64" in str(e)


def test_keyword_arguments_the_module_refuses_are_option_errors():
    e = raised(voxcd.OptionError, voxcd.voxelize, "torus", resolution=0)
    assert e.where == "resolution" and isinstance(e, ValueError)
    e = raised(voxcd.OptionError, voxcd.voxelize, "torus", voxel=0.1, resolution=8)
    assert e.where == "" and str(e).startswith("give voxel")


def test_old_except_clauses_still_catch():
    with pytest.raises(ValueError):
        voxcd.voxelize("no-such-shape", resolution=32)
    with pytest.raises(RuntimeError):
        voxcd.voxelize("no-such-shape", resolution=32)
    with pytest.raises(RuntimeError, match="no-such-backend"):
        voxcd.collide("cube", None, "cube", None, backend="no-such-backend")
