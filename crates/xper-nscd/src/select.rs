//! Which contacts a step solves: the normal shift of the Signorini condition per interaction
//! law, and, in a distributed run, the process that owns a contact.

use crate::operator::SolverBody;
use crate::world::Detection;
use xper_bodies::BodySet;
use xper_math::Real;

/// Whether a body in this working state can be moved by contacts (at least one free degree
/// of freedom); immovable bodies (walls, fully driven bodies) are held by every process of a
/// distributed run.
#[inline]
pub fn is_movable(body: &SolverBody) -> bool {
    body.is_movable()
}

/// The body whose owner owns contact `(i, j)`: the first, or the second when the first is
/// immovable (a wall, held by every process).
#[inline]
pub fn contact_owner_body(bodies: &BodySet, i: usize, j: usize) -> usize {
    if bodies.is_movable(i) {
        i
    } else {
        j
    }
}

/// The gap after the explicit part of the motion, `g_TT`, of a contact whose detected gap is
/// `gap` and whose normal velocity at the beginning of the step is `un_begin`: predicted to
/// first order from a detection on `q_i`, measured by a detection on `q_TT`.
#[inline]
pub fn predicted_gap(
    detection: Detection,
    gap: Real,
    un_begin: Real,
    h: Real,
    theta: Real,
) -> Real {
    match detection {
        Detection::Begin => gap + h * (1.0 - theta) * un_begin,
        Detection::Predicted => gap,
    }
}

/// The normal shift `s` of a contact in the Signorini condition `U_N + s >= 0 _|_ R_N >= 0`,
/// or `None` when the contact stays out of the problem this step.
///
/// With `g_tt` the gap after the explicit part of the motion ([`predicted_gap`]):
/// - `e = 0` (LMGC90's inelastic quasi-shock law): every contact within the alert distance is in
///   the problem with `s = max(g_TT, 0) / h`, so bodies may approach by at most the open gap;
///   the gap then closes in two steps (to `(1 - theta) g_TT`, then exactly to 0) with neither
///   an impact nor an overlap, and a resting contact is simply `U_N >= 0`;
/// - `e > 0` (Newton's impact law): the contact enters the problem when `g_TT` closes (within
///   `closed`), with `s = e min(U_N,i, 0)`, so an impact restitutes `-e U_N,i` exactly.
#[inline]
pub fn normal_shift(
    g_tt: Real,
    un_begin: Real,
    h: Real,
    restitution: Real,
    closed: Real,
) -> Option<Real> {
    if restitution == 0.0 {
        Some(g_tt.max(0.0) / h)
    } else if g_tt <= closed {
        Some(restitution * un_begin.min(0.0))
    } else {
        None
    }
}
