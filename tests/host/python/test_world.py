"""A world a collision user drives (docs/python.md, "World"): bodies added with a BodyDef's keywords and named by
BodyIds, poses and velocities read and set, static and kinematic bodies, steps in seconds that are the frame step with
every motion scaled, and a world without walls or response that only detects and reports contact events."""
import math

import numpy as np
import pytest

import voxcd


@pytest.fixture(scope="module")
def sphere():
    return voxcd.voxelize("sphere", voxel=0.1)  # radius 1


def test_ids_generations_and_user_data(sphere):
    w = voxcd.World()
    tag = {"name": "first"}
    a = w.add(sphere, [20, 50, 50], user_data=tag)
    b = w.add(sphere, [40, 50, 50], user_data="second")
    assert (a, b) == (voxcd.BodyId(0, 1), voxcd.BodyId(1, 1)) and a != b and len({a, b, voxcd.BodyId(0, 1)}) == 2
    assert w.user_data(a) is tag and w.user_data(b) == "second" and w.ids == [a, b] and len(w) == 2
    w.remove(b)
    assert not w.is_valid(b) and w.ids == [a]
    c = w.add(sphere, [60, 50, 50])
    assert c == voxcd.BodyId(1, 2) and w.user_data(c) is None and repr(c) == "BodyId(1, 2)"
    with pytest.raises(voxcd.BodyError, match=r"^body 1: it was removed \(generation 1; the slot is at 2\)$") as e:
        w.pose(b)
    assert e.value.body == b and e.value.where == "body 1" and isinstance(e.value, ValueError)
    w.set_user_data(a, 5)
    assert w.user_data(a) == 5
    with pytest.raises(voxcd.BodyError, match=r"the null id"):
        w.velocity(voxcd.BodyId())


def test_poses_and_velocities_are_read_and_set(sphere):
    w = voxcd.World()
    a = w.add(sphere, [30, 40, 50, 0, 0, 90], velocity=[0.5, 0, 0], angular_velocity=[0, 0, 0.01])
    m = w.pose(a)
    assert m.shape == (4, 4) and np.allclose(m[:3, 3], [30, 40, 50]) and np.allclose(m[:3, 0], [0, 1, 0])
    assert np.array_equal(w.velocity(a), [0.5, 0, 0]) and np.array_equal(w.angular_velocity(a), [0, 0, 0.01])
    w.step()
    assert np.array_equal(w.pose(a)[:3, 3], [30.5, 40, 50])
    w.set_pose(a, m)  # a pose read goes back in
    w.set_velocity(a, [0, 0.25, 0])
    w.set_angular_velocity(a, None)
    assert np.allclose(w.pose(a), m)
    w.step()
    assert np.allclose(w.pose(a)[:3, 3], [30, 40.25, 50]) and np.array_equal(w.velocities[0], [0, 0.25, 0])
    with pytest.raises(voxcd.BodyError, match=r"^body 0: velocity: \(nan, 0, 0\) is not finite$"):
        w.set_velocity(a, [math.nan, 0, 0])
    with pytest.raises(voxcd.OptionError, match=r"kind: 'heavy' is not dynamic, static or kinematic"):
        w.add(sphere, kind="heavy")
    with pytest.raises(voxcd.OptionError, match=r"^dt: -1 is not a number of seconds"):
        w.step(-1)


def test_static_bodies_never_move_and_kinematic_ones_are_not_pushed(sphere):
    w = voxcd.World()
    s = w.add(sphere, [50, 50, 50], kind="static")
    d = w.add(sphere, [46, 50, 50], velocity=[0.25, 0, 0])
    k = w.add(sphere, [20, 20, 20], velocity=[0.25, 0, 0], kind="kinematic")
    w.add(sphere, [24, 20.2, 20])
    assert (w.kind(s), w.kind(d), w.kind(k)) == ("static", "dynamic", "kinematic")
    before = w.pose(s)
    for _ in range(30):
        w.step()
    assert np.array_equal(w.pose(s), before) and not w.velocity(s).any()
    assert w.velocity(d)[0] < 0 and math.isclose(np.linalg.norm(w.velocity(d)), 0.25)
    assert np.array_equal(w.velocity(k), [0.25, 0, 0]) and w.velocities[3][0] > 0.3
    with pytest.raises(voxcd.BodyError, match=r"given to a static body"):
        w.set_velocity(s, [1, 0, 0])


def bodies(w, sphere, scale):
    for p, v in [([2.5, 10, 10], [-0.3, 0.05, 0]), ([8, 10, 10], [0.2, 0, 0.01]), ([11, 10.5, 10], [-0.2, 0, 0])]:
        w.add(sphere, p, velocity=np.multiply(v, scale), angular_velocity=np.multiply([0.01, 0.02, 0], scale))


def test_a_step_of_dt_seconds_is_the_frame_step_scaled(sphere):
    frames, seconds = voxcd.World(side=20), voxcd.World(side=20)
    bodies(frames, sphere, 1)
    bodies(seconds, sphere, 64)
    stats = [(frames.step(), seconds.step(1 / 64)) for _ in range(60)]
    keys = ["touching", "responses", "wall_hits", "hits"]
    assert all([a[k] for k in keys] == [b[k] for k in keys] for a, b in stats)
    assert sum(a["wall_hits"] for a, _ in stats) > 0 and sum(a["responses"] for a, _ in stats) > 0
    assert np.array_equal(frames.positions, seconds.positions)
    assert np.array_equal(frames.orientations, seconds.orientations)
    assert np.array_equal(frames.velocities * 64, seconds.velocities)


def test_a_detect_only_world_reports_events(sphere):
    w = voxcd.World(walls=False, response=False)
    a = w.add(sphere, [44, 50, 50], velocity=[0.5, 0, 0], user_data="a")
    b = w.add(sphere, [56, 51, 50], velocity=[-0.5, 0, 0], user_data="b")
    begun, ended, touching = [], [], 0
    for f in range(30):
        st = w.step()
        assert st["responses"] == 0 and st["wall_hits"] == 0
        assert np.array_equal(w.velocities, [[0.5, 0, 0], [-0.5, 0, 0]])
        begun += [(f, e) for e in w.begin_events]
        ended += [(f, e) for e in w.end_events]
        for t in w.touching:
            assert (t["a"], t["b"], t["user_data_a"], t["user_data_b"]) == (a, b, "a", "b")
            assert t["hits"] > 0 and t["contacts"] > 0 and math.isclose(np.linalg.norm(t["normal"]), 1)
            assert t["deepest"]["depth"] > 0 and tuple(w.pairs[t["pair"]]) == (0, 1)
            touching += 1
    assert [e for _, e in begun] == [{"a": a, "b": b, "user_data_a": "a", "user_data_b": "b"}]
    assert [e for _, e in ended] == [{"a": a, "b": b, "user_data_a": "a", "user_data_b": "b"}]
    assert begun[0][0] < ended[0][0] and touching == ended[0][0] - begun[0][0]
    assert w.positions[0][0] > 55  # it left the cube's middle through the other, and keeps going: no walls


def test_removing_a_body_ends_its_contacts_with_its_user_data(sphere):
    w = voxcd.World(walls=False, response=False)
    a = w.add(sphere, [50, 50, 50], user_data="a")
    b = w.add(sphere, [51, 50, 50], user_data=["b"])
    w.step()
    assert len(w.begin_events) == 1
    w.remove(b)
    assert len(w.pairs) == 0
    w.step()
    assert w.end_events == [{"a": a, "b": b, "user_data_a": "a", "user_data_b": ["b"]}]
    assert w.touching == [] and w.begin_events == []
    c = w.add(sphere, [50, 51, 50])
    w.step()
    w.set_enabled(c, False)
    w.step()
    assert [e["b"] for e in w.end_events] == [c] and not w.is_enabled(c) and len(w) == 1


def test_without_walls_a_body_leaves_the_cube(sphere):
    for walls in (True, False):
        w = voxcd.World(side=10, walls=walls)
        w.add(sphere, [5, 5, 5], velocity=[1, 0, 0])
        bounces = sum(w.step()["wall_hits"] for _ in range(20))
        assert (bounces > 0, w.positions[0][0] <= 10) == (walls, walls)
