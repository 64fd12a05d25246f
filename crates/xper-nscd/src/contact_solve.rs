//! The contact solve of a rigid step shared with other processes: a
//! [`xper_solver::ContactSolve`] on the [`RigidContactOperator`] (a domain decomposition
//! implements it; `MoreauJean::step_with` calls it).

use crate::operator::RigidContactOperator;

pub use xper_solver::ContactSolve;

/// A shorter borrow of an optional shared solver (trait-object lifetimes shorten only at a
/// coercion).
pub(crate) fn reborrow<'b>(
    s: &'b mut Option<&mut dyn ContactSolve<RigidContactOperator>>,
) -> Option<&'b mut dyn ContactSolve<RigidContactOperator>> {
    match s {
        Some(s) => Some(&mut **s),
        None => None,
    }
}
