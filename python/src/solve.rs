//! `xper.solve` and `xper.read_problem`: the contact problem of `xper solve`
//! (`u = W r + q`, `K* ∋ û ⟂ r ∈ K` with the friction cones of `mu`; Acary, Bremond, Huber
//! 2018) given as arrays or read from a Siconos or FCLib file, solved by the library's solvers.

use crate::{guard, SceneError};
use numpy::{PyArray1, PyReadonlyArray1};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::PathBuf;
use xper_fclib::{read_local, ReadAs};
use xper_solver::{solve, CsrMatrix, ErrorScaling, FrictionProblem, SolverKind, SolverParams};

fn kind(name: &str) -> PyResult<SolverKind> {
    Ok(match name {
        "nlgs" | "nsgs" => SolverKind::Nlgs,
        "newton" => SolverKind::Newton,
        "proximal_newton" => SolverKind::ProximalNewton,
        "lemke" => SolverKind::Lemke,
        _ => {
            return Err(SceneError::new_err(format!(
                "solver {name:?}: one of nlgs (or nsgs), newton, proximal_newton, lemke"
            )))
        }
    })
}

fn scaling(name: &str) -> PyResult<ErrorScaling> {
    match name {
        "q" => Ok(ErrorScaling::RelativeQ),
        "max" => Ok(ErrorScaling::RelativeMax),
        _ => Err(SceneError::new_err(format!(
            "scaling {name:?}: \"q\" (|e| / |q|) or \"max\" (|e| / max(|q|, |r|, |u|))"
        ))),
    }
}

/// Solves the problem whose `W` is the CSR matrix (`indptr`, `indices`, `data`, `shape`);
/// returns a dict: `r`, `u`, `solver`, `iterations`, `inner_iterations`, `error` (`absolute`,
/// `relative_q`, `relative_max`), `converged`, `wall_time_s`.
#[pyfunction]
#[pyo3(signature = (indptr, indices, data, shape, q, mu, solver, tol, max_iter, error_scaling, warm_start, dim))]
#[allow(clippy::too_many_arguments)]
pub fn solve_csr<'py>(
    py: Python<'py>,
    indptr: PyReadonlyArray1<'py, i64>,
    indices: PyReadonlyArray1<'py, i64>,
    data: PyReadonlyArray1<'py, f64>,
    shape: (usize, usize),
    q: PyReadonlyArray1<'py, f64>,
    mu: PyReadonlyArray1<'py, f64>,
    solver: &str,
    tol: f64,
    max_iter: Option<u32>,
    error_scaling: &str,
    warm_start: Option<PyReadonlyArray1<'py, f64>>,
    dim: Option<usize>,
) -> PyResult<Bound<'py, PyDict>> {
    guard(|| {
        let (q, mu) = (q.as_array().to_vec(), mu.as_array().to_vec());
        let dim = match dim {
            Some(d) => d,
            None if !mu.is_empty() && q.len() % mu.len() == 0 => q.len() / mu.len(),
            None => {
                return Err(SceneError::new_err(format!(
                    "q has {} entries and mu {}: q needs 2 or 3 per contact (give dim for a \
                     problem without contacts)",
                    q.len(),
                    mu.len()
                )))
            }
        };
        let index = |what: &str, a: PyReadonlyArray1<'py, i64>| {
            (a.as_array().iter())
                .map(|&k| usize::try_from(k))
                .collect::<Result<Vec<usize>, _>>()
                .map_err(|_| SceneError::new_err(format!("W: negative entry in {what}")))
        };
        let (row_ptr, col_idx) = (index("indptr", indptr)?, index("indices", indices)?);
        let values = data.as_array().to_vec();
        let w = CsrMatrix::from_parts(shape.0, shape.1, row_ptr, col_idx, values)
            .map_err(|e| SceneError::new_err(format!("W: {e}")))?;
        let problem =
            FrictionProblem::new(dim, w, q, mu).map_err(|e| SceneError::new_err(e.to_string()))?;
        if !(tol > 0.0 && tol.is_finite()) {
            return Err(SceneError::new_err(format!("tol = {tol}: must be > 0")));
        }
        let mut params = SolverParams::with_kind(kind(solver)?);
        params.tolerance = tol;
        params.scaling = scaling(error_scaling)?;
        if let Some(n) = max_iter {
            params.max_iterations = n;
        }
        let warm = warm_start.map(|w| w.as_array().to_vec());
        let start = std::time::Instant::now();
        let report = solve(&problem, &params, warm.as_deref())
            .map_err(|e| SceneError::new_err(e.to_string()))?;
        let wall = start.elapsed().as_secs_f64();
        let out = PyDict::new(py);
        out.set_item("r", PyArray1::from_vec(py, report.r))?;
        out.set_item("u", PyArray1::from_vec(py, report.u))?;
        out.set_item("solver", report.solver)?;
        out.set_item("iterations", report.iterations)?;
        out.set_item("inner_iterations", report.inner_iterations)?;
        let error = PyDict::new(py);
        error.set_item("absolute", report.error.absolute)?;
        error.set_item("relative_q", report.error.relative_q)?;
        error.set_item("relative_max", report.error.relative_max)?;
        out.set_item("error", error)?;
        out.set_item("converged", report.converged)?;
        out.set_item("wall_time_s", wall)?;
        Ok(out)
    })
}

/// Reads a problem file (Siconos `.dat`, FCLib `.hdf5` when built with HDF5) in its local
/// form (a global problem reduced as `xper solve` does); returns a dict: `dim`, `form`,
/// `indptr`, `indices`, `data`, `shape`, `q`, `mu`.
#[pyfunction]
#[pyo3(signature = (path, form="auto"))]
pub fn read_problem<'py>(
    py: Python<'py>,
    path: PathBuf,
    form: &str,
) -> PyResult<Bound<'py, PyDict>> {
    guard(|| {
        let how = match form {
            "auto" => ReadAs::Auto,
            "local" => ReadAs::Local,
            "global" => ReadAs::Global,
            _ => {
                return Err(SceneError::new_err(format!(
                    "form {form:?}: \"auto\", \"local\" or \"global\""
                )))
            }
        };
        let (p, form) = read_local(&path, how).map_err(SceneError::new_err)?;
        let out = PyDict::new(py);
        out.set_item("dim", p.dim)?;
        out.set_item("form", form)?;
        out.set_item("indptr", PyArray1::from_vec(py, p.w.row_ptr))?;
        out.set_item("indices", PyArray1::from_vec(py, p.w.col_idx))?;
        out.set_item("data", PyArray1::from_vec(py, p.w.values))?;
        out.set_item("shape", (p.w.nrows, p.w.ncols))?;
        out.set_item("q", PyArray1::from_vec(py, p.q))?;
        out.set_item("mu", PyArray1::from_vec(py, p.mu))?;
        Ok(out)
    })
}
