"""The public API in Python (docs/api.md): objects from arrays and trimesh-style meshes, collide() in one call, and a
World stepped from Python that gives `voxcd simulate`'s state hash."""
from types import SimpleNamespace

import numpy as np
import pytest

import voxcd

TETRA_V = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float)
TETRA_F = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])


def test_objects_from_arrays_and_trimesh_style_meshes():
    a = voxcd.voxelize((TETRA_V, TETRA_F), resolution=16)
    b = voxcd.voxelize(SimpleNamespace(vertices=TETRA_V, faces=TETRA_F), resolution=16)
    c = voxcd.voxelize(SimpleNamespace(vertices=TETRA_V.tolist(), triangles=TETRA_F.tolist()), resolution=16)  # Open3D
    assert np.array_equal(a.states, b.states) and np.array_equal(a.states, c.states)
    assert a.counts["interior"] > 0 and a.report["closed"]
    with pytest.raises(ValueError, match=r"vertices: give a \(V, 3\) array"):
        voxcd.voxelize((TETRA_V[:, :2], TETRA_F), resolution=16)
    with pytest.raises(ValueError, match=r"faces: face 1 has vertex index -1 \(negative\)"):
        voxcd.voxelize((TETRA_V, np.array([[0, 2, 1], [0, 1, -1]])), resolution=16)
    with pytest.raises(ValueError, match=r"faces: give an \(F, 3\) array of integer"):
        voxcd.voxelize((TETRA_V, TETRA_F.astype(float)), resolution=16)


def test_collide_in_one_call():
    torus = voxcd.voxelize("torus", resolution=32)
    mesh = SimpleNamespace(vertices=TETRA_V, faces=TETRA_F)
    c = voxcd.collide(torus, None, mesh, [0.9, 0, 0, 0, 0, 30])
    assert c["hits"] > 0 and len(c["positions"]) == len(c["depths"]) > 0
    # The same pose as a 4 x 4 matrix, and the same query through Pair (both directions).
    t = np.radians(30)
    m = np.array([[np.cos(t), -np.sin(t), 0, 0.9], [np.sin(t), np.cos(t), 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])
    b = voxcd.voxelize(mesh, resolution=32)
    c2 = voxcd.collide(torus, np.eye(4), b, m)
    want = voxcd.Pair(torus, b).query([0.9, 0, 0, 0, 0, 30], both_directions=True)
    assert c2["hits"] == want["hits"]
    assert np.allclose(c2["positions"], want["positions"])
    assert voxcd.collide(torus, None, b, [0.9, 0, 0, 0, 0, 30], mode="COUNT")["hits"] == want["hits"]
    assert voxcd.collide(torus, None, b, [9, 0, 0])["hits"] == 0
    with pytest.raises(ValueError, match=r"pose_b: the matrix's upper left 3x3 is not a rotation"):
        voxcd.collide(torus, None, b, np.diag([2.0, 1, 1, 1]))
    with pytest.raises(ValueError, match=r"mode: 'ANY' is not ALL, FIRST or COUNT"):
        voxcd.collide(torus, None, b, None, mode="ANY")


def test_a_world_stepped_from_python_is_the_tools_run(cli):
    import json

    w = voxcd.World.scene()
    for _ in range(100):
        w.step()
    assert w.frame == 100 and len(w) == 64
    assert w.state_hash == json.loads(cli("simulate", "--frames", 100, "--json"))["state_hash"]
    # Positions are a view of the world's state: it follows the world.
    p = w.positions
    assert p.shape == (64, 3) and not p.flags["OWNDATA"]
    w.step()
    assert np.shares_memory(p, w.positions) and np.array_equal(p, w.positions)
    q = w.orientations
    assert q.shape == (64, 4) and np.allclose(np.linalg.norm(q, axis=1), 1)
    with pytest.raises(ValueError, match=r"frames: a World is stepped by its caller"):
        voxcd.World.scene(frames=5)


def test_a_world_of_ones_own():
    w = voxcd.World()
    torus = voxcd.voxelize("torus", voxel=0.1)
    assert w.add(torus, [40, 50, 50], velocity=[0.25, 0, 0]) == voxcd.BodyId(0, 1)
    with pytest.deprecated_call():  # the form before World.add: an index
        assert w.add_body((TETRA_V * 2, TETRA_F), [46, 50, 50], velocity=[-0.25, 0, 0]) == 1
    touching = sum(w.step()["touching"] for _ in range(30))
    assert touching > 0
    assert w.positions[0, 0] > 40
    assert w.pairs.shape[1] == 2


def test_collide_holds_no_pool_per_thread_and_pair_is_the_reusable_query():
    """voxcd.collide keeps nothing per calling thread (one shared pool for threads=0); a Pair keeps its device."""
    import os
    import threading
    import time

    def threads_now():
        return len(os.listdir("/proc/self/task"))

    def settled(want):
        """The thread count once it is `want`, or after 10 s: an ended thread leaves /proc/self/task a little after
        its join returns (later under the sanitizers); a pool that stayed never does."""
        deadline = time.monotonic() + 10
        while threads_now() != want and time.monotonic() < deadline:
            time.sleep(0.01)
        return threads_now()

    a, b = voxcd.voxelize("torus", resolution=32), voxcd.voxelize("cube", resolution=32)
    want = voxcd.collide(a, None, b, [1.2, 0, 0])      # the shared pool exists from here on
    before = threads_now()
    during = []

    def query():
        voxcd.collide(a, None, b, [1.2, 0, 0])
        voxcd.collide(a, None, b, [1.2, 0, 0], threads=3)   # a pool for the call alone
        during.append(settled(before + 1))

    for _ in range(3):
        t = threading.Thread(target=query)
        t.start()
        t.join()
    assert during == [before + 1] * 3 and settled(before) == before
    got = voxcd.Pair(a, b).query([1.2, 0, 0], both_directions=True)
    assert got["hits"] == want["hits"]
    np.testing.assert_array_equal(got["positions"], want["positions"])


def test_objects_with_cpp_names_and_defaults():
    """Object.load and Object.from_arrays take an ObjectDef's fields with its defaults: 32 voxels along the longest
    side, stored dense; an object file brings its own voxel."""
    torus = voxcd.Object.load("torus")
    want = voxcd.voxelize("torus", resolution=32, storage="dense")
    assert torus.voxel == want.voxel and torus.dims == want.dims and torus.storage["voxmap"] == "dense"
    np.testing.assert_array_equal(torus.shell_points, want.shell_points)
    fine = voxcd.Object.load("torus", voxel=0.1)
    assert fine.voxel == 0.1 and voxcd.Object.load("torus", resolution=16).voxel == pytest.approx(2 * torus.voxel)
    tetra = voxcd.Object.from_arrays(TETRA_V, TETRA_F.astype(np.uint32))
    np.testing.assert_array_equal(tetra.states, voxcd.voxelize((TETRA_V, TETRA_F), resolution=32,
                                                               storage="dense").states)
    with pytest.raises(voxcd.OptionError, match=r"^voxel: -1\.0 is not 0 or a positive number$"):
        voxcd.Object.load("torus", voxel=-1.0)
    with pytest.raises(voxcd.OptionError, match=r"^triangles: a vertex index is negative"):
        voxcd.Object.from_arrays(TETRA_V, TETRA_F - 1)
    with pytest.raises(voxcd.OptionError, match=r"^vertices: give a \(V, 3\) array"):
        voxcd.Object.from_arrays(TETRA_V[:, :2], TETRA_F)
    with pytest.raises(voxcd.MeshError, match=r"^arrays: "):
        voxcd.Object.from_arrays(TETRA_V, TETRA_F + 1)   # an index beyond the vertices
    # The library's Object itself: the C++ names in messages ("torus", not the tool's "shape:torus").
    with pytest.raises(voxcd.RangeError, match=r"^pair 0 \(torus, torus\)"):
        voxcd.collide(torus, None, torus, [1e9, 0, 0])


def test_object_files_through_object_load(tmp_path):
    torus = voxcd.Object.load("torus", resolution=16, distance_bits=8)
    torus.save(tmp_path / "t.vxo")
    again = voxcd.Object.load(tmp_path / "t.vxo", resolution=99)   # an object file brings its own voxel
    assert again.voxel == torus.voxel and again.distance_bits == 8
    with pytest.raises(voxcd.MeshError, match=r"the object has a 8-bit distance field|4 bits were asked for"):
        voxcd.Object.load(tmp_path / "t.vxo", distance_bits=4)


def test_a_collider_gives_collides_contacts():
    """voxcd.Collider is the C++ Collider: its options are collide()'s, its results collide()'s, one pose or a batch."""
    a, b = voxcd.Object.load("torus"), voxcd.Object.load("cube")
    collider = voxcd.Collider(threads=1)
    assert collider.options == {"mode": "ALL", "both_directions": True, "margin": 0.0, "backend": "cpu", "lanes": 4,
                                "threads": 1}
    assert collider.worker_threads == 0
    poses = [(None, [1.2, 0, 0]), (np.eye(4), [0.9, 0, 0, 0, 0, 30]), (None, [5, 0, 0])]
    for pose_a, pose_b in poses:
        got, want = collider.collide(a, pose_a, b, pose_b), voxcd.collide(a, pose_a, b, pose_b)
        assert got["hits"] == want["hits"]
        np.testing.assert_array_equal(got["positions"], want["positions"])
    batch = collider.collide(a, b, poses)
    assert [r["hits"] for r in batch] == [r["hits"] for r in voxcd.collide(a, b, poses)]
    assert [r["hits"] for r in batch] == [voxcd.collide(a, p, b, q)["hits"] for p, q in poses]
    assert batch[0]["hits"] > 0 and batch[2]["hits"] == 0
    first = voxcd.Collider(mode="FIRST", both_directions=False).collide(a, None, b, [1.2, 0, 0])
    assert first["hits"] == voxcd.collide(a, None, b, [1.2, 0, 0], mode="FIRST", both_directions=False)["hits"] == 1
    with pytest.raises(voxcd.OptionError, match=r"^mode: 'SOME' is not ALL, FIRST or COUNT$"):
        voxcd.Collider(mode="SOME")
    with pytest.raises(voxcd.OptionError, match=r"^poses\[0\]: give a \(pose_a, pose_b\) pair$"):
        collider.collide(a, b, [[1, 2, 3]])


def test_shell_arrays_view_the_objects_own_without_a_copy():
    torus = voxcd.Object.load("torus", resolution=16)
    points, normals, cells = torus.shell_points, torus.shell_normals, torus.shell_cells
    assert points.shape == normals.shape == cells.shape == (torus.shell_count, 3)
    assert points.dtype == np.float64 and cells.dtype == np.uint32
    assert not points.flags.writeable and not points.flags.owndata and points.base is not None
    assert np.shares_memory(torus.shell_points, points)   # the same buffer each time: the object's own
    copy = points.copy()
    del torus   # the views keep the object alive
    np.testing.assert_array_equal(points, copy)
    with pytest.raises(ValueError, match="read-only"):
        points[0, 0] = 1
