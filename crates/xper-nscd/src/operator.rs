//! The Delassus operator of rigid bodies in factorised form `W = H^T M^-1 H`.
//!
//! The operator keeps one working velocity per body; applying an impulse to a contact updates
//! the velocities of its two bodies, and a local velocity is read from them, so a contact
//! update costs O(1) whatever the number of contacts (LMGC90's rigid NLGS). Per contact it
//! stores what the two updates need and nothing else.

pub use crate::dimension::SolverBody;
use crate::dimension::{generalized_impulses, push_bodies, relative_velocity, Local};
use xper_bodies::BodySet;
pub use xper_geometry::ContactRow;
use xper_math::buffer::refill;
use xper_math::{Real, DOFS};
use xper_solver::{BlockOf, ContactOperator};

#[cfg(feature = "dim2")]
type Frame = xper_solver::Frame2;
#[cfg(feature = "dim3")]
type Frame = xper_solver::Frame3;

/// A velocity problem in factorised form: the bodies at their free velocities, the active
/// contact rows, friction coefficients, normal shifts and warm start. What a step solves,
/// without the geometry; a domain decomposition splits it among processes.
#[derive(Clone, Debug, Default)]
pub struct RigidProblem {
    /// Working state per body (free velocity, inverse masses).
    pub bodies: Vec<SolverBody>,
    /// One row per active contact.
    pub rows: Vec<ContactRow>,
    /// Friction coefficient per row.
    pub mu: Vec<Real>,
    /// Normal shift per row (see [`crate::normal_shift`]).
    pub shift: Vec<Real>,
    /// Warm-start impulse per row.
    pub impulses: Vec<Local>,
}

/// Rigid-body contact operator: the body working states and the contact rows.
#[derive(Clone, Debug, Default)]
pub struct RigidContactOperator {
    /// Working state per body.
    pub bodies: Vec<SolverBody>,
    /// One row per contact of the problem.
    pub rows: Vec<ContactRow>,
}

impl RigidContactOperator {
    /// Loads the inverse masses of `set` and the given velocities.
    pub fn load_bodies(&mut self, set: &BodySet, velocity: impl Fn(usize) -> [Real; DOFS]) {
        refill(
            &mut self.bodies,
            (0..set.len()).map(|b| SolverBody {
                velocity: velocity(b),
                inv_mass: set.inv_mass(b),
            }),
        );
    }

    /// Fills the Delassus blocks of the rows from the inverse masses of the bodies.
    pub fn refresh_blocks(&mut self) {
        let bodies = &self.bodies;
        for row in &mut self.rows {
            row.refresh_block(|b| bodies[b].inv_mass);
        }
    }

    /// The local velocity `U = (U_N, U_T)` of row `a` for the velocities of the bodies of `set`
    /// instead of the working ones (e.g. those at the beginning of the step, which a body
    /// set holds until the step's update).
    #[inline(always)]
    pub fn local_velocity_at(&self, a: usize, set: &BodySet) -> Local {
        let row = &self.rows[a];
        let vi = set.generalized_velocity(row.bodies[0] as usize);
        let vj = set.generalized_velocity(row.bodies[1] as usize);
        relative_velocity(row, &vi, &vj)
    }

    /// Generalised impulses `(on body i, on body j)` of a local impulse `r` at a row.
    #[inline(always)]
    pub fn generalized_impulses(row: &ContactRow, r: Local) -> ([Real; DOFS], [Real; DOFS]) {
        generalized_impulses(row, r)
    }
}

impl ContactOperator for RigidContactOperator {
    type Frame = Frame;
    #[inline(always)]
    fn contact_count(&self) -> usize {
        self.rows.len()
    }

    #[inline(always)]
    fn diagonal_block(&self, a: usize) -> BlockOf<Self> {
        self.rows[a].full_block()
    }

    #[inline(always)]
    fn local_velocity(&self, a: usize) -> Local {
        let row = &self.rows[a];
        let vi = &self.bodies[row.bodies[0] as usize].velocity;
        let vj = &self.bodies[row.bodies[1] as usize].velocity;
        relative_velocity(row, vi, vj)
    }

    #[inline(always)]
    fn apply_impulse(&mut self, a: usize, d: Local) {
        push_bodies(&mut self.bodies, &self.rows[a], d);
    }

    /// The row and the two bodies' velocities are read once for the local velocity and the
    /// update.
    #[inline(always)]
    fn update_contact(
        &mut self,
        a: usize,
        solve: impl FnOnce(&BlockOf<Self>, Local) -> Local,
    ) -> (BlockOf<Self>, Local) {
        let row = &self.rows[a];
        let vi = self.bodies[row.bodies[0] as usize].velocity;
        let vj = self.bodies[row.bodies[1] as usize].velocity;
        let block = row.full_block();
        let d = solve(&block, relative_velocity(row, &vi, &vj));
        if d.iter().any(|&x| x != 0.0) {
            push_bodies(&mut self.bodies, row, d);
        }
        (block, d)
    }
}
