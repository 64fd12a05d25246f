//! Geometric multigrid for the pressure Poisson equation of a staggered (MAC) flow solver.
//!
//! # Equation and discretisation
//!
//! On a rectangle covered by `nx` x `ny` uniform cells of size `hx` x `hy`, with the unknown at
//! cell centres stored row-major (`phi[i + nx * j]`, `i` along x, `j` along y, `j = 0` the
//! bottom row), [`Multigrid::solve`] solves
//!
//! ```text
//! (phi[i-1,j] - 2 phi[i,j] + phi[i+1,j]) / hx^2 + (phi[i,j-1] - 2 phi[i,j] + phi[i,j+1]) / hy^2 = rhs[i,j]
//! ```
//!
//! the 5-point Laplacian, with one homogeneous condition per side, expressed through a ghost
//! cell beyond the face: Neumann `d phi / dn = 0` (ghost = interior), Dirichlet `phi = 0` on the
//! face (ghost = -interior) or periodic (ghost = the cell on the opposite side). With no
//! Dirichlet side the operator is singular (its kernel is the constants): the mean of `rhs` is
//! removed before solving (reported as [`MultigridInfo::removed_mean`]) and the zero-mean solution
//! is returned; the caller need not pass a zero-mean rhs.
//!
//! The operator is the usual one (negative semi-definite): for a pressure correction
//! `Lap phi = (rho / dt) div u*` the rhs is passed as is.
//!
//! # Method
//!
//! A hierarchy of uniform cell-centred grids over the same rectangle: a direction with `n >= 2`
//! cells is coarsened to `ceil(n / 2)` cells. For even `n` the grids are nested (two fine cells
//! per coarse cell); for odd `n` the coarse grid is still uniform but not nested, and the
//! transfers below are computed from the actual cell positions. A direction whose spacing is
//! more than `sqrt 2` times the smallest one is not coarsened (semi-coarsening towards square
//! cells), so every level stays nearly isotropic and a point smoother suffices.
//!
//! - smoother: red-black Gauss-Seidel (optionally over-relaxed, red-black SOR), the boundary
//!   rules folded into the diagonal so that boundary cells are relaxed exactly;
//! - restriction: the volume average of the residual over each coarse cell (for nested grids
//!   the 4-cell average), which conserves its integral, so coarse singular problems stay
//!   compatible;
//! - prolongation: bilinear interpolation between coarse cell centres (for nested grids the
//!   weights 9/16, 3/16, 3/16, 1/16), with the boundary rules applied to the coarse ghosts;
//! - coarse operators: the same 5-point discretisation on the coarse grid;
//! - coarsest grid (at most [`MultigridParams::coarsest_cells`] cells): a dense Cholesky
//!   factorisation computed once, the singular case regularised by a rank-one term `c 1 1^T`
//!   which leaves compatible right-hand sides with their zero-mean solution;
//! - cycle: V, W or F ([`CycleType`]), repeated until `||rhs - Lap phi||_2 <= tol ||rhs||_2`.
//!
//! The last smoothing sweep of a level is fused with the residual computation (and with the
//! restriction, or with the residual norm on the finest level), and the red and black
//! half-sweeps are pipelined row by row, so one sweep streams the arrays once.
//!
//! # Work units
//!
//! [`MultigridInfo::work_units`] counts passes over the cells, each scaled by the cells of its level
//! over those of the finest grid: a smoothing sweep counts 1, a residual evaluation 1 (also when
//! fused with a sweep), a restriction 0.5, a prolongation with correction 0.5; on the finest
//! grid, copying the rhs and initial guess in counts 1, copying the answer out 0.5 (1 with the
//! mean removal of singular problems); the coarsest solve counts `2 N_c^2 / (8 N)` (its flops
//! over those of a fine sweep). A V(2,1) cycle is thus about `5 * 4/3 + 1` units.
//! The benchmark (`xper_bench::poisson`) also reports a timed figure: the solve time over the
//! time of one fine sweep.
//!
//! # Defaults and measured figures
//!
//! V(2,1) with red-black SOR `omega = 1.2` minimised the work per decade among V(1,1), V(2,1),
//! V(1,2), V(2,2), F(1,1), F(2,1) and `omega` in 1..1.35 while keeping the asymptotic factor
//! below 0.1 (V(1,1) reaches 0.10 to 0.12). On 512^2 and 1024^2, all-Neumann, doubly periodic
//! and Neumann with a Dirichlet top (`crates/xper-bench/examples/poisson_bench.rs`, one core): 6 cycles to 1e-8
//! from a random rhs, mean factor 0.036, asymptotic factor 0.056 to 0.072, 5.6 to 5.7 counted
//! (4.2 to 5.1 timed) work units per decade, about 8e8 smoothed cells per second, solves of
//! 12 ms (512^2) and 55 ms (1024^2). Elongated and odd grids (64 x 640, 82 x 440, 80 x 320,
//! 100 x 37, 127 x 255) take 5 or 6 cycles; strips one to four cells wide become 1D, where the
//! factor degrades to 0.2 to 0.3.
//!
//! # Sources
//!
//! - A. Brandt, "Multi-level adaptive solutions to boundary-value problems", Math. Comp. 31
//!   (1977) 333-390: the multigrid cycle, coarse-grid correction, work units.
//! - U. Trottenberg, C. W. Oosterlee, A. Schueller, "Multigrid", Academic Press, 2001: red-black
//!   Gauss-Seidel and its smoothing analysis, cell-centred transfer operators, V, W and F
//!   cycles (chapters 2 to 4), semi-coarsening for anisotropic problems (chapter 5),
//!   convergence factors (chapters 3 and 4).
//! - I. Yavneh, "On red-black SOR smoothing in multigrid", SIAM J. Sci. Comput. 17 (1996)
//!   180-192: over-relaxation of the red-black smoother.
#![warn(missing_docs)]

mod coarse;
mod level;
mod multigrid;
mod operator;
pub mod random;
mod strip_hierarchy;
mod strip_level;
pub mod strip_multigrid;
pub mod strips;
mod transfer;

pub use multigrid::Multigrid;
pub use strip_multigrid::StripMultigrid;
pub use strips::{CountingLinks, OneStrip, RowExchange, RowLinks, StripLayout};

use serde::{Deserialize, Serialize};
use std::fmt;

/// The homogeneous condition on one side of the rectangle.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum PoissonSide {
    /// `d phi / dn = 0` on the face (ghost = interior).
    Neumann,
    /// `phi = 0` on the face (ghost = -interior).
    Dirichlet,
    /// The opposite side's cells are the neighbours; both sides of the axis must be periodic.
    Periodic,
}

/// The conditions on the four sides.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub struct Boundary {
    /// Side `x = 0`.
    pub left: PoissonSide,
    /// Side `x = nx hx`.
    pub right: PoissonSide,
    /// Side `y = 0`.
    pub bottom: PoissonSide,
    /// Side `y = ny hy`.
    pub top: PoissonSide,
}

impl Boundary {
    /// The same condition on every side.
    pub fn all(condition: PoissonSide) -> Self {
        Boundary {
            left: condition,
            right: condition,
            bottom: condition,
            top: condition,
        }
    }

    /// Neumann on the sides and bottom, Dirichlet on top: the pressure of a box open at the
    /// top.
    pub fn open_top() -> Self {
        Boundary {
            top: PoissonSide::Dirichlet,
            ..Boundary::all(PoissonSide::Neumann)
        }
    }

    /// True when no side is Dirichlet: the operator's kernel is the constants.
    pub fn is_singular(&self) -> bool {
        [self.left, self.right, self.bottom, self.top]
            .iter()
            .all(|&c| c != PoissonSide::Dirichlet)
    }

    /// The conditions of axis 0 (left, right) or 1 (bottom, top).
    pub fn axis(&self, axis: usize) -> [PoissonSide; 2] {
        if axis == 0 {
            [self.left, self.right]
        } else {
            [self.bottom, self.top]
        }
    }
}

/// The finest grid: `nx` x `ny` cells of size `hx` x `hy`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct GridShape {
    /// Cells along x.
    pub nx: usize,
    /// Cells along y.
    pub ny: usize,
    /// Cell size along x.
    pub hx: f64,
    /// Cell size along y.
    pub hy: f64,
}

impl GridShape {
    /// `nx x ny` square cells over a width `width` (cells of side `width / nx`).
    pub fn square_cells(nx: usize, ny: usize, width: f64) -> Self {
        let h = width / nx as f64;
        GridShape {
            nx,
            ny,
            hx: h,
            hy: h,
        }
    }

    /// Number of cells, `nx ny`.
    pub fn cells(&self) -> usize {
        self.nx * self.ny
    }
}

/// The multigrid cycle (Trottenberg et al. section 2.4).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum CycleType {
    /// One coarse-grid correction per level.
    V,
    /// Two coarse-grid corrections per level.
    W,
    /// An F-cycle on the coarse level followed by a V-cycle.
    F,
}

/// Parameters of the solver.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct MultigridParams {
    /// Stop when `||rhs - Lap phi||_2 <= relative_tolerance ||rhs||_2` (the rhs after the mean
    /// removal of singular problems). Default `1e-8`.
    pub relative_tolerance: f64,
    /// Largest number of cycles. Default 50.
    pub max_cycles: u32,
    /// Red-black sweeps before the coarse-grid correction. Default 2.
    pub pre_smoothing: u32,
    /// Red-black sweeps after the coarse-grid correction. Default 1.
    pub post_smoothing: u32,
    /// The cycle. Default V.
    pub cycle: CycleType,
    /// Over-relaxation `omega` of the red-black smoother, in (0, 2); 1 is Gauss-Seidel.
    /// Default 1.2 (Yavneh 1996 for the idea; the value measured best with V(2,1)).
    pub omega: f64,
    /// Coarsening stops at a grid with at most this many cells, solved by a dense Cholesky
    /// factorisation (at most 4096). Default 64.
    pub coarsest_cells: usize,
}

impl Default for MultigridParams {
    fn default() -> Self {
        MultigridParams {
            relative_tolerance: 1e-8,
            max_cycles: 50,
            pre_smoothing: 2,
            post_smoothing: 1,
            cycle: CycleType::V,
            omega: 1.2,
            coarsest_cells: 64,
        }
    }
}

/// What a solve did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct MultigridInfo {
    /// Cycles performed.
    pub cycles: u32,
    /// Final `||rhs - Lap phi||_2 / ||rhs||_2` (0 when the rhs is zero).
    pub relative_residual: f64,
    /// `||rhs - Lap phi||_2` of the initial guess.
    pub initial_residual: f64,
    /// Geometric mean of the residual reduction per cycle,
    /// `(final / initial)^(1 / cycles)` (0 without cycles).
    pub convergence_factor: f64,
    /// Work in finest-grid smoothing sweeps (see the crate documentation for the convention).
    pub work_units: f64,
    /// Mean of the rhs removed before solving a singular problem (0 otherwise); a large value
    /// relative to the rhs reveals a compatibility defect of the caller's data.
    pub removed_mean: f64,
}

/// A solve that failed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum MultigridError {
    /// The tolerance was not reached in `max_cycles` cycles; `phi` holds the last iterate.
    NotConverged {
        /// The state at the last cycle.
        info: MultigridInfo,
    },
    /// A residual became NaN or infinite (cycle 0: the rhs or the initial guess).
    NonFinite {
        /// The cycle after which it was detected.
        cycle: u32,
    },
    /// `rhs` or `phi` does not have `nx ny` entries.
    SizeMismatch {
        /// `nx ny`.
        expected: usize,
        /// The length received.
        got: usize,
    },
}

impl fmt::Display for MultigridError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            MultigridError::NotConverged { info } => write!(
                f,
                "multigrid did not converge in {} cycles (relative residual {:.3e})",
                info.cycles, info.relative_residual
            ),
            MultigridError::NonFinite { cycle } => {
                write!(f, "non-finite residual after multigrid cycle {cycle}")
            }
            MultigridError::SizeMismatch { expected, got } => {
                write!(f, "expected {expected} values (nx ny), got {got}")
            }
        }
    }
}

impl std::error::Error for MultigridError {}

/// Why a solver cannot be built.
#[derive(Clone, Debug, PartialEq)]
pub enum SetupError {
    /// `nx` or `ny` is zero, or `nx ny` overflows.
    NoCells {
        /// Cells along x.
        nx: usize,
        /// Cells along y.
        ny: usize,
    },
    /// `hx` or `hy` is not a positive finite number.
    BadSpacing {
        /// Cell size along x.
        hx: f64,
        /// Cell size along y.
        hy: f64,
    },
    /// One side of an axis is periodic and the other is not.
    OneSidedPeriodic {
        /// 0 for x (left, right), 1 for y (bottom, top).
        axis: usize,
    },
    /// The coarsest operator could not be factorised (not expected: it is positive definite
    /// by construction).
    CoarseFactorisation {
        /// Unknowns of the coarsest grid.
        cells: usize,
    },
    /// A parameter is out of its range.
    BadParameter {
        /// The field of [`MultigridParams`].
        name: &'static str,
        /// Its value.
        value: f64,
    },
    /// The strip layout does not cut the rows into strips of at least `min_rows` rows, or
    /// names no such strip.
    BadStrips {
        /// The row cuts.
        starts: Vec<usize>,
        /// Rows of the grid.
        ny: usize,
        /// The strip asked for.
        strip: usize,
        /// The fewest rows a strip may have: the ghost rows of the cycle asked for.
        min_rows: usize,
    },
}

impl fmt::Display for SetupError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SetupError::NoCells { nx, ny } => {
                write!(
                    f,
                    "the grid needs at least one cell each way, got {nx} x {ny}"
                )
            }
            SetupError::BadSpacing { hx, hy } => {
                write!(f, "cell sizes must be positive and finite, got {hx} x {hy}")
            }
            SetupError::OneSidedPeriodic { axis } => write!(
                f,
                "axis {} is periodic on one side only",
                ["x (left, right)", "y (bottom, top)"][*axis]
            ),
            SetupError::CoarseFactorisation { cells } => {
                write!(
                    f,
                    "the coarsest operator ({cells} cells) is not positive definite"
                )
            }
            SetupError::BadParameter { name, value } => {
                write!(f, "multigrid parameter {name} = {value} is out of range")
            }
            SetupError::BadStrips {
                starts,
                ny,
                strip,
                min_rows,
            } => write!(
                f,
                "strip {strip} of the row cuts {starts:?}: the cuts must rise from 0 to {ny} \
                 by at least {min_rows} rows and the strip must exist"
            ),
        }
    }
}

impl std::error::Error for SetupError {}
