//! The external suite: every problem of `../shared/fclib/` (written by Siconos and LMGC90,
//! never copied into this repository) is solved by xper's solvers. For each problem at least
//! one solver must reach the published tolerance (1e-8; 1e-4 for LMGC_100_PR_PerioBox) in the
//! `|q|` scaling of Acary, Bremond, Huber (2018), every solver's error is recomputed by the one
//! shared function, and the best solution must satisfy the Signorini-Coulomb conditions,
//! checked here by code independent of the solvers and of the error measure.

use std::path::{Path, PathBuf};
use xper_cli::solve::{load_local, FormArg};
use xper_solver::{solve, ErrorScaling, FrictionProblem, SolverKind, SolverParams};

fn shared_dir() -> Option<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/fclib");
    dir.is_dir().then_some(dir)
}

fn problem_files(dir: &Path) -> Vec<PathBuf> {
    let mut files = Vec::new();
    for sub in ["siconos_dat_2d", "hdf5_3d_local", "hdf5_3d_global"] {
        let Ok(entries) = std::fs::read_dir(dir.join(sub)) else {
            continue;
        };
        for e in entries.flatten() {
            let path = e.path();
            let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("");
            if ext == "dat" || (cfg!(feature = "hdf5") && (ext == "hdf5" || ext == "h5")) {
                files.push(path);
            }
        }
    }
    files.sort();
    files
}

/// The tolerance of the published comparisons for this problem.
fn target(path: &Path) -> f64 {
    if path.to_string_lossy().contains("PerioBox") {
        1e-4
    } else {
        1e-8
    }
}

/// Violations of the Signorini-Coulomb conditions, with `u = W r + q` computed here from the
/// CSR arrays directly: `[impulse conditions (r_N >= 0, |r_T| <= mu r_N), velocity condition
/// (u_N >= 0), products (r_N u_N = 0, r_T . u_T + mu r_N |u_T| = 0) / (max|r| + max|u|)]`.
fn law_violations(p: &FrictionProblem, r: &[f64]) -> [f64; 3] {
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

#[test]
fn every_shared_problem_is_solved_to_the_published_tolerance() {
    let Some(dir) = shared_dir() else {
        eprintln!("skipped: ../shared/fclib is absent");
        return;
    };
    if !cfg!(feature = "hdf5") {
        eprintln!("note: built without the hdf5 feature: only the Siconos .dat problems are run");
    }
    let files = problem_files(&dir);
    assert!(!files.is_empty(), "no problem files in {}", dir.display());
    let mut failures = Vec::new();
    for path in &files {
        let (problem, _) = load_local(path, FormArg::Auto).expect("shared file reads");
        let tol = target(path);
        let mut best: Option<(f64, &'static str, Vec<f64>)> = None;
        for kind in [
            SolverKind::ProximalNewton,
            SolverKind::Nsgs,
            SolverKind::Newton,
        ] {
            let mut params = SolverParams::with_kind(kind);
            params.tolerance = tol;
            params.scaling = ErrorScaling::RelativeQ;
            if kind == SolverKind::Nsgs {
                params.max_iterations = 3000;
            }
            let Ok(report) = solve(&problem, &params, None) else {
                continue;
            };
            // The solver's own figure is the shared function's.
            let shared = problem.error(&report.r);
            assert!(
                (shared.relative_q - report.error.relative_q).abs()
                    <= 1e-12 * (1.0 + shared.relative_q),
                "{}: {} reports {:?}, shared function {:?}",
                path.display(),
                kind.name(),
                report.error,
                shared
            );
            if best.as_ref().is_none_or(|b| shared.relative_q < b.0) {
                best = Some((shared.relative_q, kind.name(), report.r.clone()));
            }
            if report.converged {
                break;
            }
        }
        let Some((error, solver, r)) = best else {
            failures.push(format!("{}: no solver ran", path.display()));
            continue;
        };
        let violation = law_violations(&problem, &r);
        let absolute = problem.error(&r).absolute;
        eprintln!(
            "{:<45} {:>5} contacts  {:<16} error {:.2e}  violations {:.1e} {:.1e} {:.1e} (|e| {:.1e})",
            path.file_name().unwrap().to_string_lossy(),
            problem.contact_count(),
            solver,
            error,
            violation[0],
            violation[1],
            violation[2],
            absolute
        );
        if error > tol {
            failures.push(format!(
                "{}: best error {error:.3e} > {tol:.0e}",
                path.display()
            ));
        }
        // r - e_a is a projection on the cone, so r is within |e| of it; the velocity and
        // product conditions follow within a few |e| (x (1 + mu), mu <= 1 here): allow 10 |e|,
        // plus round-off on the scale of the data.
        let allowed =
            10.0 * absolute + 1e-12 * problem.q.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        if violation.iter().any(|&v| v > allowed) {
            failures.push(format!(
                "{}: law violated by {violation:?} (allowed {allowed:.1e})",
                path.display()
            ));
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}
