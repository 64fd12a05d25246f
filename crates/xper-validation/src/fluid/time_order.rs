//! The order of the fluid's time integration, measured alone: the Taylor-Green vortex on one
//! grid stepped with `M`, `2M` and `4M` steps, each compared with the same grid stepped with
//! `64 M` steps of the three-stage Runge-Kutta scheme. The grid is the same in every run, so
//! the difference is the time error only (the space error, common to all, cancels).

use super::{taylor_green_grid, taylor_green_state, Case};
use xper_fluid::{FluidBoundary, FluidParams, FluidSolver, FluidState, TimeScheme};
use xper_math::{Real, DIM};

/// Kinematic viscosity of the time study (m^2/s): the vortex decays by `e^-0.4` over it.
const NU: Real = 0.1;
/// Length of the run (s).
const END: Real = 2.0;

/// The Taylor-Green vortex on an `n x n` periodic grid of `[0, 2 pi]^2` after `END` s in
/// `steps` equal steps of `scheme`, the pressure solved to a relative residual of 1e-13 (so
/// that the solve's error stays far below the time errors measured).
fn run(n: usize, steps: usize, scheme: TimeScheme) -> Result<FluidState, String> {
    let grid = taylor_green_grid(n);
    let params = FluidParams {
        pressure_tolerance: 1e-13,
        pressure_max_cycles: 200,
        time_scheme: scheme,
        ..FluidParams::new(1.0, NU, FluidBoundary::periodic())
    };
    let mut solver = FluidSolver::new(grid, &params).map_err(|e| e.to_string())?;
    let mut state = taylor_green_state(grid, &params);
    let dt = END / steps as Real;
    for _ in 0..steps {
        solver
            .step(&params, &mut state, dt, &[])
            .map_err(|e| e.to_string())?;
    }
    Ok(state)
}

/// Largest difference of the face velocities of two states of one grid.
fn largest_difference(a: &FluidState, b: &FluidState) -> Real {
    let g = &a.grid;
    let mut largest: Real = 0.0;
    for d in 0..DIM {
        for j in 0..g.ny as isize {
            for i in 0..g.nx as isize {
                let k = g.index(i, j);
                largest = largest.max((a.velocity[d][k] - b.velocity[d][k]).abs());
            }
        }
    }
    largest
}

/// The time errors of `scheme` with `steps`, `2 steps` and `4 steps` on an `n x n` grid (the
/// largest face-velocity difference from the reference run, in units of the initial
/// amplitude, 1 m/s) and the observed order `log2(e1 / e3) / 2`.
pub fn taylor_green_time_errors(
    n: usize,
    steps: usize,
    scheme: TimeScheme,
) -> Result<([Real; 3], Real), String> {
    let reference = run(n, 64 * steps, TimeScheme::Rk3)?;
    let mut errors = [0.0; 3];
    for (k, e) in errors.iter_mut().enumerate() {
        *e = largest_difference(&run(n, steps << k, scheme)?, &reference);
    }
    let order = (errors[0] / errors[2]).log2() / 2.0;
    Ok((errors, order))
}

/// The observed order in time of explicit Euler (1) and of the Runge-Kutta scheme (at least
/// 2: Le and Moin's result for the velocity with the last stage's pressure), on `n x n` cells
/// with `steps`, `2 steps` and `4 steps` over 2 s. Tolerance 0.15 on the order: the spread of
/// the pre-asymptotic range at the step counts the tests use.
pub fn taylor_green_in_time(n: usize, steps: usize) -> Result<Vec<Case>, String> {
    let mut cases = Vec::new();
    for (scheme, name, expected) in [
        (TimeScheme::Euler, "explicit Euler", 1.0),
        (TimeScheme::Rk3, "three-stage Runge-Kutta (rk3)", 2.0),
    ] {
        let (errors, order) = taylor_green_time_errors(n, steps, scheme)?;
        let error = if scheme == TimeScheme::Euler {
            (order - expected).abs()
        } else {
            (expected - order).max(0.0)
        };
        cases.push(Case {
            name: format!(
                "Taylor-Green vortex, order in time of {name} ({n} x {n} cells, {steps}, {}, {} \
                 steps over {END} s, nu = {NU} m^2/s)",
                2 * steps,
                4 * steps
            ),
            reference: format!(
                "{} (against the same grid with {} rk3 steps)",
                if scheme == TimeScheme::Euler {
                    "1"
                } else {
                    "at least 2"
                },
                64 * steps
            ),
            measured: format!(
                "errors {:.2e}, {:.2e}, {:.2e} m/s; order {order:.3}",
                errors[0], errors[1], errors[2]
            ),
            error,
            tolerance: 0.15,
        });
    }
    Ok(cases)
}
