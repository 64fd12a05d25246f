"""The examples of python/examples, run as the README shows them, with their claims checked:
each is a documented program and a test."""

import importlib.util
import subprocess
import sys

import numpy as np
import pytest
from conftest import REPO

EXAMPLES = REPO / "python" / "examples"


def load(name):
    spec = importlib.util.spec_from_file_location(name, EXAMPLES / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_servo_wall_holds_its_pressure(tmp_path):
    servo = load("servo_wall")
    t, asked, measured, _ = servo.run(tmp_path / "servo", pressure=2000.0, grains=200)
    held = t > 0.2
    # Once the bed is still, the grains push on the lid with the pressure asked.
    assert np.abs(measured[held] - 2000.0).max() < 0.01 * 2000.0


def test_contact_network_carries_the_weight(tmp_path):
    net = load("contact_network")
    import xper
    sim = xper.Simulation.from_scene(net.deposit(200), out=tmp_path / "deposit")
    sim.run()
    m = net.network(sim)
    assert m["kinetic_energy"] < 1e-6
    assert m["wall_force"][1] == pytest.approx(m["weight"], rel=1e-4)
    assert abs(m["wall_force"][0]) < 1e-4 * m["weight"]
    assert 2.5 < m["z"] < 4.0        # a frictional 2D packing: between 3 and 4
    s = m["sigma"]
    assert s[0, 0] > 0 and s[1, 1] > 0


def test_parameter_study_matches_the_formula(tmp_path):
    study = load("parameter_study")
    for mu in [0.2, 0.8]:
        t, v = study.rolling_start(mu, tmp_path / f"mu_{mu}")
        assert abs(t - study.V0 / (3 * mu * study.G)) <= study.DT
        assert v == pytest.approx(2 * study.V0 / 3, abs=1e-6)


@pytest.mark.parametrize("name", ["servo_wall", "contact_network", "parameter_study"])
def test_examples_run_from_the_command_line(name, tmp_path):
    pytest.importorskip("matplotlib")
    args = [sys.executable, str(EXAMPLES / f"{name}.py"), "--out", str(tmp_path / name)]
    if name != "contact_network":
        args += ["--plot", str(tmp_path / f"{name}.png")]
    done = subprocess.run(args, capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr
    if name != "contact_network":
        assert (tmp_path / f"{name}.png").stat().st_size > 1000
