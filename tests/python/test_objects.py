"""voxcd.voxelize and voxcd.Object against `voxcd voxelize`: the same object file, the same arrays, the same report."""
import filecmp
import math

import numpy as np
import pytest

import voxcd


def cli_object(cli, tmp_path, source, *opts):
    path = tmp_path / "cli.vxo"
    cli("voxelize", source, *opts, "-o", path, "--json")
    return voxcd.read_object(path), path


@pytest.mark.parametrize("source, opts, kw", [
    ("torus", ["--resolution", "20"], {"resolution": 20}),
    ("stellated", ["--voxel", "0.15", "--shell-ratio", "2"], {"voxel": 0.15, "shell_ratio": 2.0}),
    ("tetra.obj", ["--resolution", "16"], {"resolution": 16}),
])
def test_voxelize_equals_the_tools_object_file(cli, tmp_path, scenes, source, opts, kw):
    if source.endswith(".obj"):
        source = str(scenes / source)
    ref, ref_path = cli_object(cli, tmp_path, source, *opts)
    obj = voxcd.voxelize(source, **kw)
    assert obj.source == ref.source == (source if "." in source else "shape:" + source)
    assert obj.source_hash == ref.source_hash
    assert obj.dims == ref.dims and obj.voxel == ref.voxel
    np.testing.assert_array_equal(obj.origin, ref.origin)
    np.testing.assert_array_equal(obj.states, ref.states)
    np.testing.assert_array_equal(obj.shell_points, ref.shell_points)
    np.testing.assert_array_equal(obj.shell_normals, ref.shell_normals)
    np.testing.assert_array_equal(obj.shell_cells, ref.shell_cells)
    assert obj.repair == ref.repair
    assert obj.counts == ref.counts
    # Saved, it is the tool's file byte for byte.
    obj.save(tmp_path / "py.vxo")
    assert filecmp.cmp(tmp_path / "py.vxo", ref_path, shallow=False)


def test_arrays_follow_the_voxmap_and_the_report_is_the_tools(cli_json, tmp_path, scenes):
    mesh = str(scenes / "tetra.obj")
    info = cli_json("voxelize", mesh, "--resolution", "12", "-o", tmp_path / "t.vxo")
    obj = voxcd.voxelize(mesh, resolution=12)
    assert list(obj.dims) == info["dims"]
    assert obj.states.shape == obj.dims and obj.states.dtype == np.uint8
    counts = np.bincount(obj.states.ravel(), minlength=4)
    assert [int(c) for c in counts[:3]] == [info["empty"], info["surface"], info["interior"]]
    assert counts[3] == 0
    assert obj.counts == {"empty": info["empty"], "surface": info["surface"], "interior": info["interior"]}
    assert obj.shell_points.shape == (info["shell_points"], 3)
    assert obj.shell_spacing == pytest.approx(info["shell_spacing"], rel=1e-15)
    assert list(obj.shell_dims) == info["shell_dims"]
    assert obj.repair == info["repair"]
    # Every shell point is the centre of its cell of the shell grid, and its normal is a unit vector.
    np.testing.assert_allclose(obj.shell_points, obj.shell_origin + (obj.shell_cells + 0.5) * obj.shell_spacing,
                               rtol=0, atol=1e-12)
    np.testing.assert_allclose(np.linalg.norm(obj.shell_normals, axis=1), 1.0, atol=1e-12)
    # states[x, y, z] is voxel (x, y, z): the voxel holding the tetrahedron's centre (the origin) is inside.
    centre = np.floor((np.zeros(3) - obj.origin) / obj.voxel).astype(int)
    assert obj.states[tuple(centre)] == voxcd.INTERIOR
    assert obj.states[0, 0, 0] == voxcd.EMPTY


def test_a_repaired_mesh_reports_what_was_repaired(tmp_path):
    # Two triangles of a tetrahedron missing: an open surface, surface only.
    (tmp_path / "open.obj").write_text("v 1 1 1\nv -1 -1 1\nv -1 1 -1\nv 1 -1 -1\nf 1 2 4\nf 1 4 3\n")
    obj = voxcd.voxelize(tmp_path / "open.obj", resolution=8)
    assert obj.repair["closed"] is False
    assert obj.repair["open_edges"] == 4
    assert obj.counts["interior"] == 0 and obj.counts["surface"] > 0
    with pytest.raises(ValueError, match=r"open\.obj"):
        voxcd.voxelize(tmp_path / "open.obj", resolution=8, strict=True)


def test_save_reports_a_file_that_cannot_be_written(tmp_path):
    obj = voxcd.voxelize("cube", resolution=4)
    with pytest.raises(OSError, match=r"no/such/dir/x\.vxo"):
        obj.save(tmp_path / "no" / "such" / "dir" / "x.vxo")
    assert "cube" in repr(obj) and math.isclose(obj.voxel, obj.voxel)
