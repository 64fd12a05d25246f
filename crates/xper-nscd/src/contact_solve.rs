//! The interface of a contact solve shared with other processes (a domain decomposition
//! implements it; `MoreauJean::step_with` calls it).

use crate::operator::RigidContactOperator;
use xper_math::Real;
use xper_solver::{NlgsParams, SolveError, SolveInfo};

/// A solver of the step's velocity and projection problems shared with other processes (a
/// domain decomposition): [`crate::MoreauJean::step_with`] hands it the problem of the contacts this
/// process owns, on its copies of their bodies, instead of solving it alone.
pub trait ContactSolve {
    /// Solves the problem of `op` (zero impulses applied, `impulses` the warm start on entry
    /// and the solution on exit) as [`xper_solver::nlgs`] does, together with the other
    /// processes; every process gets the same outcome.
    fn solve(
        &mut self,
        op: &mut RigidContactOperator,
        mu: &[Real],
        shift: &[Real],
        impulses: &mut [[Real; 2]],
        params: &NlgsParams,
    ) -> Result<SolveInfo, SolveError>;
    /// The largest `value` over the processes, for decisions they must all take alike.
    fn agree_max(&mut self, value: Real) -> Real;
}

/// A shorter borrow of an optional shared solver (trait-object lifetimes shorten only at a
/// coercion).
pub(crate) fn reborrow<'b>(
    s: &'b mut Option<&mut dyn ContactSolve>,
) -> Option<&'b mut dyn ContactSolve> {
    match s {
        Some(s) => Some(&mut **s),
        None => None,
    }
}
