//! `xper bench --fclib DIR`: every solver on every problem of the external suite
//! (`../shared/fclib/`: FCLib HDF5 and Siconos `.dat` files), with the error reached, the
//! iterations and the wall time, against the published mean time of the fastest solver per
//! collection (Acary, Bremond, Huber 2018: Capsules 0.015 s, BoxesStack 0.034 s, on the
//! authors' machine). Tolerance 1e-8 (1e-4 for the LMGC90 PerioBox collection) on the error
//! scaled by `|q|`, as in that comparison.

use serde::{Deserialize, Serialize};
use std::path::Path;
use xper_simulation::RunError;
use xper_solver::solve_timed;
use xper_solver::ErrorScaling;
use xper_validation::suite::{load_local, suite_files, suite_solvers, suite_tolerance};

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

/// Runs every solver on every problem of `dir`.
pub fn bench_suite(dir: &Path, machine: String) -> Result<SolverBench, RunError> {
    let files = suite_files(dir);
    if files.is_empty() {
        return Err(RunError::BadInput(format!(
            "{}: no problem files (.dat{}) found in its hdf5_3d_local, hdf5_3d_global or siconos_dat_2d folders",
            dir.display(),
            if cfg!(feature = "hdf5") { ", .hdf5" } else { "" }
        )));
    }
    let mut rows = Vec::new();
    for path in &files {
        let problem = load_local(path)?;
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
         (their machine). Time: median of up to 5 solves, reading and global-to-local reduction excluded.\n\
         One row per problem: the fastest solver that reached the tolerance, of those tried; every\n\
         solver's figures are in `bench-results/solvers.json`.\n\n\
         | problem | dim | contacts | fastest solver (tried) | iterations | error (/ abs q) | time (s) | fastest published (s) |\n\
         |---|---|---|---|---|---|---|---|\n",
    );
    let mut problems: Vec<&str> = bench.rows.iter().map(|r| r.problem.as_str()).collect();
    problems.dedup();
    for problem in problems {
        let rows: Vec<&SolverBenchRow> =
            bench.rows.iter().filter(|r| r.problem == problem).collect();
        let best = rows
            .iter()
            .filter(|r| r.converged)
            .min_by(|a, b| a.time_s.total_cmp(&b.time_s));
        let r = rows[0];
        let (solver, iterations, error, time) = match best {
            Some(b) => (
                format!("{} ({})", b.solver, rows.len()),
                b.iterations.to_string(),
                format!("{:.1e}", b.error_q),
                format!("{:.4}", b.time_s),
            ),
            None => (
                format!("none reached it ({})", rows.len()),
                "-".into(),
                "-".into(),
                "-".into(),
            ),
        };
        md.push_str(&format!(
            "| {} | {} | {} | {solver} | {iterations} | {error} | {time} | {} |\n",
            r.problem,
            r.dimension,
            r.contacts,
            r.published_fastest_s
                .map_or("-".to_string(), |t| format!("{t}"))
        ));
    }
    md.push_str(&format!("\nMachine: {}.\n", bench.machine));
    md
}
