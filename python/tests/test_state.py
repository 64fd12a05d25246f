"""The state as NumPy arrays: shapes, dtypes and units as documented, values against exact
answers, writes between steps, and errors that name what is wrong."""

import math
import re

import numpy as np
import pytest
import xper
from conftest import DT, G, R, REPO, RHO, Y0, cut_scene, drop



def check_documented(sim):
    """Every listed array has the listed shape (n: its part's count) and dtype."""
    counts = {"bodies": len(sim.bodies.id), "contacts": len(sim.contacts.bodies),
              "laws": len(sim.laws.friction), "world": 1}
    for info in sim.array_info():
        a = sim.array(info["name"])
        n = counts[info["name"].split(".")[0]]
        shape = eval(info["shape"], {"n": n})  # "(n, 2)" -> (n, 2)
        assert a.shape == shape, info
        assert a.dtype == np.dtype(info["dtype"]), info
        assert info["unit"] and info["about"], info
        assert not a.flags.writeable, info


def test_free_fall_is_exact_and_arrays_are_documented(tmp_path, fresh):
    sim = drop(tmp_path, fresh)
    assert [a["name"] for a in sim.array_info()][:3] == ["bodies.id", "bodies.group",
                                                          "bodies.position"]
    check_documented(sim)
    units = {a["name"]: a["unit"] for a in sim.array_info()}
    assert units["bodies.position"] == "m" and units["bodies.velocity"] == "m/s"
    assert units["contacts.normal_impulse"] == "N s" and units["bodies.mass"] == "kg"
    sim.step(100)
    t = sim.time
    assert t == pytest.approx(0.1, rel=1e-12)
    # Moreau-Jean with theta = 1/2 integrates a constant force exactly.
    assert sim.bodies.position[0] == pytest.approx([0.0, Y0 - G * t * t / 2], abs=1e-12)
    assert sim.bodies.velocity[0] == pytest.approx([0.0, -G * t], abs=1e-12)
    assert sim.bodies.mass[0] == pytest.approx(RHO * math.pi * R * R, rel=1e-14)
    assert sim.bodies.radius[0] == R
    assert math.isinf(sim.bodies.mass[1])          # the wall
    assert sim.bodies.radius[1] == pytest.approx(0.5)  # the wall's half-length
    assert sim.world.time[0] == t
    check_documented(sim)


def test_a_resting_disk_carries_its_weight(tmp_path, fresh):
    sim = drop(tmp_path, fresh, duration="0.6")
    sim.run()
    c = sim.contacts
    assert c.bodies.tolist() == [[0, 1]]
    m = sim.bodies.mass[0]
    # At rest the normal impulse of a step is the weight times the step.
    assert c.normal_impulse[0] == pytest.approx(m * G * DT, rel=1e-3)
    assert c.tangential_impulse.tolist() == [[0.0]]
    assert abs(c.normal[0] @ [0.0, 1.0]) == pytest.approx(1.0, abs=1e-12)
    assert c.point[0] == pytest.approx([0.0, 0.0], abs=1e-6)
    assert abs(c.gap[0]) < 1e-6
    assert c.status.tolist() == [1]                # sticking: no tangential load
    assert sim.report["contacts"] == 1
    assert len(sim.series["time"]) == sim.step_index == 600
    check_documented(sim)


def test_velocities_and_gravity_set_between_steps_are_used(tmp_path, fresh):
    sim = drop(tmp_path, fresh)
    sim.bodies.velocity = [[1.0, 2.0], [0.0, 0.0]]
    sim.step(50)
    t = sim.time
    assert sim.bodies.position[0] == pytest.approx([t, Y0 + 2 * t - G * t * t / 2], abs=1e-12)
    sim.world.gravity = np.zeros(2)
    v = sim.bodies.velocity[0].copy()
    p = sim.bodies.position[0].copy()
    sim.step(10)
    assert sim.bodies.velocity[0] == pytest.approx(v, abs=1e-15)
    assert sim.bodies.position[0] == pytest.approx(p + v * 10 * DT, abs=1e-12)
    sim.bodies.angular_velocity = [[3.0], [0.0]]
    sim.step(10)
    assert sim.bodies.orientation[0, 0] == pytest.approx(3.0 * 10 * DT, abs=1e-12)
    # What the script changed of the energy is counted as external work: the budget holds.
    assert abs(sim.report["energy_error"]) < 1e-9 * sim.report["kinetic_energy"]
    assert sim.report["external_work"] != 0


def test_3d_arrays(tmp_path, fresh):
    scene = cut_scene("mixed_shapes_3d", tmp_path, duration="0.02")
    sim = xper.Simulation.from_file(scene, out=fresh("mixed"))
    sim.run()
    check_documented(sim)
    assert sim.bodies.position.shape[1] == 3
    q = sim.bodies.orientation
    assert q.shape[1] == 4
    assert np.linalg.norm(q, axis=1) == pytest.approx(1.0, abs=1e-12)
    assert sim.contacts.tangential_impulse.shape[1] == 2
    n = sim.contacts.normal
    assert np.linalg.norm(n, axis=1) == pytest.approx(1.0, abs=1e-12)
    assert sim.world.gravity.tolist() == [0.0, 0.0, -G]


def test_callbacks_run_every_k_steps(tmp_path, fresh):
    sim = drop(tmp_path, fresh)
    seen = []
    sim.run(until=0.05, every=10, callback=lambda s: seen.append(s.step_index))
    assert seen == [10, 20, 30, 40, 50]
    assert sim.step_index == 50 and not sim.is_finished


def test_a_scene_from_toml_text_runs_as_its_file(tmp_path, fresh):
    text = (REPO / "scenes" / "drop" / "scene.toml").read_text()
    a = xper.Simulation.from_toml(text.replace("duration = 1.0", "duration = 0.02"),
                                  out=fresh("text"))
    b = drop(tmp_path, fresh, duration="0.02")
    a.run()
    b.run()
    assert (a.bodies.position == b.bodies.position).all()
    assert (tmp_path / "text1" / "scene.toml").exists()


def test_arrays_refuse_writes_and_bad_values(tmp_path, fresh):
    sim = drop(tmp_path, fresh)
    position = sim.bodies.position
    with pytest.raises(ValueError):
        position[0, 0] = 1.0
    with pytest.raises(xper.SceneError, match=r"bodies.velocity: an array of shape \[3\]"):
        sim.bodies.velocity = [1.0, 2.0, 3.0]
    with pytest.raises(xper.SceneError, match="bodies.position: read-only"):
        sim.bodies.position = np.zeros((2, 2))
    with pytest.raises(xper.SceneError, match="finite"):
        sim.world.gravity = [0.0, float("nan")]
    with pytest.raises(AttributeError, match="bodies has no array 'positions'"):
        sim.bodies.positions
    with pytest.raises(xper.SceneError, match="no array"):
        sim.array("bodies.nothing")
    with pytest.raises(xper.SceneError, match="whole number"):
        sim.step(-1)
    with pytest.raises(xper.SceneError, match="whole number"):
        sim.run(every=0)


def test_bad_scenes_raise_scene_errors_naming_the_place(tmp_path, fresh):
    bad = tmp_path / "bad.toml"
    bad.write_text('[scene]\nname = "x"\ndt = -1e-3\nduration = 1.0\n')
    with pytest.raises(xper.SceneError) as e:
        xper.Simulation.from_file(bad, out=fresh())
    assert re.search(r"bad\.toml:3:6: scene\.dt: must be > 0 s", str(e.value))
    with pytest.raises(xper.SceneError, match="missing.toml"):
        xper.Simulation.from_file(tmp_path / "missing.toml", out=fresh())
    with pytest.raises(xper.SceneError, match="without a scene file"):
        xper.Simulation.from_file(tmp_path, out=fresh())
    assert issubclass(xper.SceneError, xper.XperError)
    assert issubclass(xper.RunError, xper.XperError)


def test_a_finished_run_refuses_steps_and_keeps_its_state(tmp_path, fresh):
    sim = drop(tmp_path, fresh, duration="0.01")
    sim.run()
    assert sim.is_finished and sim.summary["status"] == "completed"
    with pytest.raises(xper.RunError, match="is finished"):
        sim.step()
    assert sim.bodies.position.shape == (2, 2)
    assert sim.finish()["status"] == "completed"


def test_one_output_directory_holds_one_run(tmp_path, fresh):
    scene = cut_scene("drop", tmp_path, duration="0.01")
    out = fresh()
    first = xper.Simulation.from_file(scene, out=out)
    with pytest.raises(xper.XperError, match="lock"):
        xper.Simulation.from_file(scene, out=out)
    first.finish()


def test_a_step_that_fails_raises_and_ends_the_run(fresh):
    # Two disks falling under a gravity of 1e200 m/s^2: their kinetic energy overflows in the
    # first steps, and the energy check refuses the step.
    s = xper.Scene(name="blows_up", dt=1e-3, duration=0.1, gravity=[0.0, -1e200])
    s.add("materials", name="steel", density=7800.0)
    s.add("laws", between=["disk", "disk"], kind="signorini_coulomb", friction=0.3)
    for x in (0.0, 0.1):
        s.add("bodies", shape="disk", center=[x, 0.0], radius=0.01, material="steel",
              group="disk")
    sim = xper.Simulation.from_scene(s, out=fresh("blows_up"))
    with pytest.raises(xper.RunError, match=r"step \d+ \(t = .* s\): energy blow-up"):
        sim.run()
    assert sim.is_finished and sim.summary is None
    with pytest.raises(xper.RunError, match="is finished"):
        sim.step()
    assert sim.bodies.position.shape == (2, 2)          # the state is still there to read


def test_a_held_body_against_a_wall_makes_no_contact(fresh):
    # A plate whose sideways motion and rotation are imposed (held still), pressed against a
    # wall by gravity along x, beside a free disk on the same wall: no impulse could move the
    # plate along the wall's normal (W_nn = 0), so that pair makes no contact (as in LMGC90)
    # and the run goes on; the disk rests on the wall with its weight.
    s = xper.Scene(name="held", dt=1e-3, duration=0.05, gravity=[-9.81, 0.0])
    s.add("materials", name="steel", density=7800.0)
    s.add("laws", between=["plate", "wall"], kind="signorini_coulomb", friction=0.3)
    s.add("laws", between=["disk", "wall"], kind="signorini_coulomb", friction=0.3)
    s.add("bodies", shape="rectangle", center=[0.0101, 0.0], size=[0.02, 0.1],
          material="steel", group="plate",
          drive={"x": {"velocity": 0.0}, "rotation": {"velocity": 0.0}})
    s.add("bodies", shape="disk", center=[0.01, 0.5], radius=0.01, material="steel",
          group="disk")
    s.add("walls", from_=[0.0, -1.0], to=[0.0, 1.0], group="wall")
    sim = xper.Simulation.from_scene(s, out=fresh("held"))
    sim.run()
    assert sim.is_finished and sim.summary["status"] == "completed"
    assert sim.contacts.bodies.tolist() == [[1, 2]]
    weight = 7800.0 * np.pi * 0.01**2 * 9.81 * 1e-3      # N s per step
    assert abs(sim.contacts.normal_impulse[0] - weight) < 1e-9 * weight
    assert sim.bodies.position[0].tolist() == [0.0101, 0.0]
