"""Frictional contact problems as arrays: ``u = W r + q`` with, per contact, ``r`` in the
Coulomb cone of ``mu`` and ``(u_n + mu |u_t|, u_t)`` in its dual, complementary to ``r``
(the form of FCLib and Siconos; Acary, Bremond, Huber 2018). ``xper solve`` solves the same."""

from __future__ import annotations

import os
from dataclasses import dataclass
from typing import Any, Dict, Optional, Tuple

import numpy as np

from . import _xper
from ._xper import SceneError


@dataclass(frozen=True)
class CsrMatrix:
    """A sparse matrix in compressed rows (SciPy's ``csr_matrix`` layout)."""

    indptr: np.ndarray
    indices: np.ndarray
    data: np.ndarray
    shape: Tuple[int, int]

    def toarray(self) -> np.ndarray:
        """The dense matrix."""
        dense = np.zeros(self.shape)
        for i in range(self.shape[0]):
            lo, hi = self.indptr[i], self.indptr[i + 1]
            dense[i, self.indices[lo:hi]] = self.data[lo:hi]
        return dense

    def to_scipy(self) -> Any:
        """The same matrix as ``scipy.sparse.csr_matrix`` (needs SciPy)."""
        from scipy.sparse import csr_matrix
        return csr_matrix((self.data, self.indices, self.indptr), shape=self.shape)


@dataclass(frozen=True)
class Problem:
    """A problem in its local form: ``dim`` (2 or 3) components per contact."""

    dim: int
    W: CsrMatrix
    q: np.ndarray
    mu: np.ndarray
    form: str
    """``local``, or ``global`` when the file held ``M``, ``H``, ``f``, ``w`` (reduced to
    ``W = H^T M^-1 H``, ``q = H^T M^-1 f + w``)."""

    @property
    def contacts(self) -> int:
        return len(self.mu)


@dataclass(frozen=True)
class SolveResult:
    """Impulses ``r`` and local velocities ``u = W r + q`` (``dim`` per contact: normal
    first), with the solver's report. ``error`` is the natural-map error (``absolute``,
    ``relative_q`` = / |q|, ``relative_max`` = / max(|q|, |r|, |u|))."""

    r: np.ndarray
    u: np.ndarray
    solver: str
    iterations: int
    inner_iterations: int
    error: Dict[str, float]
    converged: bool
    wall_time_s: float


def _as_csr(W: Any) -> CsrMatrix:
    if isinstance(W, CsrMatrix):
        return W
    if hasattr(W, "tocsr"):                     # any SciPy sparse matrix or array
        m = W.tocsr()
        m.sort_indices()
        return CsrMatrix(np.asarray(m.indptr), np.asarray(m.indices),
                         np.asarray(m.data, dtype=np.float64), m.shape)
    dense = np.asarray(W, dtype=np.float64)
    if dense.ndim != 2:
        raise SceneError(f"W: a matrix (2 axes) is needed, got {dense.ndim} axes")
    rows, cols = np.nonzero(dense)
    indptr = np.searchsorted(rows, np.arange(dense.shape[0] + 1))
    return CsrMatrix(indptr, cols, dense[rows, cols], dense.shape)


def solve(W: Any, q: Any, mu: Any, solver: str = "nlgs", tol: float = 1e-8,
          max_iter: Optional[int] = None, scaling: str = "max",
          warm_start: Optional[Any] = None, dim: Optional[int] = None) -> SolveResult:
    """Solves ``u = W r + q`` under Coulomb friction. ``W``: a NumPy matrix, a SciPy sparse
    matrix or a :class:`CsrMatrix`; ``q``: ``dim * n`` values (normal first per contact);
    ``mu``: ``n`` coefficients. ``solver``: ``nlgs`` (``nsgs``), ``newton``,
    ``proximal_newton`` or ``lemke`` (2D); ``tol`` on the error scaled by ``scaling``
    (``max`` or ``q``); ``max_iter`` the solver's default when ``None``; ``dim`` (2 or 3)
    is ``len(q) / len(mu)`` unless given (a problem without contacts needs it). An unconverged
    solve is returned with ``converged = False``; a malformed problem raises
    :class:`SceneError`."""
    m = _as_csr(W)
    q = np.ascontiguousarray(q, dtype=np.float64).ravel()
    mu = np.ascontiguousarray(mu, dtype=np.float64).ravel()
    warm = None if warm_start is None else np.ascontiguousarray(warm_start, np.float64).ravel()
    out = _xper.solve_csr(np.ascontiguousarray(m.indptr, dtype=np.int64),
                          np.ascontiguousarray(m.indices, dtype=np.int64),
                          np.ascontiguousarray(m.data, dtype=np.float64),
                          (int(m.shape[0]), int(m.shape[1])), q, mu, solver, float(tol),
                          max_iter, scaling, warm, dim)
    return SolveResult(**out)


def read_problem(path: Any, form: str = "auto") -> Problem:
    """Reads a problem file as ``xper solve`` does: Siconos ``.dat`` (``form``: ``auto``,
    ``local`` or ``global``) or FCLib ``.hdf5`` (when the module was built with HDF5)."""
    p = _xper.read_problem(os.fspath(path), form)
    W = CsrMatrix(p["indptr"], p["indices"], p["data"], tuple(p["shape"]))
    return Problem(p["dim"], W, p["q"], p["mu"], p["form"])
