//! The fluid validation cases at reduced resolution (the full ones run in `xper validate --full`).

use std::path::PathBuf;
use xper_validation::fluid::{self as validation, Case};

fn check(case: Case) {
    println!(
        "{}: {} (error {:.3e}, tolerance {:.1e})",
        case.name, case.measured, case.error, case.tolerance
    );
    assert!(case.passed(), "{case:?}");
}

fn ghia() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/validation_refs/Ghia1982")
}

#[test]
fn taylor_green_converges_at_second_order() {
    check(validation::taylor_green(16).unwrap());
}

#[test]
fn projection_leaves_divergence_below_the_pressure_tolerance() {
    check(validation::projection_divergence(48).unwrap());
}

/// 64 x 64 cells reproduce Ghia's Re 100 centreline velocities within 0.02 lid velocities
/// (the second-order error at this resolution; 128 cells halve it, see VALIDATION.md).
#[test]
fn lid_driven_cavity_re100_matches_ghia() {
    if !ghia().exists() {
        eprintln!("skipped: {} not found", ghia().display());
        return;
    }
    for case in validation::lid_driven_cavity(100, 64, &ghia(), 0.02).unwrap() {
        check(case);
    }
}

#[test]
fn resting_grain_stays_at_rest() {
    check(xper_validation::fluid::resting_grain().unwrap());
}

#[test]
fn settling_velocity_converges_under_refinement() {
    check(xper_validation::fluid::settling_convergence(8).unwrap());
}

/// 40 cells per diameter to t = 3 s (the drag is steady to 0.2 % by then); 20 cells per
/// diameter give 6.06, outside the 3 % band (see VALIDATION.md).
#[test]
fn schaefer_turek_drag_within_three_percent() {
    check(validation::schaefer_turek(0.0025, 3.0).unwrap());
}
