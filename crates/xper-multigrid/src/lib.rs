//! Geometric multigrid for the pressure Poisson equation of a staggered (MAC) fluid solver:
//!
//! ```text
//! (phi_{i+1,j} - 2 phi_{i,j} + phi_{i-1,j}) / hx^2 + (phi_{i,j+1} - 2 phi_{i,j} + phi_{i,j-1}) / hy^2 = f_{i,j}
//! ```
//!
//! on `nx x ny` cells with unknowns at cell centres (row-major `phi[i + nx j]`), a homogeneous
//! condition per side (Neumann, Dirichlet on the face, or periodic). V-cycles (Brandt, Math.
//! Comp. 31 (1977) 333) with red-black Gauss-Seidel smoothing, the cell-centred transfers of
//! Trottenberg, Oosterlee and Schueller, "Multigrid" (Academic Press 2001), section 2.8.4 (the
//! four-cell average to restrict, bilinear interpolation to prolong: orders 1 + 2 > 2 as needed
//! for a second-order operator) and rediscretised coarse operators; the grid is halved while
//! both sizes are even and at least 4, and the coarsest level is solved exactly by a sparse
//! Cholesky factorisation (faer) made once. Without a Dirichlet side the problem is singular:
//! the right-hand side is projected onto zero mean (the removed mean is reported) and the
//! solution returned has zero mean.

mod coarsest;
mod level;

pub mod bench;

use coarsest::CoarsestSolver;
use level::Level;
use serde::{Deserialize, Serialize};

/// Homogeneous condition on one side.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum SideCondition {
    /// Zero normal derivative at the face.
    Neumann,
    /// Zero value at the face.
    Dirichlet,
    /// Periodic with the opposite side (which must be periodic too).
    Periodic,
}

/// The conditions on the four sides.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Boundary {
    /// Side `x = 0`.
    pub left: SideCondition,
    /// Side `x = nx hx`.
    pub right: SideCondition,
    /// Side `y = 0`.
    pub bottom: SideCondition,
    /// Side `y = ny hy`.
    pub top: SideCondition,
}

impl Boundary {
    /// The same condition on every side.
    pub fn all(c: SideCondition) -> Self {
        Boundary {
            left: c,
            right: c,
            bottom: c,
            top: c,
        }
    }

    /// Whether no side fixes the level of the solution (the operator is singular).
    pub fn is_singular(&self) -> bool {
        [self.left, self.right, self.bottom, self.top]
            .iter()
            .all(|&c| c != SideCondition::Dirichlet)
    }
}

/// Cells and their sizes.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct GridShape {
    /// Cells along x.
    pub nx: usize,
    /// Cells along y.
    pub ny: usize,
    /// Cell width (m).
    pub hx: f64,
    /// Cell height (m).
    pub hy: f64,
}

/// Tuning of the solve.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct MultigridParams {
    /// Stop when `||f - A phi||_2 <= relative_tolerance ||f||_2`.
    pub relative_tolerance: f64,
    /// Largest number of V-cycles.
    pub max_cycles: u32,
    /// Gauss-Seidel sweeps before the coarse-grid correction.
    pub pre_smoothing: u32,
    /// Gauss-Seidel sweeps after it.
    pub post_smoothing: u32,
}

impl Default for MultigridParams {
    /// Relative tolerance 1e-8, 50 cycles, V(2, 2) (V(2, 1) reaches only 0.14 per cycle).
    fn default() -> Self {
        MultigridParams {
            relative_tolerance: 1e-8,
            max_cycles: 50,
            pre_smoothing: 2,
            post_smoothing: 2,
        }
    }
}

/// Outcome of a solve.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct SolveInfo {
    /// V-cycles done.
    pub cycles: u32,
    /// `||f - A phi|| / ||f||` at the end.
    pub relative_residual: f64,
    /// `||f - A phi||` of the initial guess.
    pub initial_residual: f64,
    /// Geometric mean of the residual reduction per cycle.
    pub convergence_factor: f64,
    /// Smoother sweeps counted in finest-grid equivalents (a coarse sweep counts its size).
    pub work_units: f64,
    /// Mean removed from `f` to make a singular problem solvable (0 otherwise).
    pub removed_mean: f64,
}

/// A solve that failed.
#[derive(Clone, Debug, PartialEq)]
pub enum SolveError {
    /// The tolerance was not reached within `max_cycles`.
    NotConverged {
        /// Where it stopped.
        info: SolveInfo,
    },
    /// The iterate became NaN or infinite (a non-finite right-hand side).
    NonFinite {
        /// Cycle at which it was seen.
        cycle: u32,
    },
    /// An array does not have `nx * ny` entries.
    SizeMismatch {
        /// Expected length.
        expected: usize,
        /// Actual length.
        got: usize,
    },
}

impl std::fmt::Display for SolveError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            SolveError::NotConverged { info } => write!(
                f,
                "multigrid did not converge in {} cycles (relative residual {:.3e}, factor {:.3})",
                info.cycles, info.relative_residual, info.convergence_factor
            ),
            SolveError::NonFinite { cycle } => {
                write!(f, "non-finite values at multigrid cycle {cycle}")
            }
            SolveError::SizeMismatch { expected, got } => {
                write!(f, "array of {got} values, the grid has {expected} cells")
            }
        }
    }
}

impl std::error::Error for SolveError {}

/// A grid or parameters refused at set-up.
#[derive(Clone, Debug, PartialEq)]
pub struct SetupError(pub String);

impl std::fmt::Display for SetupError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "multigrid set-up: {}", self.0)
    }
}

impl std::error::Error for SetupError {}

/// The multigrid solver: level hierarchy and coarsest factorisation, built once.
pub struct Multigrid {
    shape: GridShape,
    boundary: Boundary,
    params: MultigridParams,
    levels: Vec<Level>,
    coarsest: CoarsestSolver,
}

impl Multigrid {
    /// Builds the hierarchy for `shape` with `boundary`.
    pub fn new(
        shape: GridShape,
        boundary: Boundary,
        params: MultigridParams,
    ) -> Result<Self, SetupError> {
        if shape.nx == 0 || shape.ny == 0 {
            return Err(SetupError(format!(
                "the grid has {} x {} cells",
                shape.nx, shape.ny
            )));
        }
        if !(shape.hx > 0.0 && shape.hy > 0.0 && shape.hx.is_finite() && shape.hy.is_finite()) {
            return Err(SetupError(format!(
                "cell sizes must be positive, got {} x {}",
                shape.hx, shape.hy
            )));
        }
        let periodic = |c: SideCondition| c == SideCondition::Periodic;
        if periodic(boundary.left) != periodic(boundary.right)
            || periodic(boundary.bottom) != periodic(boundary.top)
        {
            return Err(SetupError(
                "a periodic side needs a periodic opposite side".into(),
            ));
        }
        if params.relative_tolerance.is_nan()
            || params.relative_tolerance <= 0.0
            || params.max_cycles == 0
            || params.pre_smoothing + params.post_smoothing == 0
        {
            return Err(SetupError(format!("invalid parameters {params:?}")));
        }
        let (mut nx, mut ny, mut hx, mut hy) = (shape.nx, shape.ny, shape.hx, shape.hy);
        let mut levels = vec![Level::new(nx, ny, hx, hy)];
        while nx % 2 == 0 && ny % 2 == 0 && nx >= 4 && ny >= 4 {
            (nx, ny, hx, hy) = (nx / 2, ny / 2, 2.0 * hx, 2.0 * hy);
            levels.push(Level::new(nx, ny, hx, hy));
        }
        let coarsest = CoarsestSolver::new(levels.last().expect("at least one level"), &boundary)?;
        Ok(Multigrid {
            shape,
            boundary,
            params,
            levels,
            coarsest,
        })
    }

    /// Number of grids in the hierarchy.
    pub fn levels(&self) -> usize {
        self.levels.len()
    }

    /// Cells of the coarsest grid (solved directly).
    pub fn coarsest_cells(&self) -> usize {
        self.levels.last().map_or(0, Level::cells)
    }

    fn check_len(&self, len: usize) -> Result<(), SolveError> {
        let expected = self.shape.nx * self.shape.ny;
        if len != expected {
            return Err(SolveError::SizeMismatch { expected, got: len });
        }
        Ok(())
    }

    /// `out = A phi` with the boundary conditions (row-major arrays of `nx * ny`).
    pub fn apply_laplacian(&self, phi: &[f64], out: &mut [f64]) {
        let fine = &self.levels[0];
        let mut scratch = Level::new(fine.nx, fine.ny, self.shape.hx, self.shape.hy);
        self.load(&mut scratch.phi, phi);
        let _ = scratch.residual(&self.boundary);
        for j in 0..fine.ny {
            for i in 0..fine.nx {
                out[i + fine.nx * j] = -scratch.res[scratch.at(i, j)];
            }
        }
    }

    /// `||f - A phi||_2`.
    pub fn residual_norm(&self, rhs: &[f64], phi: &[f64]) -> f64 {
        let mut a = vec![0.0; rhs.len()];
        self.apply_laplacian(phi, &mut a);
        rhs.iter()
            .zip(&a)
            .map(|(f, a)| (f - a) * (f - a))
            .sum::<f64>()
            .sqrt()
    }

    fn load(&self, padded: &mut [f64], values: &[f64]) {
        let nx = self.shape.nx;
        for (j, row) in values.chunks_exact(nx).enumerate() {
            let start = 1 + (nx + 2) * (j + 1);
            padded[start..start + nx].copy_from_slice(row);
        }
    }

    /// Solves `A phi = f`; `phi` holds the initial guess (warm start) on entry.
    pub fn solve(&mut self, rhs: &[f64], phi: &mut [f64]) -> Result<SolveInfo, SolveError> {
        self.check_len(rhs.len())?;
        self.check_len(phi.len())?;
        let singular = self.boundary.is_singular();
        let n = rhs.len() as f64;
        let mut info = SolveInfo::default();
        let mut fine = std::mem::take(&mut self.levels[0].rhs);
        self.load(&mut fine, rhs);
        self.levels[0].rhs = fine;
        if singular {
            info.removed_mean = rhs.iter().sum::<f64>() / n;
            let level = &mut self.levels[0];
            for j in 0..level.ny {
                for i in 0..level.nx {
                    let k = level.at(i, j);
                    level.rhs[k] -= info.removed_mean;
                }
            }
        }
        let rhs_norm = {
            let l = &self.levels[0];
            let mut sum = 0.0;
            for j in 0..l.ny {
                for i in 0..l.nx {
                    sum += l.rhs[l.at(i, j)].powi(2);
                }
            }
            sum.sqrt()
        };
        let mut p = std::mem::take(&mut self.levels[0].phi);
        self.load(&mut p, phi);
        self.levels[0].phi = p;
        let mut residual = self.levels[0].residual(&self.boundary).sqrt();
        info.initial_residual = residual;
        let target = self.params.relative_tolerance * rhs_norm;
        while residual > target && rhs_norm > 0.0 {
            if info.cycles == self.params.max_cycles {
                info.relative_residual = residual / rhs_norm;
                self.finish(phi, singular);
                return Err(SolveError::NotConverged { info });
            }
            info.work_units += self.cycle(0);
            info.cycles += 1;
            residual = self.levels[0].residual(&self.boundary).sqrt();
            if !residual.is_finite() {
                return Err(SolveError::NonFinite { cycle: info.cycles });
            }
        }
        if rhs_norm == 0.0 {
            self.levels[0].phi.iter_mut().for_each(|v| *v = 0.0);
            residual = 0.0;
        }
        info.relative_residual = if rhs_norm > 0.0 {
            residual / rhs_norm
        } else {
            0.0
        };
        info.convergence_factor = if info.cycles > 0 && info.initial_residual > 0.0 {
            (residual / info.initial_residual).powf(1.0 / info.cycles as f64)
        } else {
            0.0
        };
        self.finish(phi, singular);
        Ok(info)
    }

    /// Copies the finest iterate out (zero mean when singular).
    fn finish(&self, phi: &mut [f64], singular: bool) {
        let l = &self.levels[0];
        for j in 0..l.ny {
            for i in 0..l.nx {
                phi[i + l.nx * j] = l.phi[l.at(i, j)];
            }
        }
        if singular {
            let mean = phi.iter().sum::<f64>() / phi.len() as f64;
            phi.iter_mut().for_each(|v| *v -= mean);
        }
    }

    /// One V-cycle from level `l` (its `rhs` and initial `phi` set); returns its work units.
    fn cycle(&mut self, l: usize) -> f64 {
        let fine_cells = self.levels[0].cells() as f64;
        if l + 1 == self.levels.len() {
            self.coarsest.solve(&mut self.levels[l], &self.boundary);
            return 0.0;
        }
        let weight = self.levels[l].cells() as f64 / fine_cells;
        for _ in 0..self.params.pre_smoothing {
            self.levels[l].smooth(&self.boundary);
        }
        self.levels[l].residual(&self.boundary);
        let (upper, lower) = self.levels.split_at_mut(l + 1);
        upper[l].restrict_into(&mut lower[0]);
        lower[0].phi.iter_mut().for_each(|v| *v = 0.0);
        let mut work = self.cycle(l + 1);
        let (upper, lower) = self.levels.split_at_mut(l + 1);
        upper[l].prolong_add(&mut lower[0], &self.boundary);
        for _ in 0..self.params.post_smoothing {
            self.levels[l].smooth(&self.boundary);
        }
        work += weight * (self.params.pre_smoothing + self.params.post_smoothing) as f64;
        work
    }
}
