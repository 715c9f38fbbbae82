"""One name and one default for each concept (docs/python.md, "Deprecated spellings"): both directions by default,
every pose form (and a pose the module or the tool gives back going in again), shell_count beside the shell_points
array, report for repair, broadphase for pruning; each old spelling still works with a DeprecationWarning."""
import json
import math
import warnings

import numpy as np
import pytest

import voxcd


def euler_matrix(deg):
    """R = Rz Ry Rx of degrees about x, y and z (the 6-number form's rotation)."""
    x, y, z = np.radians(deg)
    rx = np.array([[1, 0, 0], [0, math.cos(x), -math.sin(x)], [0, math.sin(x), math.cos(x)]])
    ry = np.array([[math.cos(y), 0, math.sin(y)], [0, 1, 0], [-math.sin(y), 0, math.cos(y)]])
    rz = np.array([[math.cos(z), -math.sin(z), 0], [math.sin(z), math.cos(z), 0], [0, 0, 1]])
    return rz @ ry @ rx


def quaternion_wxyz(r):
    """A unit quaternion (w, x, y, z) of a rotation matrix whose trace is above -1."""
    w = math.sqrt(1 + np.trace(r)) / 2
    return [w, (r[2, 1] - r[1, 2]) / (4 * w), (r[0, 2] - r[2, 0]) / (4 * w), (r[1, 0] - r[0, 1]) / (4 * w)]


def test_both_directions_is_the_default(cli_json):
    pair = voxcd.Pair("torus", "cube")
    pose = [1.2, 0, 0, 0, 0, 30]
    default, both, one = pair.query(pose), pair.query(pose, both_directions=True), pair.query(pose, both_directions=False)
    assert default["hits"] == both["hits"] > one["hits"]
    assert not default["a_in_b"].all() and one["a_in_b"].all()
    assert pair.contacts(pose)["hits"].tolist() == [both["hits"]]
    assert voxcd.pair("torus", "cube", pose)["hits"] == both["hits"]
    assert voxcd.collide(pair.a, None, pair.b, pose)["hits"] == both["hits"]
    # The tool's default is the same.
    want = cli_json("pair", "torus", "cube", "--pose", "1.2,0,0,0,0,30")
    assert want["both_directions"] is True and want["results"][0]["hits"] == both["hits"]
    # A World tests both directions as collide() does; the built-in scene keeps the paper's one.
    w = voxcd.World()
    w.add(pair.a, [50, 50, 50])
    w.add(pair.b, [51.2, 50, 50, 0, 0, 30])
    w.step()
    assert [c["hits"] for c in w.contacts] == [voxcd.collide(pair.a, w.poses[0], pair.b, w.poses[1])["hits"]]
    assert voxcd.simulate(frames=1)["both_directions"] is False


def test_every_pose_form_gives_the_same_contacts(cli_json):
    pair = voxcd.Pair("torus", "cube")
    t, deg = [1.2, -0.1, 0.05], [10, 20, 30]
    r = euler_matrix(deg)
    m34 = np.hstack([r, np.array(t)[:, None]])
    m44 = np.vstack([m34, [0, 0, 0, 1]])
    want = pair.query(t + deg)
    assert want["hits"] > 0
    forms = {
        "7 numbers": t + quaternion_wxyz(r),
        "3 x 4": m34,
        "4 x 4": m44,
        "12 numbers": m34.ravel(),
        "16 numbers": m44.ravel(),
        "(R, t)": (r, t),
        "dict": {"translation": t, "rotation_wxyz": quaternion_wxyz(r)},
    }
    for name, pose in forms.items():
        got = pair.query(pose)
        assert got["hits"] == want["hits"], name
        np.testing.assert_allclose(got["positions"], want["positions"], atol=1e-12, err_msg=name)
    # Batches: rows of any count, or matrices.
    batch = pair.query(np.array([t + deg, t + [0, 0, 0]]))
    assert [b["hits"] for b in batch] == [want["hits"], pair.query(t)["hits"]]
    assert [b["hits"] for b in pair.query(np.stack([m44, m44]))] == [want["hits"]] * 2
    assert [b["hits"] for b in pair.query(np.array([forms["7 numbers"]] * 3))] == [want["hits"]] * 3
    # The pose `voxcd pair --json` prints goes back in, as its dict or as 7 numbers.
    tool = cli_json("pair", "torus", "cube", "--pose", "1.2,-0.1,0.05,10,20,30")["results"][0]
    printed = tool["pose_b"]
    for pose in (printed, printed["translation"] + printed["rotation_wxyz"]):
        got = pair.query(pose)
        assert got["hits"] == tool["hits"] == want["hits"]
        assert got["points"].tolist() == [c["point"] for c in tool["contacts"]]


def test_a_worlds_poses_go_back_in():
    torus = voxcd.voxelize("torus", resolution=16)
    w = voxcd.World()
    w.add(torus, [20, 30, 40, 10, 20, 30], velocity=[0.3, 0, 0], angular_velocity=[0, 0.1, 0])
    for _ in range(5):
        w.step()
    p = w.poses
    assert p.shape == (1, 7)
    np.testing.assert_array_equal(p[0, :3], w.positions[0])
    w2 = voxcd.World()
    w2.add(torus, p[0])
    np.testing.assert_array_equal(w2.poses, p)  # bit for bit
    # Orientations stay scalar last (scipy's order): the same rotation as the pose's w, x, y, z.
    np.testing.assert_array_equal(w.orientations[0], p[0, [4, 5, 6, 3]])


def test_bad_poses_name_what_and_where():
    pair = voxcd.Pair("cube", "cube", voxel=0.25)
    cases = [
        ([1, 2, 3, 4], r"^pose: give 3 \(tx, ty, tz\), 6 .*; got shape \(4\)$"),
        ([0, 0, 0, 2, 0, 0, 0], r"^pose: the quaternion \(2, 0, 0, 0\) has norm 2, not 1$"),
        (np.diag([2.0, 1, 1, 1]), r"^pose: the matrix's upper left 3x3 is not a rotation"),
        (np.diag([1.0, 1, 1, 2]), r"^pose: the 4x4 matrix's last row is \(0, 0, 0, 2\), not \(0, 0, 0, 1\)$"),
        ({"translation": [1, 2]}, r"^pose: translation must be 3 numbers$"),
        ({"translation": [1, 2, 3], "rot": [1, 0, 0, 0]}, r"^pose: rot: unknown key"),
        ([0, 0, math.nan], r"^pose: number 3 of 3 \(nan\) is not finite$"),
        (np.zeros((2, 5)), r"^pose: give .* got shape \(2, 5\)$"),
    ]
    for pose, message in cases:
        with pytest.raises(voxcd.OptionError, match=message):
            pair.query(pose)
    with pytest.raises(voxcd.OptionError, match=r"^pose_b: number 1 of 3 \(inf\) is not finite$"):
        voxcd.collide("cube", None, "cube", [math.inf, 0, 0])
    with pytest.raises(voxcd.OptionError, match=r"^pose: give .* an array of 2 poses \(one pose here\)$"):
        voxcd.World().add(pair.a, np.zeros((2, 3)))


def test_shell_count_and_report():
    obj = voxcd.voxelize("torus", resolution=16)
    assert obj.shell_count == len(obj.shell_points) == len(obj.shell_normals) > 0
    assert obj.report["closed"] is True
    with pytest.warns(DeprecationWarning, match=r"Object\.repair is deprecated: use Object\.report"):
        assert obj.repair == obj.report


def test_broadphase_and_its_old_spelling_pruning(tmp_path):
    want = voxcd.simulate(frames=5, broadphase="sap")
    assert want["broadphase"] == want["pruning"] == "sap"
    assert want["shell_count"] == want["shell_points"] > 0
    with pytest.warns(DeprecationWarning, match=r"^pruning is deprecated: use broadphase"):
        old = voxcd.simulate(frames=5, pruning="sap")
    assert old["state_hash"] == want["state_hash"] and old["broadphase"] == "sap"
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # broadphase warns of nothing
        assert voxcd.simulate(frames=5, broadphase="sap")["state_hash"] == want["state_hash"]
    with pytest.warns(DeprecationWarning):  # both, agreeing
        assert voxcd.simulate(frames=5, pruning="sap", broadphase="sap")["state_hash"] == want["state_hash"]
    with pytest.raises(voxcd.OptionError, match=r"^pruning: is broadphase's deprecated spelling, and names 'sap' "
                                                 r"where broadphase names 'tree'$"):
        voxcd.simulate(frames=5, pruning="sap", broadphase="tree")
    # A scene's "pruning": the same run, a warning naming the scene.
    scene = {"types": [{"shape": "cube", "count": 12}], "frames": 3}
    now = voxcd.simulate(dict(scene, broadphase="sap"))
    with pytest.warns(DeprecationWarning, match=r"^scene: pruning is deprecated: use \"broadphase\""):
        old = voxcd.simulate(dict(scene, pruning="sap"))
    assert old["state_hash"] == now["state_hash"]
    assert now["both_directions"] is True  # a scene without "both_directions" tests both, as a World does
    path = tmp_path / "old.json"
    path.write_text(json.dumps(dict(scene, pruning="sap", broadphase="tree")))
    with pytest.raises(voxcd.SceneFileError, match=r"old\.json: pruning: is \"broadphase\"'s deprecated spelling"):
        voxcd.simulate(path)
    # World takes broadphase, and pruning with a warning.
    assert "broadphase" in voxcd.broadphases.__doc__
    with pytest.warns(DeprecationWarning):
        voxcd.World(pruning="sap")
    with pytest.raises(voxcd.OptionError, match=r"^pruning: .* names 'sap' where broadphase names 'tree'$"):
        voxcd.World(pruning="sap", broadphase="tree")


def test_device_cycles_is_the_one_name():
    pair = voxcd.Pair("torus", "cube")
    r = pair.query([1.2, 0, 0])
    assert r["device_cycles"] > 0 and "cycles" not in r
    assert pair.contacts([1.2, 0, 0])["device_cycles"].tolist() == [r["device_cycles"]]
    assert voxcd.World().step()["device_cycles"] == 0


def test_both_directions_and_its_old_spelling_both():
    pair = voxcd.Pair("torus", "cube")
    pose = [1.2, 0, 0, 0, 0, 30]
    one = pair.query(pose, both_directions=False)
    calls = {
        "Pair.query": lambda **k: pair.query(pose, **k)["hits"],
        "Pair.contacts": lambda **k: int(pair.contacts(pose, **k)["hits"][0]),
        "pair": lambda **k: voxcd.pair("torus", "cube", pose, **k)["hits"],
        "collide": lambda **k: voxcd.collide(pair.a, None, pair.b, pose, **k)["hits"],
    }
    for name, call in calls.items():
        with warnings.catch_warnings():
            warnings.simplefilter("error")  # both_directions warns of nothing
            assert call(both_directions=False) == one["hits"], name
        with pytest.warns(DeprecationWarning, match=r"^both is deprecated: use both_directions"):
            assert call(both=False) == one["hits"], name
        with pytest.raises(voxcd.OptionError, match=r"^both: is both_directions' deprecated spelling, and is True "
                                                     r"where both_directions is False$"):
            call(both=True, both_directions=False)
    with pytest.warns(DeprecationWarning, match=r"^both is deprecated"):
        voxcd.World(both=False)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        voxcd.World(both_directions=False)
    # simulate and World.scene: None is the scene's own default.
    want = voxcd.simulate(frames=3, objects=16, both_directions=True)
    assert want["both_directions"] is True
    with pytest.warns(DeprecationWarning, match=r"^both is deprecated"):
        old = voxcd.simulate(frames=3, objects=16, both=True)
    assert old["state_hash"] == want["state_hash"] and old["both_directions"] is True
    with pytest.raises(voxcd.OptionError, match=r"^both: .* is False where both_directions is True$"):
        voxcd.simulate(frames=3, objects=16, both=False, both_directions=True)
    w = voxcd.World.scene(objects=16, both_directions=True)
    for _ in range(3):
        w.step()
    assert w.state_hash == want["state_hash"]
