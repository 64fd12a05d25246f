"""Control between steps, against exact answers: imposed velocities, forces, a law's
friction and restitution."""

import math

import numpy as np
import pytest
import xper
from conftest import DT, G, Y0, drop

NAN = float("nan")


def test_an_imposed_velocity_moves_the_body_then_frees_it(tmp_path, fresh):
    sim = drop(tmp_path, fresh)
    v = sim.bodies.imposed_velocity
    # The disk is free; the wall's velocity is imposed (0: it is fixed).
    assert v.shape == (2, 3) and np.isnan(v[0]).all() and v[1].tolist() == [0.0] * 3
    v = v.copy()
    v[0, 1] = -1.0                     # m/s, downwards
    sim.bodies.imposed_velocity = v
    sim.step(100)
    # Moreau-Jean (theta = 1/2): the first step moves by h (0 + v) / 2, the others by h v.
    y1 = Y0 - (0.1 - DT / 2)
    assert sim.bodies.position[0, 1] == pytest.approx(y1, abs=1e-12)
    assert sim.bodies.imposed_velocity[0].tolist()[1] == -1.0
    v[0, 1] = NAN                      # free again, from -1 m/s
    sim.bodies.imposed_velocity = v
    assert np.isnan(sim.bodies.imposed_velocity[0]).all()
    sim.step(100)
    t = 0.1
    assert sim.bodies.position[0, 1] == pytest.approx(y1 - t - G * t * t / 2, abs=1e-12)


def test_a_force_equal_to_the_weight_holds_the_body(tmp_path, fresh):
    sim = drop(tmp_path, fresh)
    m = sim.bodies.mass[0]
    f = sim.bodies.force.copy()
    assert f[0].tolist() == [0.0] * 3 and np.isnan(f[1]).all()
    f[0, 1] = m * G                    # N per m of thickness
    sim.bodies.force = f
    sim.step(200)
    assert sim.bodies.position[0] == pytest.approx([0.0, Y0], abs=1e-12)
    assert sim.bodies.force[0, 1] == m * G
    f[1, 0] = 1.0
    with pytest.raises(xper.SceneError, match="body 1 has an infinite mass"):
        sim.bodies.force = f


def test_restitution_set_before_the_impact_makes_the_disk_bounce(tmp_path, fresh):
    sim = drop(tmp_path, fresh)
    assert sim.group_names == ["ball", "ground"]
    assert sim.laws.groups.tolist() == [[0, 1]]
    assert sim.laws.restitution.tolist() == [0.0]
    sim.laws.restitution = [1.0]
    impact = math.sqrt(2 * G * 0.5)    # m/s at the wall
    highest = []
    sim.run(until=0.45, callback=lambda s: highest.append(s.bodies.velocity[0, 1]))
    assert max(highest) == pytest.approx(impact, rel=0.02)
    with pytest.raises(xper.SceneError, match=r"laws.restitution\[0\]: must be in \[0, 1\]"):
        sim.laws.restitution = [1.5]


def test_friction_turns_sliding_into_rolling(tmp_path, fresh):
    sim = drop(tmp_path, fresh)
    sim.run(until=0.6)                 # at rest on the wall
    sim.laws.friction = [0.0]
    sim.bodies.velocity = [[1.0, 0.0], [0.0, 0.0]]
    sim.step(100)
    assert sim.bodies.velocity[0, 0] == pytest.approx(1.0, abs=1e-9)
    assert sim.bodies.angular_velocity[0, 0] == pytest.approx(0.0, abs=1e-9)
    sim.laws.friction = [0.3]
    sim.step(300)
    # A disk (I = m r^2 / 2) sliding at v0 rolls at v0 / (1 + I / (m r^2)) = 2 v0 / 3, after
    # (v0 / 3) / (mu g) = 0.11 s.
    r = sim.bodies.radius[0]
    v, w = sim.bodies.velocity[0, 0], sim.bodies.angular_velocity[0, 0]
    assert v == pytest.approx(2.0 / 3.0, rel=2e-3)
    assert -w * r == pytest.approx(v, rel=2e-3)
    with pytest.raises(xper.SceneError, match=r"laws.friction\[0\]: must be >= 0"):
        sim.laws.friction = [-0.1]


def test_bodies_added_between_steps_fall_and_land(tmp_path, fresh):
    sim = drop(tmp_path, fresh)
    sim.step(100)
    e0 = sim.report["energy_error"]
    new = sim.add_bodies(
        bodies=[dict(shape="disk", center=[0.3, 0.4], radius=0.02, material="iron",
                     group="ball", velocity=[0.0, 1.0])],
        materials=[dict(name="iron", density=7800.0)])
    assert new.tolist() == [2]
    assert sim.bodies.id.tolist() == [0, 1, 2]
    assert sim.bodies.mass[2] == pytest.approx(7800.0 * math.pi * 0.02 ** 2, rel=1e-14)
    sim.step(100)
    t = 0.1
    # Added at rest on the theta = 1/2 scheme: exact under gravity from its own start.
    assert sim.bodies.position[2] == pytest.approx([0.3, 0.4 + t - G * t * t / 2], abs=1e-12)
    # Its energy entered the budget: the error did not jump.
    assert abs(sim.report["energy_error"] - e0) < 1e-9
    sim.run(until=1.0)
    assert sim.contacts.bodies.tolist() == [[0, 1], [1, 2]]
    assert sim.bodies.position[2, 1] == pytest.approx(0.02, abs=1e-5)   # on the wall


def test_bodies_that_cannot_be_added_are_refused(tmp_path, fresh):
    sim = drop(tmp_path, fresh)
    with pytest.raises(xper.SceneError, match='group "stone" is not one of the scene'):
        sim.add_bodies(bodies=[dict(shape="disk", center=[0.3, 0.4], radius=0.02,
                                    material="m", group="stone")],
                       materials=[dict(name="m", density=1000.0)])
    with pytest.raises(xper.SceneError, match=r"added bodies:\d+:\d+: bodies\[0\]\.radius"):
        sim.add_bodies(bodies=[dict(shape="disk", center=[0.3, 0.4], radius=-0.02,
                                    material="m", group="ball")],
                       materials=[dict(name="m", density=1000.0)])
    assert len(sim.bodies.id) == 2
