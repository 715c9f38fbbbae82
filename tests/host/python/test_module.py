"""The module itself: version, backends, lists, and how errors reach Python (type and the library's message)."""
import math

import pytest

import voxcd


def test_version_is_the_tools(cli):
    assert voxcd.__version__ == cli("--version").splitlines()[0].split()[-1]
    assert voxcd.__version__.count(".") >= 1


def test_backends_shapes_and_broadphases(cli):
    assert {"ref", "cpu"} <= set(voxcd.backends())
    status = voxcd.backend_status()
    assert [b["name"] for b in status] == ["ref", "cpu", "rtl", "sysc-rtl", "sysc-tlm"]
    assert voxcd.backends() == [b["name"] for b in status if b["ready"]]
    assert all(b["why_not"] == "" for b in status if b["ready"])
    assert all(b["why_not"] for b in status if not b["ready"])
    # The tool says the same: `voxcd --version` lists every backend after "backends:".
    listed = dict(line.split(None, 1) for line in cli("--version").splitlines()[2:])
    assert listed == {b["name"]: "ready" if b["ready"] else "not ready: " + b["why_not"] for b in status}
    assert voxcd.shapes()[0] == "polytope36" and "torus" in voxcd.shapes()
    assert "grid" in voxcd.broadphases()
    assert (voxcd.EMPTY, voxcd.SURFACE, voxcd.INTERIOR) == (0, 1, 2)


def test_missing_files_raise_file_not_found_with_the_librarys_message(tmp_path):
    with pytest.raises(FileNotFoundError, match=r"nothing\.vxo: cannot open"):
        voxcd.read_object(tmp_path / "nothing.vxo")
    with pytest.raises(FileNotFoundError, match=r"nothing\.json: cannot open the scene file"):
        voxcd.simulate(tmp_path / "nothing.json")
    with pytest.raises(FileNotFoundError, match=r"nothing\.json: cannot open the scene file"):
        voxcd.size(str(tmp_path / "nothing.json"))


def test_a_name_that_is_neither_file_nor_shape():
    with pytest.raises(ValueError, match=r"^no-such-shape: no such file, and not a built-in shape \(polytope36, "):
        voxcd.voxelize("no-such-shape", voxel=0.1)


def test_a_file_that_is_not_an_object_file(tmp_path):
    bad = tmp_path / "bad.vxo"
    bad.write_bytes(b"not an object file at all")
    with pytest.raises(ValueError, match=r"bad\.vxo"):
        voxcd.read_object(bad)


def test_nan_and_infinite_poses():
    # The pose parser refuses them, naming the number (and, in a batch, the pose).
    with pytest.raises(ValueError, match=r"^pose: number 1 of 3 \(nan\) is not finite$"):
        voxcd.pair("cube", "cube", [math.nan, 0, 0], voxel=0.25)
    with pytest.raises(ValueError, match=r"^pose: number 2 of 6 \(inf\) is not finite$"):
        voxcd.pair("cube", "cube", [0, math.inf, 0, 0, 0, 0], voxel=0.25)
    with pytest.raises(ValueError, match=r"^pose\[1\]: number 3 of 7 \(nan\) is not finite$"):
        voxcd.pair("cube", "cube", [[0, 0, 0, 1, 0, 0, 0], [0, 0, math.nan, 1, 0, 0, 0]], voxel=0.25)
    with pytest.raises(ValueError, match=r"^pose: give 3 \(tx, ty, tz\), 6 .* got shape \(2\)$"):
        voxcd.pair("cube", "cube", [1, 2], voxel=0.25)
    with pytest.raises(ValueError, match=r"T0 = -3999999999\.[0-9]+ does not fit signed 48-bit"):
        voxcd.pair("cube", "cube", [1e9, 0, 0], voxel=0.25)


def test_bad_resolutions_and_voxels():
    with pytest.raises(ValueError, match=r"cube: a resolution of 2 voxels is too coarse; at least 4"):
        voxcd.voxelize("cube", resolution=2)
    with pytest.raises(ValueError, match=r"resolution: 0 is not a positive count of voxels"):
        voxcd.voxelize("cube", resolution=0)
    with pytest.raises(ValueError, match=r"give voxel .* or resolution .*, not both"):
        voxcd.voxelize("cube", voxel=0.1, resolution=8)
    with pytest.raises(ValueError, match=r"give voxel .* or resolution .*, one of them"):
        voxcd.voxelize("cube")
    with pytest.raises(ValueError, match=r"the voxel size must be a positive finite number"):
        voxcd.voxelize("cube", voxel=-1.0)
    with pytest.raises(ValueError, match=r"a resolution of 3 voxels is too coarse"):
        voxcd.pair("cube", "torus", resolution=3)
    with pytest.raises(ValueError, match=r"^resolution: 3 is outside \[4, 1020\]$"):
        voxcd.simulate(resolution=3, frames=1)


def test_simulate_refuses_what_the_tool_refuses():
    with pytest.raises(ValueError, match=r"^mode: 'SOME' is not ALL, FIRST or COUNT$"):
        voxcd.simulate(mode="SOME", frames=1)
    with pytest.raises(ValueError, match=r"^voxel, resolution: give the voxel size in world units"):
        voxcd.simulate(voxel=1, resolution=10, frames=1)
    with pytest.raises(ValueError, match=r"^voxel: must be a positive number of world units$"):
        voxcd.simulate(voxel=0.0, frames=1)
    with pytest.raises(ValueError, match=r"^config: unknown config parameter 'FOO'$"):
        voxcd.simulate(config="FOO 1", frames=1)
    with pytest.raises(ValueError, match=r"could not place object 27 of 64 without overlapping bounding spheres"):
        voxcd.simulate(density=0.3, frames=1)
    with pytest.raises(ValueError, match=r"^objects: -1 is not an integer in \[0, 2\^64\)$"):
        voxcd.simulate(objects=-1, frames=1)
    with pytest.raises(TypeError, match=r"frames must be an int, not float"):
        voxcd.simulate(frames=2.5)


def test_a_backend_that_cannot_run_is_a_runtime_error():
    with pytest.raises(RuntimeError, match=r"LANES = 100 is outside 1\.\.64"):
        voxcd.pair("cube", "cube", voxel=0.25, lanes=100)
    with pytest.raises(RuntimeError, match=r"no-such-backend"):
        voxcd.pair("cube", "cube", voxel=0.25, backend="no-such-backend")


def test_paths_must_be_strings_or_path_likes():
    with pytest.raises(TypeError, match=r"path must be a str or an os.PathLike naming a file, not int"):
        voxcd.read_object(3)
