//! The external suite: every problem of `../shared/fclib/` (written by Siconos and LMGC90,
//! never copied into this repository) is solved by xper's solvers. For each problem at least
//! one solver must reach the published tolerance (1e-8; 1e-4 for LMGC_100_PR_PerioBox) in the
//! `|q|` scaling of Acary, Bremond, Huber (2018), every solver's error must equal the one
//! shared function's, and the best solution must satisfy the Signorini-Coulomb conditions
//! (sign, cone, complementarity, maximal dissipation), checked by code independent of the
//! solvers and of the error measure (`xper_validation::suite::law_violations`).

use std::path::Path;
use xper_validation::suite::{suite_files, validate_problem};

#[test]
fn every_shared_problem_is_solved_to_the_published_tolerance() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/fclib");
    if !dir.is_dir() {
        eprintln!("skipped: ../shared/fclib is absent");
        return;
    }
    if !cfg!(feature = "hdf5") {
        eprintln!("note: built without the hdf5 feature: only the Siconos .dat problems are run");
    }
    let files = suite_files(&dir);
    assert!(
        files.len() >= 14,
        "too few problem files in {}",
        dir.display()
    );
    let mut failures = Vec::new();
    for path in &files {
        let case = validate_problem(path).expect("shared problem reads and solves");
        eprintln!(
            "{:<45} {:>5} contacts  {:<16} error {:.2e}  violations {:.1e} {:.1e} {:.1e} (allowed {:.1e})",
            case.problem, case.contacts, case.solver, case.error_q,
            case.violations[0], case.violations[1], case.violations[2], case.allowed
        );
        if !case.passed {
            failures.push(format!("{case:?}"));
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

/// The checker is not vacuous: a solution perturbed off the cone is caught.
#[test]
fn the_law_checker_catches_a_violation() {
    use xper_solver::{CsrMatrix, FrictionProblem};
    let w = CsrMatrix::from_dense_row_major(2, 2, &[1.0, 0.0, 0.0, 1.0]);
    let p = FrictionProblem::new(2, w, vec![-1.0, 0.0], vec![0.5]).unwrap();
    let ok = xper_validation::suite::law_violations(&p, &[1.0, 0.0]);
    assert!(ok.iter().all(|&v| v < 1e-15), "{ok:?}");
    let off_cone = xper_validation::suite::law_violations(&p, &[1.0, 0.7]);
    assert!(off_cone[0] > 0.19, "{off_cone:?}");
    let penetrating = xper_validation::suite::law_violations(&p, &[0.5, 0.0]);
    assert!(penetrating[1] > 0.49, "{penetrating:?}");
}
