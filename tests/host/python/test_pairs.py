"""voxcd.pair and voxcd.Pair against `voxcd pair --json`: the same contacts at the same poses."""
import numpy as np
import pytest

import voxcd


def assert_same_contacts(got, want):
    """got: the module's result for one pose; want: one entry of `voxcd pair --json`'s results."""
    assert got["hits"] == want["hits"]
    assert got["lookups"] == want["lookups"]
    assert got["device_cycles"] == want.get("device_cycles")
    contacts = want["contacts"]
    assert len(got["points"]) == len(contacts)
    if not contacts:
        return
    assert got["a_in_b"].tolist() == [c["shell"] == "A" for c in contacts]
    assert got["points"].tolist() == [c["point"] for c in contacts]
    assert got["voxels"].tolist() == [c["voxel"] for c in contacts]
    assert got["states"].tolist() == [c["state"] for c in contacts]
    # The tool prints positions and normals with 9 significant digits, depths with 6.
    np.testing.assert_allclose(got["positions"], [c["position"] for c in contacts], rtol=2e-8, atol=1e-9)
    np.testing.assert_allclose(got["normals"], [c["normal"] for c in contacts], rtol=2e-8, atol=1e-9)
    np.testing.assert_allclose(got["depths"], [c["depth"] for c in contacts], rtol=5e-6, atol=1e-9)


# Both directions by default in the tool and the module; --no-both is both_directions=False.
POSES = [
    ("0.5,0.2,0.1,10,20,30", [0.5, 0.2, 0.1, 10, 20, 30], ["--no-both"]),
    ("1.2,0,0", [1.2, 0, 0], ["--both"]),
    ("0.3,-0.4,0.2,0,90,0", (0.3, -0.4, 0.2, 0, 90, 0), ["--mode", "FIRST", "--both"]),
    ("0.3,-0.4,0.2,45,0,0", np.array([0.3, -0.4, 0.2, 45, 0, 0]), ["--mode", "COUNT"]),
    ("5,5,5", [5, 5, 5], []),
]


@pytest.mark.parametrize("text, pose, opts", POSES)
def test_pair_equals_the_tool(cli_json, text, pose, opts):
    want = cli_json("pair", "cube", "torus", "--pose", text, *opts)
    mode = opts[opts.index("--mode") + 1] if "--mode" in opts else "ALL"
    got = voxcd.pair("cube", "torus", pose, mode=mode, both_directions="--no-both" not in opts)
    if "--no-both" not in opts and "--both" not in opts:
        assert_same_contacts(voxcd.pair("cube", "torus", pose, mode=mode), want["results"][0])  # the defaults
    assert want["pairs"] == 1
    assert_same_contacts(got, want["results"][0])
    if text == "5,5,5":
        assert got["hits"] == 0 and got["positions"].shape == (0, 3)
    elif mode == "ALL":
        assert got["hits"] > 0 and got["positions"].shape == (got["hits"], 3)


def test_object_files_mesh_files_and_objects(cli, cli_json, tmp_path, scenes):
    mesh = str(scenes / "tetra.obj")
    cli("voxelize", "stellated", "--voxel", "0.1", "-o", tmp_path / "s.vxo")
    want = cli_json("pair", tmp_path / "s.vxo", mesh, "--voxel", "0.1", "--pose", "0.4,0.3,0.2,5,10,15", "--both")
    pose = [0.4, 0.3, 0.2, 5, 10, 15]
    from_files = voxcd.pair(tmp_path / "s.vxo", mesh, pose, voxel=0.1, both_directions=True)
    assert_same_contacts(from_files, want["results"][0])
    # The same objects made in Python (the tool's pair voxelises the mesh dense, with the triangles' exact normals).
    pair = voxcd.Pair(voxcd.read_object(tmp_path / "s.vxo"), voxcd.voxelize(mesh, voxel=0.1, storage="dense"))
    assert pair.voxel == 0  # nothing was voxelised by the pair itself
    assert pair.a.source == "shape:stellated" and pair.b.source == mesh
    assert_same_contacts(pair.query(pose, both_directions=True), want["results"][0])


def test_the_default_voxel_is_the_tools(cli_json):
    want = cli_json("pair", "sphere", "plate", "--resolution", "20", "--pose", "0,0,0.9")
    pair = voxcd.Pair("sphere", "plate", resolution=20)
    assert pair.voxel == pytest.approx(want["voxel"], rel=1e-6)
    assert pair.a.dims == voxcd.voxelize("sphere", voxel=pair.voxel).dims
    assert_same_contacts(pair.query([0, 0, 0.9]), want["results"][0])


def test_many_poses_in_one_batch_equal_one_at_a_time():
    pair = voxcd.Pair("torus", "cube", voxel=0.1, backend="ref")
    poses = np.array([[0.2 * k, 0.1, -0.1, 7 * k, 0, 3 * k] for k in range(8)])
    batch = pair.query(poses, both_directions=True)
    assert isinstance(batch, list) and len(batch) == len(poses)
    assert sum(r["hits"] for r in batch) > 0
    for pose, got in zip(poses, batch):
        one = pair.query(pose, both_directions=True)
        assert one["hits"] == got["hits"] and one["lookups"] == got["lookups"]
        np.testing.assert_array_equal(one["positions"], got["positions"])
        np.testing.assert_array_equal(one["points"], got["points"])
    # Culling changes lookups, never contacts.
    unculled = pair.query(poses, both_directions=True, cull=False)
    for a, b in zip(batch, unculled):
        assert a["hits"] == b["hits"] and a["lookups"] <= b["lookups"]
        np.testing.assert_array_equal(a["voxels"], b["voxels"])


def test_no_pose_is_the_identity():
    pair = voxcd.Pair("cube", "cube", voxel=0.25)
    assert pair.backend == "cpu" and "LANES 4" in pair.device
    same = pair.query()
    assert same["hits"] == pair.query([0, 0, 0])["hits"] > 0
    assert same["device_cycles"] > 0


def test_queries_from_several_threads_give_the_serial_results():
    from concurrent.futures import ThreadPoolExecutor

    pair = voxcd.Pair("stellated", "torus", voxel=0.08)
    poses = [[0.1 * k, 0.05 * k, 0, 0, 10 * k, 0] for k in range(12)]
    serial = [pair.query(p, both_directions=True) for p in poses]
    with ThreadPoolExecutor(max_workers=4) as pool:
        threaded = list(pool.map(lambda p: pair.query(p, both_directions=True), poses))
    assert sum(r["hits"] for r in serial) > 0
    for a, b in zip(serial, threaded):
        assert a["hits"] == b["hits"]
        np.testing.assert_array_equal(a["points"], b["points"])
        np.testing.assert_array_equal(a["positions"], b["positions"])


# Distance voxmaps: `voxcd pair --distance-bits B [--band K] [--margin M]`. Each row: the tool's options, the module's
# keywords, the pose, and the query's options.
DISTANCE = [
    (["--distance-bits", "8"], dict(distance_bits=8), "0.5,0.2,0.1,10,20,30", ["--both"]),
    (["--distance-bits", "4", "--band", "3"], dict(distance_bits=4, band=3.0), "1.2,0,0", ["--no-both"]),
    (["--distance-bits", "16", "--margin", "0.05"], dict(distance_bits=16, margin=0.05), "0.3,-0.4,0.2,0,90,0",
     ["--mode", "FIRST", "--both"]),
    (["--distance-bits", "8", "--band", "6", "--margin", "0.1"], dict(distance_bits=8, band=6.0, margin=0.1),
     "0.3,-0.4,0.2,45,0,0", ["--both"]),
    (["--distance-bits", "8", "--margin", "0.1"], dict(distance_bits=8, margin=0.1), "5,5,5", []),
]


@pytest.mark.parametrize("args, kwargs, text, opts", DISTANCE)
def test_a_distance_pair_equals_the_tool(cli_json, args, kwargs, text, opts):
    want = cli_json("pair", "cube", "torus", "--pose", text, *args, *opts)
    mode = opts[opts.index("--mode") + 1] if "--mode" in opts else "ALL"
    pose = [float(v) for v in text.split(",")]
    pair = voxcd.Pair("cube", "torus", **kwargs)
    assert pair.voxel == pytest.approx(want["voxel"], rel=1e-6)
    assert pair.distance_bits == want["distance_bits"] == kwargs["distance_bits"]
    assert pair.band == pytest.approx(want["band"], rel=1e-6)
    assert pair.margin == want["margin"] == kwargs.get("margin", 0)
    assert pair.a.distance_bits == pair.b.distance_bits == kwargs["distance_bits"]
    assert "SB %d " % kwargs["distance_bits"] in pair.device
    got = pair.query(pose, mode=mode, both_directions="--no-both" not in opts)
    assert_same_contacts(got, want["results"][0])
    # voxcd.pair takes the same keywords.
    assert_same_contacts(voxcd.pair("cube", "torus", pose, mode=mode, both_directions="--no-both" not in opts, **kwargs),
                         want["results"][0])
    if text == "5,5,5":
        assert got["hits"] == 0
        return
    assert got["hits"] > 0
    # A contact of a distance device: state 0, the field's unit gradient as its normal, and a depth (the distance
    # negated) no deeper outside than the margin.
    assert not got["states"].any()
    np.testing.assert_allclose(np.linalg.norm(got["normals"], axis=1), 1, rtol=1e-9)
    assert got["depths"].min() >= -pair.margin - 1e-12
    if pair.margin > 0 and mode == "ALL":
        assert got["depths"].min() < 0  # points within the margin outside the other object are contacts too


def test_distance_object_files_and_objects_are_used_as_they_are(cli, cli_json, cli_error, tmp_path, scenes):
    mesh = str(scenes / "tetra.obj")
    cli("voxelize", "stellated", "--voxel", "0.1", "--distance-bits", "8", "--band", "5", "-o", tmp_path / "d.vxo")
    pose = [0.4, 0.3, 0.2, 5, 10, 15]
    args = ["--voxel", "0.1", "--pose", "0.4,0.3,0.2,5,10,15", "--both", "--distance-bits", "8", "--margin", "0.02"]
    want = cli_json("pair", tmp_path / "d.vxo", mesh, *args)
    from_files = voxcd.pair(tmp_path / "d.vxo", mesh, pose, voxel=0.1, both_directions=True, distance_bits=8, margin=0.02)
    assert_same_contacts(from_files, want["results"][0])
    # The same objects made in Python: the file's band (5 voxels) is kept, whatever band= says.
    pair = voxcd.Pair(voxcd.read_object(tmp_path / "d.vxo"), voxcd.voxelize(mesh, voxel=0.1, distance_bits=8),
                      distance_bits=8, band=2.0, margin=0.02)
    assert pair.band == pytest.approx(want["band"], rel=1e-6) and pair.band[0] == pytest.approx(0.5)
    assert_same_contacts(pair.query(pose, both_directions=True), want["results"][0])

    # Without a field, or with another one, an object cannot be used as it is: the tool's message for a file, the
    # same naming the argument for an Object.
    cli("voxelize", "stellated", "--voxel", "0.1", "-o", tmp_path / "s.vxo")
    message = cli_error("pair", tmp_path / "s.vxo", mesh, *args, expect=2)
    assert message == f"{tmp_path / 's.vxo'}: the object has no distance field; 8 bits were asked for (an " \
                      "object voxelised with distance_bits = 8)"
    with pytest.raises(ValueError) as e:
        voxcd.pair(tmp_path / "s.vxo", mesh, pose, voxel=0.1, distance_bits=8)
    assert str(e.value) == message
    with pytest.raises(ValueError, match=r"^a \(shape:stellated\): the object has no distance field; 8 bits were "):
        voxcd.Pair(voxcd.read_object(tmp_path / "s.vxo"), mesh, voxel=0.1, distance_bits=8)
    message = cli_error("pair", mesh, tmp_path / "d.vxo", *args[:-4], "--distance-bits", "16", expect=2)
    with pytest.raises(ValueError) as e:
        voxcd.pair(mesh, tmp_path / "d.vxo", voxel=0.1, distance_bits=16)
    assert str(e.value) == message and "a distance field of 8 bits; 16 bits were asked for" in message
    with pytest.raises(ValueError, match=r"^b \(shape:stellated\): the object has a distance field of 8 bits; 4 "):
        voxcd.Pair(mesh, voxcd.read_object(tmp_path / "d.vxo"), voxel=0.1, distance_bits=4)


def test_the_distance_keywords_are_not_ignored():
    pose = [0.3, -0.4, 0.2, 45, 0, 0]
    states = voxcd.Pair("cube", "torus")
    fields = voxcd.Pair("cube", "torus", distance_bits=8)
    assert (states.distance_bits, states.band, states.margin) == (0, None, 0)
    assert " SB " not in states.device and "SB 8 " in fields.device
    two, dist = states.query(pose, both_directions=True), fields.query(pose, both_directions=True)
    assert two["hits"] > 0 and dist["hits"] > 0
    assert two["hits"] != dist["hits"] or not np.array_equal(two["positions"], dist["positions"])
    assert set(two["states"].tolist()) <= {voxcd.SURFACE, voxcd.INTERIOR} and two["states"].all()
    assert not dist["states"].any()
    assert fields.a.shell_on_surface and not states.a.shell_on_surface  # meshes and shapes get fields and shells
    # A margin adds the points within it; a wider band changes the fields.
    wide = voxcd.Pair("cube", "torus", distance_bits=8, margin=0.1).query(pose, both_directions=True)
    assert wide["hits"] > dist["hits"] and (wide["depths"] < 0).any() and not (dist["depths"] < 0).any()
    banded = voxcd.Pair("cube", "torus", distance_bits=8, band=8.0)
    assert banded.band[0] == pytest.approx(2 * fields.band[0])
    assert not np.array_equal(banded.a.distance, fields.a.distance)


def test_bad_distance_keywords_are_refused_as_the_tool_refuses_them(cli, cli_error):
    for bits in (3, 2, 32):
        cli_error("pair", "cube", "torus", "--distance-bits", bits, expect=105)
        with pytest.raises(ValueError, match=r"^distance_bits: %d is not 4, 8 or 16" % bits):
            voxcd.Pair("cube", "torus", distance_bits=bits)
        with pytest.raises(ValueError, match=r"^distance_bits: %d is not 4, 8 or 16" % bits):
            voxcd.pair("cube", "torus", distance_bits=bits)
    for band in (0.0, -1.0):
        cli_error("pair", "cube", "torus", "--distance-bits", "8", "--band", band, expect=105)
        with pytest.raises(ValueError, match=r"^band: %r is not a positive finite number of voxels$" % band):
            voxcd.Pair("cube", "torus", distance_bits=8, band=band)
    with pytest.raises(ValueError, match=r"^band: inf is not a positive finite number of voxels$"):
        voxcd.pair("cube", "torus", distance_bits=8, band=float("inf"))
    with pytest.raises(ValueError, match=r"^margin: nan is not a finite number$"):
        voxcd.Pair("cube", "torus", distance_bits=8, margin=float("nan"))
    # A margin beyond what a job's threshold holds: the library's RangeError, the tool's message.
    message = cli_error("pair", "cube", "torus", "--distance-bits", "8", "--margin", "1", expect=2)
    assert message.startswith("pair 0 (cube, torus): margin = 1.000000 does not fit a distance job's threshold")
    pair = voxcd.Pair("cube", "torus", distance_bits=8, margin=1.0)
    with pytest.raises(ValueError) as e:
        pair.query()
    assert str(e.value) == message
    with pytest.raises(ValueError) as e:
        voxcd.pair("cube", "torus", distance_bits=8, margin=1.0)
    assert str(e.value) == message
    # As the tool does, a device of 2-bit states has no distances: a margin (or a band) changes nothing there.
    want = cli("pair", "cube", "torus", "--pose", "1.2,0,0", "--margin", "0.1", "--json")
    assert '"margin"' not in want
    plain = voxcd.pair("cube", "torus", [1.2, 0, 0])
    with_margin = voxcd.pair("cube", "torus", [1.2, 0, 0], margin=0.1, band=6.0)
    assert with_margin["hits"] == plain["hits"] and np.array_equal(with_margin["depths"], plain["depths"])


def test_contacts_in_flat_arrays_are_those_of_query():
    pair = voxcd.Pair("torus", "cube", voxel=0.1)
    poses = np.array([[0.2 * k, 0.1, -0.1, 7 * k, 0, 3 * k] for k in range(8)])
    for both in (False, True):
        flat = pair.contacts(poses, both_directions=both)
        per_pose = pair.query(poses, both_directions=both)
        assert flat["first"].shape == (len(poses) + 1,) and flat["first"][0] == 0
        assert flat["first"][-1] == len(flat["points"]) == sum(len(r["points"]) for r in per_pose) > 0
        for i, want in enumerate(per_pose):
            rows = slice(flat["first"][i], flat["first"][i + 1])
            assert flat["hits"][i] == want["hits"] and flat["lookups"][i] == want["lookups"]
            assert flat["device_cycles"][i] == want["device_cycles"]
            assert (flat["pose"][rows] == i).all()
            for key in ("a_in_b", "points", "positions", "normals", "voxels", "states", "depths"):
                np.testing.assert_array_equal(flat[key][rows], want[key], err_msg=key)
    one = pair.contacts([0.2, 0.1, -0.1])
    assert one["first"].shape == (2,) and one["hits"][0] == pair.query([0.2, 0.1, -0.1])["hits"]
    with pytest.raises(ValueError, match="mode"):
        pair.contacts(poses, mode="SOME")


def test_contact_arrays_are_views_reused_once_freed():
    import gc

    pair = voxcd.Pair("torus", "cube", voxel=0.1)
    poses = np.array([[0.1 * k, 0, 0, 5 * k, 0, 0] for k in range(6)])
    first = pair.contacts(poses, both_directions=True)
    assert not first["positions"].flags["OWNDATA"] and first["positions"].base is not None
    kept = first["positions"]
    address = kept.__array_interface__["data"][0]
    values = kept.copy()
    del first
    gc.collect()
    # One array still alive keeps every array of its query: a second query writes elsewhere.
    second = pair.contacts(poses, both_directions=True)
    assert second["positions"].__array_interface__["data"][0] != address
    np.testing.assert_array_equal(kept, values)
    del second
    gc.collect()
    del kept
    gc.collect()
    # All freed (the first query's last): the next query of the same size writes into the first's memory again.
    third = pair.contacts(poses, both_directions=True)
    assert third["positions"].__array_interface__["data"][0] == address
    np.testing.assert_array_equal(third["positions"], values)
