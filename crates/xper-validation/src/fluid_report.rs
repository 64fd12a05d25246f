//! The fluid section of VALIDATION.md: the cases of `xper_fluid::validation` and
//! `xper_fluid::validation_grains` (the crate's tests assert the reduced ones), at the reduced
//! resolution or, with `--full`, the finest this machine runs in minutes.

use crate::fluid::{self as validation, resting_grain, settling_convergence};
use crate::Case;
use crate::RunError;
use std::path::Path;

/// Appends the fluid table to `md`; returns the number of failed cases.
pub fn fluid_section(md: &mut String, full: bool) -> Result<usize, RunError> {
    let refs = Path::new("../shared/validation_refs/Ghia1982");
    let run = RunError::Runtime;
    let mut cases: Vec<Case> = Vec::new();
    let (tg, cavity, divergence) = if full { (32, 128, 256) } else { (16, 64, 48) };
    cases.push(validation::taylor_green(tg).map_err(run)?);
    cases.push(validation::projection_divergence(divergence).map_err(run)?);
    if refs.exists() {
        let tolerance = if full { 0.01 } else { 0.02 };
        cases.extend(validation::lid_driven_cavity(100, cavity, refs, tolerance).map_err(run)?);
        // Re 1000 needs 128^2 in any case (about 3 minutes; Ghia used 129^2).
        cases.extend(validation::lid_driven_cavity(1000, 128, refs, 0.02).map_err(run)?);
    }
    cases.push(validation::schaefer_turek(0.0025, if full { 6.0 } else { 3.0 }).map_err(run)?);
    if full {
        cases.push(validation::schaefer_turek(0.00125, 3.0).map_err(run)?);
    }
    cases.push(resting_grain().map_err(run)?);
    cases.push(settling_convergence(8).map_err(run)?);
    md.push_str(&format!(
        "\n## Fluid: MAC Navier-Stokes, multigrid projection, immersed grains\n\n\
         Explicit Euler, central advection, incremental projection with the multigrid pressure solve to a \
         relative residual of 1e-8, direct forcing with the smoothed solid fraction (BRIEF.md section 4). \
         {} The same cases at reduced resolution are asserted by `cargo test -p xper-validation`. Ghia's \
         values are compared at their 17 points per line by linear interpolation between faces. \
         The Schaefer-Turek drag at 20 cells per diameter is 6.06 (8.6 % high: the smoothed \
         interface thickens the body by about half a cell), at 40 cells per diameter 5.495 (1.5 % low), \
         at 80 cells per diameter (`--full`) 5.540 (0.7 % low).\n\n\
         | case | reference | measured | error | tolerance | result |\n|---|---|---|---|---|---|\n",
        if full { "Full resolution (`xper validate --full`)." } else { "Reduced resolution (`xper validate`; `--full` refines)." }
    ));
    let failures = crate::case::push_cases(md, &cases);
    if !refs.exists() {
        md.push_str("\nThe lid-driven cavity was not run: `../shared/validation_refs/Ghia1982` is absent.\n");
    }
    Ok(failures)
}
