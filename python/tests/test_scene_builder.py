"""Scenes built in Python: the same scene as the TOML file, and the reader's errors."""

import numpy as np
import pytest
import xper
from conftest import REPO


def drop_scene(duration=0.05):
    s = xper.Scene(name="drop", dt=1e-3, duration=duration, theta=0.5, gravity=[0.0, -9.81])
    s.section("solver", kind="nlgs", tolerance=1.666e-4, max_iterations=1000, check_every=10,
              relaxation=1.0, norm="quad")
    s.section("output", frame_every=10, checkpoint_every=100)
    s.add("materials", name="water_like", density=1000.0)
    s.add("laws", between=["ball", "ground"], kind="signorini_coulomb", friction=0.3,
          restitution=0.0)
    s.add("bodies", shape="disk", center=np.array([0.0, 0.55]), radius=0.05,
          material="water_like", group="ball")
    s.add("walls", from_=[-0.5, 0.0], to=[0.5, 0.0], group="ground")
    return s


def test_a_built_scene_runs_as_the_shipped_file(fresh):
    built = xper.Simulation.from_scene(drop_scene(duration=0.4), out=fresh("built"))
    text = (REPO / "scenes" / "drop" / "scene.toml").read_text()
    shipped = xper.Simulation.from_toml(text.replace("duration = 1.0", "duration = 0.4"),
                                        out=fresh("file"))
    built.run()
    shipped.run()
    assert (built.bodies.position == shipped.bodies.position).all()
    assert (built.contacts.normal_impulse == shipped.contacts.normal_impulse).all()
    assert built.report["contacts"] == 1


def test_defaults_are_the_readers():
    s = drop_scene()
    assert s.check() == "rigid"
    # Leaving out the solver and output sections takes the format's defaults.
    bare = xper.Scene(name="drop", dt=1e-3, duration=0.05, gravity=[0.0, -9.81])
    bare.add("materials", name="m", density=1000.0)
    bare.add("bodies", shape="disk", center=[0.0, 0.5], radius=0.05, material="m", group="g")
    assert bare.check() == "rigid"


def test_bad_values_raise_scene_errors_with_field_and_reason():
    s = drop_scene()
    s.section("scene", dt=-1.0)
    with pytest.raises(xper.SceneError, match=r"scene\.toml:\d+:\d+: scene\.dt: must be > 0 s"):
        s.check()
    s = drop_scene()
    s.add("bodies", shape="disk", center=[0.0, 0.3], radius=-0.05, material="water_like",
          group="ball")
    with pytest.raises(xper.SceneError, match="radius"):
        s.check()
    with pytest.raises(TypeError, match="not object"):
        xper.Scene(name="x", dt=object()).to_toml()


def test_toml_values():
    s = xper.Scene(name="q\"uote", flag=True, big=1e300, small=5e-324, n=3, inf=float("inf"),
                   nested={"a": 1, "b": [1.5, 2.0]})
    text = s.to_toml()
    tomllib = pytest.importorskip("tomllib")
    parsed = tomllib.loads(text)["scene"]
    assert parsed == {"name": "q\"uote", "flag": True, "big": 1e300, "small": 5e-324, "n": 3,
                      "inf": float("inf"), "nested": {"a": 1, "b": [1.5, 2.0]}}
