//! Figures of the multigrid solver on one grid (for `xper bench --fluid` and BENCHMARKS.md).

use crate::{Boundary, GridShape, Multigrid, MultigridParams};
use serde::{Deserialize, Serialize};
use std::time::Instant;

/// Measured figures of one grid and boundary.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct BenchFigures {
    /// Cells along x and y.
    pub cells: [usize; 2],
    /// Grids in the hierarchy.
    pub levels: usize,
    /// Cells of the coarsest (directly solved) grid.
    pub coarsest_cells: usize,
    /// V-cycles to reduce the residual of a random right-hand side by 1e-8 from zero.
    pub cycles: u32,
    /// Mean residual reduction per cycle.
    pub convergence_factor: f64,
    /// Smoother sweeps (finest-grid equivalents) per decade of residual reduction.
    pub work_units_per_decade: f64,
    /// Red-black Gauss-Seidel throughput on the finest grid, best of 3 runs (cells/s).
    pub smoother_cells_per_second: f64,
    /// Wall time of the solve (s).
    pub solve_seconds: f64,
    /// Cells per second of the whole solve.
    pub solve_cells_per_second: f64,
}

/// Solves a random zero-mean problem on `nx x ny` unit-spaced cells and times the smoother.
pub fn run_benchmark(nx: usize, ny: usize, boundary: Boundary) -> Result<BenchFigures, String> {
    let shape = GridShape {
        nx,
        ny,
        hx: 1.0 / nx as f64,
        hy: 1.0 / nx as f64,
    };
    let params = MultigridParams {
        max_cycles: 100,
        ..MultigridParams::default()
    };
    let mut mg = Multigrid::new(shape, boundary, params).map_err(|e| e.to_string())?;
    let mut seed = 0x9e37_79b9_7f4a_7c15_u64;
    let rhs: Vec<f64> = (0..nx * ny)
        .map(|_| {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        })
        .collect();
    let mut phi = vec![0.0; nx * ny];
    let start = Instant::now();
    let info = mg.solve(&rhs, &mut phi).map_err(|e| e.to_string())?;
    let solve_seconds = start.elapsed().as_secs_f64();
    // From a zero guess the initial residual is ||f||: decades = -log10(relative residual).
    let decades = -info.relative_residual.max(1e-300).log10();
    let sweeps = 20;
    let mut best = f64::INFINITY;
    for _ in 0..3 {
        let start = Instant::now();
        for _ in 0..sweeps {
            mg.levels[0].smooth(&mg.boundary);
        }
        best = best.min(start.elapsed().as_secs_f64());
    }
    Ok(BenchFigures {
        cells: [nx, ny],
        levels: mg.levels(),
        coarsest_cells: mg.coarsest_cells(),
        cycles: info.cycles,
        convergence_factor: info.convergence_factor,
        work_units_per_decade: info.work_units / decades,
        smoother_cells_per_second: (sweeps * nx * ny) as f64 / best,
        solve_seconds,
        solve_cells_per_second: (nx * ny) as f64 / solve_seconds,
    })
}
