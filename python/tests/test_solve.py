"""`xper.solve` against exact answers and against `xper solve` on the shipped problem files."""

import json

import numpy as np
import pytest
import xper
from conftest import REPO, run_cli

FCLIB = REPO.parent / "shared" / "fclib"


def test_one_sliding_contact_exactly():
    # W = I, q = (-1, 0.5), mu = 0.3: r_n = 1 closes the contact, the tangential impulse
    # saturates at -mu r_n and the contact slides at u_t = 0.5 - 0.3.
    res = xper.solve(np.eye(2), [-1.0, 0.5], [0.3], tol=1e-12)
    assert res.converged
    assert res.r == pytest.approx([1.0, -0.3], abs=1e-12)
    assert res.u == pytest.approx([0.0, 0.2], abs=1e-12)


@pytest.mark.parametrize("solver", ["nlgs", "newton", "proximal_newton", "lemke"])
def test_a_sticking_pair_in_2d(solver):
    # Two contacts coupled by W; q such that both stick: r = -W^-1 q when the cones hold.
    W = np.array([[2.0, 0.0, 0.5, 0.0], [0.0, 1.0, 0.0, 0.2],
                  [0.5, 0.0, 2.0, 0.0], [0.0, 0.2, 0.0, 1.0]])
    q = np.array([-1.0, 0.05, -2.0, -0.1])
    r_stick = -np.linalg.solve(W, q)
    res = xper.solve(W, q, [0.5, 0.5], solver=solver, tol=1e-12)
    assert res.converged and res.solver == solver
    assert res.r == pytest.approx(r_stick, abs=1e-9)
    assert res.u == pytest.approx(np.zeros(4), abs=1e-9)


def test_dense_and_sparse_give_the_same_impulses():
    scipy = pytest.importorskip("scipy.sparse")
    rng = np.random.default_rng(3)
    A = rng.normal(size=(9, 9))
    W = A @ A.T + 9 * np.eye(9)                 # 3 contacts in 3D, positive definite
    q = rng.normal(size=9)
    q[::3] = -np.abs(q[::3])
    dense = xper.solve(W, q, [0.3, 0.3, 0.3], tol=1e-12)
    sparse = xper.solve(scipy.csr_matrix(W), q, [0.3, 0.3, 0.3], tol=1e-12)
    assert (dense.r == sparse.r).all() and dense.converged


def fclib_files():
    files = sorted(FCLIB.glob("*/*.dat")) + sorted(FCLIB.glob("*/*.hdf5"))
    return files or [pytest.param(None, marks=pytest.mark.skip(
        reason=f"no problem files in {FCLIB}"))]


@pytest.mark.parametrize("path", fclib_files(), ids=lambda p: p and p.name)
def test_the_problem_files_solve_as_with_the_command(path, tmp_path):
    try:
        problem = xper.read_problem(path)
    except xper.SceneError as e:
        if "HDF5" in str(e) and path.suffix == ".hdf5":
            pytest.skip(f"the module was built without HDF5: {e}")
        raise
    assert problem.dim in (2, 3)
    assert problem.W.shape == (problem.dim * problem.contacts,) * 2
    # 30 sweeps at most: the comparison is of the two ways in, not of convergence.
    res = xper.solve(problem.W, problem.q, problem.mu, tol=1e-8, max_iter=30, dim=problem.dim)
    solution = tmp_path / "solution.json"
    out = run_cli("solve", path, "--tol", "1e-8", "--max-iter", "30", "--solution", solution,
                  ok=(0, 1))
    report = json.loads(out.stdout)
    cli = json.loads(solution.read_text())
    assert report["contacts"] == problem.contacts and report["form"] == problem.form
    assert res.iterations == report["iterations"]
    assert res.r.tolist() == cli["r"]           # the same solver: the same numbers
    assert res.converged == report["converged"]


def test_malformed_problems_raise_scene_errors():
    empty = xper.solve(np.zeros((0, 0)), [], [], dim=3)
    assert empty.converged and empty.r.shape == (0,)
    with pytest.raises(xper.SceneError, match="q has 3 entries and mu 2"):
        xper.solve(np.eye(3), [1.0, 2.0, 3.0], [0.1, 0.2])
    with pytest.raises(xper.SceneError, match="W 2 x 2"):
        xper.solve(np.eye(2), [1.0, 2.0, 3.0, 4.0], [0.1, 0.2])
    with pytest.raises(xper.SceneError, match="mu"):
        xper.solve(np.eye(2), [-1.0, 0.0], [-0.5])
    with pytest.raises(xper.SceneError, match="solver .magic."):
        xper.solve(np.eye(2), [-1.0, 0.0], [0.5], solver="magic")
    with pytest.raises(xper.SceneError, match="tol"):
        xper.solve(np.eye(2), [-1.0, 0.0], [0.5], tol=-1.0)
    unsorted = xper.CsrMatrix(np.array([0, 2, 3]), np.array([1, 0, 1]),
                              np.array([0.5, 1.0, 1.0]), (2, 2))
    with pytest.raises(xper.SceneError, match="W: row 0: column indices not strictly increasing"):
        xper.solve(unsorted, [-1.0, 0.0], [0.5])
    with pytest.raises(xper.SceneError, match="missing.dat"):
        xper.read_problem("missing.dat")
