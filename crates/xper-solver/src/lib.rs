//! Frictional contact problems and their solvers, independent of any geometry.
//!
//! A contact problem (Siconos' and FCLib's "local" form) is
//!
//! ```text
//! U = W R + q,   for each contact a: (U_a + s_a e_n, R_a) satisfy Signorini-Coulomb with mu_a
//! ```
//!
//! with `U_a = (U_N, U_T)` and `R_a = (R_N, R_T)` in the contact frame (normal first),
//! `W` the Delassus operator and `s_a` a normal velocity shift (Newton's restitution target
//! in time stepping; zero for problems read from files). Solvers see `W` only through a
//! [`ContactOperator`]: an explicit matrix ([`DenseProblem`]) or the factorised form
//! `W = H^T M^-1 H` of rigid bodies, where applying an impulse updates two body velocities
//! so one contact update costs O(1).
//!
//! Assembled problems ([`FrictionProblem`], explicit CSR `W`, 2D or 3D, as read from
//! Siconos and LMGC90 files) have their own solvers behind one entry point, [`solve`]:
//! NSGS ([`mod@nsgs`]), the generalized Newton method on Alart-Curnier's function ([`mod@newton`]),
//! its proximal-point stabilisation for rank-deficient `W` ([`mod@proximal`]) and Lemke's method
//! on the LCP form of 2D problems ([`mod@lemke`]), all judged by the shared [`error_measure`].
#![warn(missing_docs)]

pub mod alart_curnier;
pub mod anderson;
mod cohesive;
mod contact_solve;
mod error;
mod frame;
pub mod lemke;
mod local;
pub mod newton;
mod nlgs;
pub mod nsgs;
mod operator;
mod outcome;
mod problem;
pub mod proximal;
mod solve;
mod sweeps;

pub use alart_curnier::LocalParams;
pub use anderson::{Acceleration, AndersonMixer};
pub use cohesive::{solve_one_cohesive_contact, CohesiveTerm, PreparedCohesiveContact};
pub use contact_solve::{ContactSolve, OneProcessSolve};
pub use error::{
    natural_map_error, natural_map_error_of, project_on_cone, ConvergenceNorms, NormAccumulator,
};
pub use frame::{dot, is_zero, ContactFrame, Frame2, Frame3, LocalVector};
pub use lemke::{lemke, LemkeParams};
pub use local::{solve_one_contact, solve_one_contact_factored, LocalFactors};
pub use newton::{newton, NewtonParams, RhoStrategy};
pub use nlgs::{
    check_contact_sizes, CheckPass, ConvergenceNorm, NlgsParams, NlgsSweeper, SolveError, SolveInfo,
};
pub use nsgs::{nsgs, NsgsParams};
pub use operator::{Block2, BlockOf, ContactOperator, DenseProblem, VectorOf};
pub use problem::{
    error_measure, project_on_cone_nd, CsrMatrix, FrictionProblem, ProblemError,
    ProblemErrorMeasure,
};
pub use proximal::{proximal_newton, ProximalParams};
pub use solve::{solve, solve_timed, ErrorScaling, SolveReport, SolverKind, SolverParams};
pub use sweeps::{nlgs, nlgs_with_cohesion, sweep_until_converged, OneProcess, SweepExchange};
