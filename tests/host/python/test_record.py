"""Recordings from Python: simulate(record=...) writes what `voxcd simulate --record` writes, read_recording reads it
as numpy arrays (docs/view.md), and refuses what is not a recording of this version."""
import json

import numpy as np
import pytest

import voxcd


def test_the_module_records_as_the_tool_does(tmp_path, cli):
    mine, tools = tmp_path / "module.vxr", tmp_path / "tool.vxr"
    summary = voxcd.simulate(objects=32, frames=6, density=0.08, seed=4, record=mine)
    cli("simulate", "--objects", 32, "--frames", 6, "--density", 0.08, "--seed", 4, "--record", tools, "--no-progress")
    a, b = voxcd.read_recording(mine), voxcd.read_recording(tools)
    assert a["version"] == 1 and not a["truncated"] and a["note"] == ""
    assert a["run"]["objects"] == 32 and a["run"]["backend"] == "cpu"
    assert len(a["frames"]) == 6 and a["body_types"].shape == (32,)
    for fa, fb in zip(a["frames"], b["frames"]):
        assert np.array_equal(fa["positions"], fb["positions"])
        assert np.array_equal(fa["rotations"], fb["rotations"])
        assert np.array_equal(fa["pairs"], fb["pairs"])
        assert np.array_equal(fa["contacts"]["position"], fb["contacts"]["position"])
    assert sum(f["stats"]["contacts"] for f in a["frames"]) == summary["contacts"]
    assert sum(len(f["contacts"]["depth"]) for f in a["frames"]) == summary["contacts"]
    t = a["types"][0]
    assert t["from_mesh"] and t["vertices"].shape[1] == 3 and t["triangles"].max() < len(t["vertices"])
    # The rotations are unit quaternions (w, x, y, z), rounded to float.
    q = a["frames"][0]["rotations"]
    assert np.allclose(np.linalg.norm(q, axis=1), 1, atol=1e-6)


def test_a_truncated_recording_reads_its_whole_frames(tmp_path):
    path = tmp_path / "run.vxr"
    voxcd.simulate(objects=16, frames=4, density=0.05, record=str(path))
    data = path.read_bytes()
    cut = tmp_path / "cut.vxr"
    cut.write_bytes(data[:-10])
    r = voxcd.read_recording(cut)
    assert r["truncated"] and len(r["frames"]) == 3
    assert f"truncated at byte {len(data) - 10}" in r["note"] and "read 3 whole frames" in r["note"]


def test_other_versions_and_files_are_refused(tmp_path):
    path = tmp_path / "run.vxr"
    voxcd.simulate(objects=16, frames=2, density=0.05, record=path)
    data = bytearray(path.read_bytes())
    data[8] = 7
    path.write_bytes(bytes(data))
    with pytest.raises(ValueError, match="a recording of format version 7; this voxcd reads version 1"):
        voxcd.read_recording(path)
    other = tmp_path / "scene.json"
    other.write_text(json.dumps({"frames": 1}))
    with pytest.raises(ValueError, match="not a voxcd recording"):
        voxcd.read_recording(other)
    with pytest.raises(FileNotFoundError):
        voxcd.read_recording(tmp_path / "missing.vxr")
