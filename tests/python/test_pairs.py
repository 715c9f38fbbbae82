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


POSES = [
    ("0.5,0.2,0.1,10,20,30", [0.5, 0.2, 0.1, 10, 20, 30], []),
    ("1.2,0,0", [1.2, 0, 0], ["--both"]),
    ("0.3,-0.4,0.2,0,90,0", (0.3, -0.4, 0.2, 0, 90, 0), ["--mode", "FIRST", "--both"]),
    ("0.3,-0.4,0.2,45,0,0", np.array([0.3, -0.4, 0.2, 45, 0, 0]), ["--mode", "COUNT"]),
    ("5,5,5", [5, 5, 5], []),
]


@pytest.mark.parametrize("text, pose, opts", POSES)
def test_pair_equals_the_tool(cli_json, text, pose, opts):
    want = cli_json("pair", "cube", "torus", "--pose", text, *opts)
    mode = opts[opts.index("--mode") + 1] if "--mode" in opts else "ALL"
    got = voxcd.pair("cube", "torus", pose, mode=mode, both="--both" in opts)
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
    from_files = voxcd.pair(tmp_path / "s.vxo", mesh, pose, voxel=0.1, both=True)
    assert_same_contacts(from_files, want["results"][0])
    # The same objects made in Python.
    pair = voxcd.Pair(voxcd.read_object(tmp_path / "s.vxo"), voxcd.voxelize(mesh, voxel=0.1))
    assert pair.voxel == 0  # nothing was voxelised by the pair itself
    assert pair.a.source == "shape:stellated" and pair.b.source == mesh
    assert_same_contacts(pair.query(pose, both=True), want["results"][0])


def test_the_default_voxel_is_the_tools(cli_json):
    want = cli_json("pair", "sphere", "plate", "--resolution", "20", "--pose", "0,0,0.9")
    pair = voxcd.Pair("sphere", "plate", resolution=20)
    assert pair.voxel == pytest.approx(want["voxel"], rel=1e-6)
    assert pair.a.dims == voxcd.voxelize("sphere", voxel=pair.voxel).dims
    assert_same_contacts(pair.query([0, 0, 0.9]), want["results"][0])


def test_many_poses_in_one_batch_equal_one_at_a_time():
    pair = voxcd.Pair("torus", "cube", voxel=0.1, backend="ref")
    poses = np.array([[0.2 * k, 0.1, -0.1, 7 * k, 0, 3 * k] for k in range(8)])
    batch = pair.query(poses, both=True)
    assert isinstance(batch, list) and len(batch) == len(poses)
    assert sum(r["hits"] for r in batch) > 0
    for pose, got in zip(poses, batch):
        one = pair.query(pose, both=True)
        assert one["hits"] == got["hits"] and one["lookups"] == got["lookups"]
        np.testing.assert_array_equal(one["positions"], got["positions"])
        np.testing.assert_array_equal(one["points"], got["points"])
    # Culling changes lookups, never contacts.
    unculled = pair.query(poses, both=True, cull=False)
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
    serial = [pair.query(p, both=True) for p in poses]
    with ThreadPoolExecutor(max_workers=4) as pool:
        threaded = list(pool.map(lambda p: pair.query(p, both=True), poses))
    assert sum(r["hits"] for r in serial) > 0
    for a, b in zip(serial, threaded):
        assert a["hits"] == b["hits"]
        np.testing.assert_array_equal(a["points"], b["points"])
        np.testing.assert_array_equal(a["positions"], b["positions"])
