//! Incompressible viscous flow around rigid grains (BRIEF.md section 4):
//!
//! ```text
//! (1 - eta) rho_f du/dt + (1 - eta)[rho_f u.grad u - div sigma - f_ext] = rho_f eta (u_s - u)/dt,
//! div u = 0,    sigma = -p I + mu (grad u + grad u^T)
//! ```
//!
//! discretised on a staggered Marker-And-Cell grid (Harlow and Welch 1965, [`grid`]) with an
//! explicit Euler (or three-stage Runge-Kutta) momentum predictor ([`momentum`]), a direct
//! forcing towards the grains' rigid velocities on Lagrangian markers ([`markers`], the
//! default) or weighted by their solid fraction `eta` ([`immersed`], the paper's, written
//! above) and an incremental
//! pressure-correction projection whose Poisson equation is solved by geometric multigrid
//! ([`projection`], `xper_poisson`). [`FluidSolver::step`] runs the stages in that order; the
//! force of the fluid on each grain comes out of the step for the contact dynamics to use.
//!
//! On several processes the grid is cut into blocks of rows: [`FluidSolver::step_with`] runs
//! the same stages on a block, with what crosses blocks (halo rows, sums, the pressure solve)
//! behind [`BlockLinks`] ([`blocks`]).
//!
//! The grid is 2D (the `DIM` of `xper_math`); the stencils are written per component with
//! neighbour offsets, so a 3D grid adds a third offset rather than a second copy.

pub mod blocks;
pub mod boundary;
pub mod grid;
pub mod immersed;
pub mod lubrication;
pub mod markers;
pub mod momentum;
pub mod params;
pub mod projection;
pub mod solver;

pub use blocks::{BlockLinks, WholeGrid};
pub use boundary::{FluidBoundary, InflowProfile, SideCondition};
pub use grid::MacGrid;
pub use immersed::{HydrodynamicForce, ImmersedDisk, InnerMomentum, SolidIndicator};
pub use lubrication::Lubrication;
pub use markers::MarkerForcingParams;
pub use params::Forcing;
pub use solver::{FluidError, FluidParams, FluidSolver, FluidState, FluidStepReport, TimeScheme};
pub mod coupling;
pub use coupling::{CoupledError, CoupledReport, CoupledState, CoupledStepper};
