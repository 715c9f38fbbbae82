"""voxcd.voxelize and voxcd.Object against `voxcd voxelize`: the same object file, the same arrays, the same report."""
import filecmp
import json
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
    assert obj.report == ref.report
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
    assert obj.shell_points.shape == (info["shell_count"], 3)
    assert obj.shell_spacing == pytest.approx(info["shell_spacing"], rel=1e-15)
    assert list(obj.shell_dims) == info["shell_dims"]
    assert obj.report == info["repair"]
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
    assert obj.report["closed"] is False
    assert obj.report["open_edges"] == 4
    assert obj.counts["interior"] == 0 and obj.counts["surface"] > 0
    with pytest.raises(ValueError, match=r"open\.obj"):
        voxcd.voxelize(tmp_path / "open.obj", resolution=8, strict=True)


def test_save_reports_a_file_that_cannot_be_written(tmp_path):
    obj = voxcd.voxelize("cube", resolution=4)
    with pytest.raises(OSError, match=r"no/such/dir/x\.vxo"):
        obj.save(tmp_path / "no" / "such" / "dir" / "x.vxo")
    assert "cube" in repr(obj) and math.isclose(obj.voxel, obj.voxel)


def box_distance(p):
    """Signed distance from points p (..., 3) to the cube [-1, 1]^3: negative inside."""
    q = np.abs(p) - 1.0
    outside = np.linalg.norm(np.maximum(q, 0.0), axis=-1)
    inside = np.minimum(q.max(axis=-1), 0.0)
    return outside + inside


@pytest.mark.parametrize("bits", [4, 8, 16])
def test_distance_field_of_the_cube(cli, tmp_path, bits):
    obj = voxcd.voxelize("cube", voxel=0.25, distance_bits=bits, band=2.5)
    assert obj.distance_bits == bits
    assert obj.distance_step == 2.5 / 2 ** (bits - 1)
    assert obj.shell_on_surface
    d = obj.distance
    assert d.dtype == np.int16 and d.shape == tuple(n + 1 for n in obj.dims) and d.flags["F_CONTIGUOUS"]
    # distance[X, Y, Z] is the node at origin + voxel * (X, Y, Z): against the cube's exact signed distance.
    idx = np.stack(np.meshgrid(*[np.arange(n) for n in d.shape], indexing="ij"), axis=-1)
    x = box_distance(obj.origin + obj.voxel * idx) / obj.voxel / obj.distance_step
    qmax = 2 ** (bits - 1) - 1
    want = np.clip(np.round(x), -qmax - 1, qmax)
    tie = np.abs(np.abs(x - np.trunc(x)) - 0.5) < 1e-9
    # Conservative cells (docs/objects.md): along the cube's edges, nodes outside are lowered to 0.
    lowered = (d == 0) & (want > 0)
    assert np.all((d == want) | (tie & (np.abs(d - want) == 1)) | lowered)
    assert lowered.any() and obj.report["conservative_cells"] > 0
    assert d.min() == -qmax - 1 and d.max() == qmax
    # The shell lies on the cube's surface, within the rounding of 1/256 of the spacing.
    assert np.all(np.abs(box_distance(obj.shell_points)) <= math.sqrt(3) * obj.shell_spacing / 512 + 1e-12)
    # The tool writes the same file, and describes the field.
    path = tmp_path / "cube.vxo"
    info = json.loads(cli("voxelize", "cube", "--voxel", "0.25", "--distance-bits", bits, "--band", "2.5",
                          "-o", path, "--json"))
    obj.save(tmp_path / "py.vxo")
    assert filecmp.cmp(tmp_path / "py.vxo", path, shallow=False)
    assert info["shell_on_surface"] is True
    f = info["distance"]
    assert f["bits"] == bits and f["step"] == obj.distance_step and f["band"] == 2.5
    assert f["node_dims"] == list(d.shape) and f["nodes"] == d.size
    assert f["min"] == d.min() and f["max"] == d.max() and f["memory_words"] > 0
    back = voxcd.read_object(path)
    np.testing.assert_array_equal(back.distance, d)
    np.testing.assert_array_equal(back.shell_points, obj.shell_points)


def test_objects_without_a_field(cli_json, tmp_path):
    obj = voxcd.voxelize("cube", resolution=8)
    assert obj.distance is None and obj.distance_bits == 0 and obj.distance_step == 0 and not obj.shell_on_surface
    info = cli_json("voxelize", "cube", "--resolution", "8", "-o", tmp_path / "c.vxo")
    assert "distance" not in info and "shell_on_surface" not in info


def test_bad_distance_options(cli, tmp_path):
    for bits in (2, 5, 32):
        with pytest.raises(ValueError, match=r"distance_bits: %d is not 4, 8 or 16" % bits):
            voxcd.voxelize("cube", resolution=8, distance_bits=bits)
    for band in (0.0, -1.0, math.nan, math.inf):
        with pytest.raises(ValueError, match=r"band: .* is not a positive finite number"):
            voxcd.voxelize("cube", resolution=8, distance_bits=8, band=band)
    out = tmp_path / "x.vxo"
    cli("voxelize", "cube", "--resolution", "8", "--distance-bits", "5", "-o", out, expect=105)
    cli("voxelize", "cube", "--resolution", "8", "--distance-bits", "8", "--band", "0", "-o", out, expect=105)
    cli("voxelize", "cube", "--resolution", "8", "--band", "2", "-o", out, expect=107)
    assert not out.exists()
    (tmp_path / "cloud.obj").write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n")
    with pytest.raises(ValueError, match=r"cloud\.obj: a point cloud has no surface"):
        voxcd.voxelize(tmp_path / "cloud.obj", resolution=8, distance_bits=8)
