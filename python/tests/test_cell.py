"""The periodic cell from Python (`sim.cell`): its edges and gradient as the scene imposes
them and as `micro.csv` measures them, and wrap counts that unwrap the bodies' paths."""

import numpy as np
import pytest
import xper
from conftest import cut_scene, drop


def test_a_sheared_cell_shows_its_edges_gradient_and_wraps(tmp_path, fresh):
    scene = cut_scene("simple_shear", tmp_path, steps="400")
    sim = xper.Simulation.from_file(scene, out=fresh("shear"))
    n = len(sim.bodies.id)
    names = [a["name"] for a in sim.array_info() if a["name"].startswith("cell.")]
    assert names == ["cell.origin", "cell.edges", "cell.gradient", "cell.wraps"]
    assert sim.cell.origin.tolist() == [0.0, 0.0]
    assert sim.cell.edges.tolist() == [[0.06, 0.0], [0.0, 0.06]]
    assert sim.cell.wraps.shape == (n, 2) and sim.cell.wraps.dtype == np.int64
    # Unwrapped paths: positions jump by a side when a body leaves the cell, x + H w does not.
    # The cell's width stays; before the packing forms its height barely moves. The disks
    # start at rest: given 0.5 m/s, many leave within the 60 steps.
    rng = np.random.default_rng(1)
    sim.bodies.velocity = rng.uniform(-0.5, 0.5, size=(n, 2))
    paths = []
    for _ in range(60):
        sim.step(1)
        h = sim.cell.edges
        paths.append(sim.bodies.position + sim.cell.wraps @ h.T)
    assert np.abs(sim.cell.wraps).sum() > 0, "no disk left the cell"
    steps = np.diff(np.array(paths), axis=0)
    assert np.abs(steps).max() < 1e-3          # m: at most v dt plus the flow's carry
    # The imposed rate, the free height under stress, upper triangular edges.
    g, h = sim.cell.gradient, sim.cell.edges
    assert g[0, 1] == 1.0 and g[1, 0] == 0.0 and g[0, 0] == 0.0
    assert h[1, 0] == 0.0 and h[0, 0] == 0.06
    sim.step(340)                               # to the frame at step 400
    last = {k: v[-1] for k, v in sim.tables()["micro.csv"].items()}
    assert last["step"] == 400
    assert sim.cell.edges[1, 1] == last["extent_y"]
    assert sim.cell.edges[0, 0] == last["extent_x"]
    assert sim.cell.gradient[1, 1] != 0.0       # the height moved under the stress
    with pytest.raises(xper.SceneError, match="cell.edges: read-only"):
        sim.cell.edges = np.eye(2)


def test_a_scene_without_a_cell_has_no_cell_arrays(tmp_path, fresh):
    sim = drop(tmp_path, fresh, duration="0.01")
    assert not [a for a in sim.array_info() if a["name"].startswith("cell.")]
    with pytest.raises(AttributeError, match="cell has no array 'edges'"):
        sim.cell.edges
