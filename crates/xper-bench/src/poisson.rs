//! Figures of the pressure multigrid (`xper_poisson`) on one grid: convergence, work and
//! throughput.

use serde::{Deserialize, Serialize};
use std::time::Instant;
use xper_poisson::random::random;
use xper_poisson::{Boundary, GridShape, Multigrid, MultigridError, MultigridParams};

/// Measured figures of one grid and boundary (default [`MultigridParams`], tolerance `1e-8`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct BenchFigures {
    /// Cells along x and y.
    pub cells: [usize; 2],
    /// Grids in the hierarchy.
    pub levels: usize,
    /// Cells of the coarsest grid (solved directly).
    pub coarsest_cells: usize,
    /// Cycles to reduce the residual of a random rhs by `1e-8` from a zero initial guess.
    pub cycles: u32,
    /// Final relative residual.
    pub relative_residual: f64,
    /// Mean residual reduction per cycle.
    pub convergence_factor: f64,
    /// Residual reduction of the 20th cycle on a random error (the slowest component).
    pub asymptotic_factor: f64,
    /// Counted work units (crate documentation) per decade of residual reduction.
    pub work_units_per_decade: f64,
    /// Solve time over the time of one finest-grid sweep, per decade of residual reduction.
    pub timed_work_units_per_decade: f64,
    /// Red-black sweep throughput on the finest grid, best of 5 runs (cells/s).
    pub smoother_cells_per_second: f64,
    /// Wall time of the setup (`Multigrid::new`) (s).
    pub setup_seconds: f64,
    /// Wall time of the solve, best of 3 (s).
    pub solve_seconds: f64,
    /// Cells per second of the whole solve.
    pub solve_cells_per_second: f64,
}

/// Solves `Lap phi = rhs` with a random rhs (uniform in `[-1, 1)`, mean removed when
/// singular) on `n_x` x `n_y` cells of size `1 / max(n_x, n_y)` from `phi = 0`, with the
/// default parameters, and times the smoother and the solve.
///
/// # Panics
/// If the solver cannot be built (no cells, one-sided periodic axis) or does not converge.
pub fn run_benchmark(n_x: usize, n_y: usize, boundary: Boundary) -> BenchFigures {
    run_benchmark_with(n_x, n_y, boundary, MultigridParams::default())
}

/// [`run_benchmark`] with chosen parameters.
///
/// # Panics
/// As [`run_benchmark`].
pub fn run_benchmark_with(
    n_x: usize,
    n_y: usize,
    boundary: Boundary,
    params: MultigridParams,
) -> BenchFigures {
    let h = 1.0 / n_x.max(n_y) as f64;
    let shape = GridShape {
        nx: n_x,
        ny: n_y,
        hx: h,
        hy: h,
    };
    let start = Instant::now();
    let mut mg = Multigrid::new(shape, boundary, params).expect("a valid benchmark grid");
    let setup_seconds = start.elapsed().as_secs_f64();
    let mut state = 0x1234_5678;
    let rhs: Vec<f64> = (0..shape.cells()).map(|_| random(&mut state)).collect();
    let mut phi = vec![0.0; rhs.len()];
    let mut solve_seconds = f64::INFINITY;
    let mut info = None;
    for _ in 0..3 {
        phi.fill(0.0);
        let start = Instant::now();
        let result = mg.solve(&rhs, &mut phi);
        solve_seconds = solve_seconds.min(start.elapsed().as_secs_f64());
        info = Some(match result {
            Ok(info) | Err(MultigridError::NotConverged { info }) => info,
            Err(e) => panic!("benchmark solve failed: {e}"),
        });
    }
    let info = info.expect("three solves");
    let sweeps = (2e7 / shape.cells() as f64).clamp(5.0, 200.0) as u32;
    let sweep_seconds = (0..5)
        .map(|_| mg.time_sweeps(sweeps) / sweeps as f64)
        .fold(f64::INFINITY, f64::min);
    let decades =
        -(info.relative_residual * mg_rhs_norm(&rhs, &mg) / info.initial_residual).log10();
    let asymptotic_factor = mg.asymptotic_factor(20, &mut state);
    let coarsest = mg.level_shape(mg.levels() - 1).expect("the coarsest level");
    BenchFigures {
        cells: [n_x, n_y],
        levels: mg.levels(),
        coarsest_cells: coarsest.cells(),
        cycles: info.cycles,
        relative_residual: info.relative_residual,
        convergence_factor: info.convergence_factor,
        asymptotic_factor,
        work_units_per_decade: info.work_units / decades,
        timed_work_units_per_decade: solve_seconds / sweep_seconds / decades,
        smoother_cells_per_second: shape.cells() as f64 / sweep_seconds,
        setup_seconds,
        solve_seconds,
        solve_cells_per_second: shape.cells() as f64 / solve_seconds,
    }
}

/// `||rhs||_2` after the mean removal of singular problems.
fn mg_rhs_norm(rhs: &[f64], mg: &Multigrid) -> f64 {
    let mean = if mg.boundary().is_singular() {
        rhs.iter().sum::<f64>() / rhs.len() as f64
    } else {
        0.0
    };
    rhs.iter()
        .map(|r| (r - mean) * (r - mean))
        .sum::<f64>()
        .sqrt()
}
