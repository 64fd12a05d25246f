//! The external problem suite (`../shared/fclib/`: FCLib HDF5 and Siconos `.dat` files): its
//! files, the published tolerances, and the validation of each problem (the best solver's
//! error against the tolerance, the Signorini-Coulomb conditions of its solution checked by
//! code independent of the solvers').

use crate::RunError;
use serde::Serialize;
use std::path::{Path, PathBuf};
use xper_fclib::{read_local, ReadAs};
use xper_solver::{solve_timed, ErrorScaling, FrictionProblem, ProblemErrorMeasure, SolverKind};

/// Reads a problem file in its local form (a bad-input error naming the file otherwise).
pub fn load_local(path: &Path) -> Result<FrictionProblem, RunError> {
    read_local(path, ReadAs::Auto)
        .map(|(p, _)| p)
        .map_err(RunError::BadInput)
}

/// The suite's problem files under `dir`, sorted; HDF5 files only with the `hdf5` feature.
pub fn suite_files(dir: &Path) -> Vec<PathBuf> {
    let mut files = Vec::new();
    for sub in ["hdf5_3d_local", "hdf5_3d_global", "siconos_dat_2d"] {
        let Ok(entries) = std::fs::read_dir(dir.join(sub)) else {
            continue;
        };
        let mut here: Vec<PathBuf> = entries
            .flatten()
            .map(|e| e.path())
            .filter(|p| {
                let ext = p.extension().and_then(|e| e.to_str()).unwrap_or("");
                ext == "dat" || (cfg!(feature = "hdf5") && (ext == "hdf5" || ext == "h5"))
            })
            .collect();
        here.sort();
        files.extend(here);
    }
    files
}

/// The published tolerance for a problem (1e-4 for LMGC90's large collections).
pub fn suite_tolerance(name: &str) -> f64 {
    if name.contains("PerioBox") {
        1e-4
    } else {
        1e-8
    }
}

/// The solvers run on a problem: Lemke only on small 2D problems (its tableau is dense).
pub fn suite_solvers(dim: usize, contacts: usize) -> Vec<SolverKind> {
    let mut kinds = vec![
        SolverKind::Nlgs,
        SolverKind::Newton,
        SolverKind::ProximalNewton,
    ];
    if dim == 2 && contacts <= 100 {
        kinds.push(SolverKind::Lemke);
    }
    kinds
}

/// The validation of one suite problem: the best of the solvers against the published
/// tolerance, and the Signorini-Coulomb conditions checked on its solution.
#[derive(Clone, Debug, Serialize)]
pub struct SuiteCase {
    /// Problem file name.
    pub problem: String,
    /// 2 or 3.
    pub dimension: usize,
    /// Contacts.
    pub contacts: usize,
    /// Tolerance on the `|q|`-scaled error.
    pub tolerance: f64,
    /// The solver with the smallest error.
    pub solver: String,
    /// Its error scaled by `|q|` (recomputed by the shared function).
    pub error_q: f64,
    /// Its unscaled error `|e|`.
    pub error_abs: f64,
    /// Violations `[impulse, velocity, products]` (see [`law_violations`]).
    pub violations: [f64; 3],
    /// The largest violation accepted: `10 |e|` plus round-off on the scale of `q`.
    pub allowed: f64,
    /// Error within tolerance, violations within `allowed`, and each solver's own error
    /// equal to the shared function's.
    pub passed: bool,
}

/// Solves one suite problem with proximal Newton, NSGS (3000 sweeps) and Newton, stopping at
/// the first that reaches the tolerance, and checks the best solution.
pub fn validate_problem(path: &Path) -> Result<SuiteCase, RunError> {
    let problem = load_local(path)?;
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let tolerance = suite_tolerance(&name);
    let mut best: Option<(ProblemErrorMeasure, &'static str, Vec<f64>)> = None;
    let mut consistent = true;
    for kind in [
        SolverKind::ProximalNewton,
        SolverKind::Nlgs,
        SolverKind::Newton,
    ] {
        let max_iter = (kind == SolverKind::Nlgs).then_some(3000);
        let Ok((report, _)) =
            solve_timed(&problem, kind, tolerance, max_iter, ErrorScaling::RelativeQ)
        else {
            continue;
        };
        let shared = problem.error(&report.r);
        consistent &= (shared.relative_q - report.error.relative_q).abs()
            <= 1e-12 * (1.0 + shared.relative_q);
        if best
            .as_ref()
            .is_none_or(|b| shared.relative_q < b.0.relative_q)
        {
            best = Some((shared, kind.name(), report.r));
        }
        if report.converged {
            break;
        }
    }
    let Some((error, solver, r)) = best else {
        return Err(RunError::Runtime(format!(
            "{}: no solver could start",
            path.display()
        )));
    };
    let violations = law_violations(&problem, &r);
    // r - e is a projection on the cone, so r is within |e| of it; the velocity and product
    // conditions follow within a few |e| (x (1 + mu), mu <= 1 here): allow 10 |e|, plus
    // round-off on the scale of the data.
    let allowed =
        10.0 * error.absolute + 1e-12 * problem.q.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    Ok(SuiteCase {
        problem: name,
        dimension: problem.dim,
        contacts: problem.contact_count(),
        tolerance,
        solver: solver.to_string(),
        error_q: error.relative_q,
        error_abs: error.absolute,
        violations,
        allowed,
        passed: consistent
            && error.relative_q <= tolerance
            && violations.iter().all(|&v| v <= allowed),
    })
}

/// Violations of the Signorini-Coulomb conditions, with `u = W r + q` computed here from the
/// CSR arrays directly: `[impulse conditions (r_N >= 0, |r_T| <= mu r_N), velocity condition
/// (u_N >= 0), products (r_N u_N = 0, r_T . u_T + mu r_N |u_T| = 0) / (max|r| + max|u|)]`.
pub fn law_violations(p: &FrictionProblem, r: &[f64]) -> [f64; 3] {
    let d = p.dim;
    let mut u = p.q.clone();
    for (i, ui) in u.iter_mut().enumerate() {
        for k in p.w.row_ptr[i]..p.w.row_ptr[i + 1] {
            *ui += p.w.values[k] * r[p.w.col_idx[k]];
        }
    }
    let max_abs = |v: &[f64]| v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let scale = (max_abs(r) + max_abs(&u)).max(1e-300);
    let mut worst = [0.0f64; 3];
    for (a, &mu) in p.mu.iter().enumerate() {
        let (ra, ua) = (&r[d * a..d * a + d], &u[d * a..d * a + d]);
        let rt = ra[1..].iter().map(|x| x * x).sum::<f64>().sqrt();
        let ut = ua[1..].iter().map(|x| x * x).sum::<f64>().sqrt();
        let rt_dot_ut: f64 = (1..d).map(|k| ra[k] * ua[k]).sum();
        worst[0] = worst[0].max(-ra[0]).max(rt - mu * ra[0]);
        worst[1] = worst[1].max(-ua[0]);
        worst[2] = worst[2]
            .max((ra[0] * ua[0]).abs() / scale)
            .max((rt_dot_ut + mu * ra[0] * ut).abs() / scale);
    }
    worst
}
