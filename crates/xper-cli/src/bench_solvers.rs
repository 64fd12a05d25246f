//! `xper bench --fclib DIR`: every solver on every problem of the external suite
//! (`../shared/fclib/`: FCLib HDF5 and Siconos `.dat` files), with the error reached, the
//! iterations and the wall time, against the published mean time of the fastest solver per
//! collection (Acary, Bremond, Huber 2018: Capsules 0.015 s, BoxesStack 0.034 s, on the
//! authors' machine). Tolerance 1e-8 (1e-4 for the LMGC90 PerioBox collection) on the error
//! scaled by `|q|`, as in that comparison.

use crate::solve::{load_local, solve_timed, FormArg};
use crate::CliError;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use xper_solver::{ErrorScaling, FrictionProblem, ProblemErrorMeasure, SolverKind};

/// File name of the results in the benchmark directory.
pub const RESULTS_FILE: &str = "solvers.json";

/// One solver on one problem.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct SolverBenchRow {
    /// Problem file name.
    pub problem: String,
    /// Folder of the suite it comes from.
    pub collection: String,
    /// 2 or 3.
    pub dimension: usize,
    /// Contacts.
    pub contacts: usize,
    /// Solver name.
    pub solver: String,
    /// Tolerance on the `|q|`-scaled error.
    pub tolerance: f64,
    /// Iterations of the fastest run.
    pub iterations: u32,
    /// Error reached, scaled by `|q|`.
    pub error_q: f64,
    /// Error reached, scaled by `max(|q|, |r|, |u|)`.
    pub error_max: f64,
    /// Whether the tolerance was reached.
    pub converged: bool,
    /// Median wall time of the solve over `repeats` runs (s).
    pub time_s: f64,
    /// Runs timed.
    pub repeats: usize,
    /// Published mean time of the fastest solver on this collection (s), if any.
    pub published_fastest_s: Option<f64>,
}

/// All rows of one benchmark run.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct SolverBench {
    /// CPU and threads.
    pub machine: String,
    /// One row per problem and solver.
    pub rows: Vec<SolverBenchRow>,
}

fn published_fastest(name: &str) -> Option<f64> {
    if name.starts_with("Capsules") {
        Some(0.015)
    } else if name.starts_with("BoxesStack") {
        Some(0.034)
    } else {
        None
    }
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
        SolverKind::Nsgs,
        SolverKind::Newton,
        SolverKind::ProximalNewton,
    ];
    if dim == 2 && contacts <= 100 {
        kinds.push(SolverKind::Lemke);
    }
    kinds
}

/// Runs every solver on every problem of `dir`.
pub fn bench_suite(dir: &Path, machine: String) -> Result<SolverBench, CliError> {
    let files = suite_files(dir);
    if files.is_empty() {
        return Err(CliError::BadInput(format!(
            "{}: no problem files (.dat{}) found in its hdf5_3d_local, hdf5_3d_global or siconos_dat_2d folders",
            dir.display(),
            if cfg!(feature = "hdf5") { ", .hdf5" } else { "" }
        )));
    }
    let mut rows = Vec::new();
    for path in &files {
        let (problem, _) = load_local(path, FormArg::Auto)?;
        let name = path
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        let collection = path
            .parent()
            .and_then(|p| p.file_name())
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        let tolerance = suite_tolerance(&name);
        for kind in suite_solvers(problem.dim, problem.contact_count()) {
            let mut times = Vec::new();
            let mut last = None;
            // Repeat short solves so that the median is not a timer artefact.
            while times.len() < 5 && (times.is_empty() || times.iter().sum::<f64>() < 0.5) {
                match solve_timed(&problem, kind, tolerance, None, ErrorScaling::RelativeQ) {
                    Ok((report, t)) => {
                        times.push(t);
                        last = Some(report);
                    }
                    Err(e) => {
                        eprintln!("{name}: {}: {e}", kind.name());
                        break;
                    }
                }
            }
            let Some(report) = last else { continue };
            times.sort_by(f64::total_cmp);
            let row = SolverBenchRow {
                problem: name.clone(),
                collection: collection.clone(),
                dimension: problem.dim,
                contacts: problem.contact_count(),
                solver: report.solver.clone(),
                tolerance,
                iterations: report.iterations,
                error_q: report.error.relative_q,
                error_max: report.error.relative_max,
                converged: report.converged,
                time_s: times[times.len() / 2],
                repeats: times.len(),
                published_fastest_s: published_fastest(&name),
            };
            println!(
                "{:<45} {:>5} contacts {:<16} it {:>6} error {:.1e} {} {:.4} s",
                row.problem,
                row.contacts,
                row.solver,
                row.iterations,
                row.error_q,
                if row.converged { "ok  " } else { "FAIL" },
                row.time_s
            );
            rows.push(row);
        }
    }
    Ok(SolverBench { machine, rows })
}

/// The Markdown section of BENCHMARKS.md for a solver benchmark.
pub fn markdown(bench: &SolverBench) -> String {
    let mut md = String::from(
        "\n## Contact solvers on the external problem suite (`../shared/fclib/`)\n\n\
         Regenerated by `cargo run --release -p xper-cli --features hdf5 -- bench --fclib ../shared/fclib`.\n\
         Tolerance 1e-8 (1e-4 for LMGC_100_PR_PerioBox) on the natural-map error scaled by |q|, as in\n\
         Acary, Bremond, Huber (2018), whose mean time of the fastest solver is given where published\n\
         (their machine). Time: median of up to 5 solves, reading and global-to-local reduction excluded.\n\n\
         | problem | dim | contacts | solver | iterations | error (/ abs q) | error (/ max) | reached | time (s) | fastest published (s) |\n\
         |---|---|---|---|---|---|---|---|---|---|\n",
    );
    for r in &bench.rows {
        md.push_str(&format!(
            "| {} | {} | {} | {} | {} | {:.1e} | {:.1e} | {} | {:.4} | {} |\n",
            r.problem,
            r.dimension,
            r.contacts,
            r.solver,
            r.iterations,
            r.error_q,
            r.error_max,
            if r.converged { "yes" } else { "no" },
            r.time_s,
            r.published_fastest_s
                .map_or("-".to_string(), |t| format!("{t}"))
        ));
    }
    md.push_str(&format!("\nMachine: {}.\n", bench.machine));
    md
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
pub fn validate_problem(path: &Path) -> Result<SuiteCase, CliError> {
    let (problem, _) = load_local(path, FormArg::Auto)?;
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let tolerance = suite_tolerance(&name);
    let mut best: Option<(ProblemErrorMeasure, &'static str, Vec<f64>)> = None;
    let mut consistent = true;
    for kind in [
        SolverKind::ProximalNewton,
        SolverKind::Nsgs,
        SolverKind::Newton,
    ] {
        let max_iter = (kind == SolverKind::Nsgs).then_some(3000);
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
        return Err(CliError::Runtime(format!(
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
