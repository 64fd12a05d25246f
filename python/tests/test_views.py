"""Arrays read in place (`Simulation.view`): no copy, the same values as the copies at every
step, read-only, alive as long as they are used, and never left pointing at moved memory."""

import gc

import numpy as np
import pytest
import xper
from conftest import cut_scene, drop

# The arrays a rigid 2D simulation keeps as contiguous float64 rows.
VIEWS_2D = ["bodies.position", "bodies.orientation", "bodies.velocity",
            "bodies.angular_velocity", "bodies.mass"]


def check_views_follow_the_state(sim, names, steps, every):
    """Each view equals the copy `array` makes, bit for bit, before and after steps, without
    being read again: it reads the simulation's memory, not a snapshot."""
    views = {name: sim.view(name) for name in names}
    addresses = {name: v.__array_interface__["data"][0] for name, v in views.items()}
    before = {name: sim.array(name) for name in names}
    for _ in range(steps // every):
        sim.step(every)
        for name, v in views.items():
            assert v.shape == sim.array(name).shape, name
            assert v.dtype == np.float64, name
            assert np.array_equal(v, sim.array(name), equal_nan=True), name
            assert not v.flags.writeable and not v.flags.owndata, name
            # The same memory, which the view does not own: no copy was made.
            assert v.__array_interface__["data"][0] == addresses[name], name
    moved = [n for n in names if not np.array_equal(views[n], before[n])]
    assert "bodies.position" in moved and "bodies.velocity" in moved


def test_views_read_the_state_in_place(tmp_path, fresh):
    sim = drop(tmp_path, fresh, duration="0.5")
    info = {a["name"]: a["view"] for a in sim.array_info()}
    assert sorted(n for n, v in info.items() if v) == sorted(VIEWS_2D)
    check_views_follow_the_state(sim, VIEWS_2D, steps=300, every=50)


def test_views_in_3d_leave_out_the_quaternion(tmp_path, fresh):
    scene = cut_scene("mixed_shapes_3d", tmp_path, duration="0.02")
    sim = xper.Simulation.from_file(scene, out=fresh("mixed"))
    names = ["bodies.position", "bodies.velocity", "bodies.angular_velocity", "bodies.mass"]
    assert sorted(a["name"] for a in sim.array_info() if a["view"]) == sorted(names)
    assert sim.view("bodies.angular_velocity").shape[1] == 3
    check_views_follow_the_state(sim, names, steps=20, every=5)
    # Kept as (x, y, z, w) by the engine, documented as (w, x, y, z): a copy only.
    with pytest.raises(xper.SceneError, match='"bodies.orientation" cannot be read in place'):
        sim.view("bodies.orientation")


def test_views_of_a_fluid_scene_are_its_grains(tmp_path, fresh):
    scene = cut_scene("single_grain_settling", tmp_path, duration="0.02")
    sim = xper.Simulation.from_file(scene, out=fresh())
    assert sorted(a["name"] for a in sim.array_info() if a["view"]) == sorted(VIEWS_2D)
    check_views_follow_the_state(sim, VIEWS_2D, steps=10, every=5)


def test_a_view_refuses_writes_and_arrays_without_one_are_named(tmp_path, fresh):
    sim = drop(tmp_path, fresh, duration="0.1")
    v = sim.view("bodies.velocity")
    with pytest.raises(ValueError, match="read-only"):
        v[0, 0] = 1.0
    # Its base is not a NumPy array: NumPy will not make it writable again.
    with pytest.raises(ValueError):
        v.flags.writeable = True
    for name in ["contacts.gap", "bodies.radius", "bodies.id", "world.gravity"]:
        with pytest.raises(xper.SceneError, match=f'"{name}" cannot be read in place.*'
                           "the arrays with a view: bodies.position"):
            sim.view(name)
    with pytest.raises(xper.SceneError, match='"bodies.nothing" cannot be read in place'):
        sim.view("bodies.nothing")
    # Writes through set_array show in the view (the same memory).
    sim.bodies.velocity = [[0.0, 0.0], [0.5, -0.25]]
    assert v[1].tolist() == [0.5, -0.25]


def test_a_view_keeps_its_simulation_alive(tmp_path, fresh):
    sim = drop(tmp_path, fresh, duration="0.1")
    sim.step(30)
    expected = sim.array("bodies.position")
    v = sim.view("bodies.position")
    del sim
    gc.collect()
    # Still the simulation's memory (freed memory would hold other values, or crash).
    np.zeros(10**6).sum()
    assert np.array_equal(v, expected)


def test_adding_bodies_waits_for_the_views_to_go(tmp_path, fresh):
    sim = drop(tmp_path, fresh, duration="0.5")
    body = dict(shape="disk", center=[0.3, 0.4], radius=0.02, material="iron", group="ball")
    iron = [dict(name="iron", density=7800.0)]
    v = sim.view("bodies.position")
    column = v[:, 1]                      # a slice keeps its view, and so the refusal
    del v
    with pytest.raises(xper.SceneError, match=r"add_bodies: 1 view\(s\) from view\(\)"):
        sim.add_bodies(bodies=[body], materials=iron)
    assert len(sim.bodies.id) == 2        # refused before anything was added
    del column
    gc.collect()
    # Copies do not hold the memory: the bodies are added once the views are gone.
    copy = sim.bodies.position
    assert sim.add_bodies(bodies=[body], materials=iron).tolist() == [2]
    assert sim.view("bodies.position").shape == (3, 2)
    assert copy.shape == (2, 2)
