//! Moreau-Jean time stepping for rigid bodies in frictional contact (NSCD).
//!
//! Dynamics `M dv = F dt + dr` in the sense of measures, discretised on `[t_i, t_i+1]` by the
//! theta-method (J.J. Moreau, "Unilateral contact and dry friction in finite freedom
//! dynamics", 1988; M. Jean, "The non-smooth contact dynamics method", CMAME 177, 1999):
//!
//! ```text
//! v_free  = v_i + h M^-1 F_theta
//! U       = H^T v,  W = H^T M^-1 H,  U = W R + H^T v_free
//! contacts within the alert distance, detected on q_i with g_TT = g_i + h (1 - theta) U_N,i,
//! or (LMGC90's way) on q_TT = q_i + h (1 - theta) v_i with g_TT = g(q_TT):
//!         Signorini-Coulomb on (U_N + s, U_T) and R        (NLGS, or Newton on the assembled W)
//!         s = max(g_TT, 0) / h             for e = 0 (LMGC90's IQS law: approach by at most the gap)
//!         s = e min(U_N,i, 0) if g_TT <= 0 for e > 0 (Newton's impact law; otherwise no contact)
//! v_i+1   = v_free + M^-1 H R
//! q_i+1   = q_i + h ((1 - theta) v_i + theta v_i+1)
//! ```
//!
//! followed, when enabled, by a position projection that removes the overlaps the
//! velocity-level scheme leaves after impacts (V. Acary, "Projected event-capturing
//! time-stepping schemes for nonsmooth mechanical systems with unilateral contact and
//! Coulomb's friction", CMAME 256, 2013): find `P >= 0` with `g_end + W_NN P >= 0 _|_ P`,
//! `q += M^-1 H_N P`, velocities unchanged.
//!
//! The step is a sequence of named stages on a [`World`] the caller owns, run by a
//! [`MoreauJean`] stepper that keeps its buffers between steps. The velocity problem is
//! solved by NLGS on the factorised operator, or, per [`StepParams::solver`]
//! ([`VelocitySolver`]), by the solvers of `xper_solver` (generalized Newton, ...) on the
//! problem assembled explicitly by [`assemble_problem`]; the stepper can hand that problem
//! out ([`MoreauJean::capture_next_problem`], [`MoreauJean::next_problem`]).

#![warn(missing_docs)]

mod assemble;
pub mod cell;
mod contact_solve;
#[cfg(feature = "dim2")]
#[path = "body2d.rs"]
mod dimension;
#[cfg(feature = "dim3")]
#[path = "body3d.rs"]
mod dimension;
mod domain;
pub mod events;
pub mod micro;
mod operator;
mod report;
mod select;
mod step;
mod world;

pub use assemble::assemble_problem;
pub use cell::{CellLoad, PeriodicCell};
pub use dimension::Local;
pub use operator::{CellCoupling, ContactRow, RigidContactOperator, RigidProblem, SolverBody};
pub use select::{contact_owner_body, is_movable, normal_shift, predicted_gap};
pub use step::{energy_blown_up, ContactSolve, MoreauJean, StageTimes, StepError, StepReport};
pub use world::{Detection, EnergyBudget, StepParams, VelocitySolver, World};
