//! The Delassus operator of rigid bodies in factorised form `W = H^T M^-1 H`.
//!
//! The operator keeps one working velocity per body; applying an impulse to a contact updates
//! the velocities of its two bodies, and a local velocity is read from them, so a contact
//! update costs O(1) whatever the number of contacts (LMGC90's rigid NLGS). Per contact it
//! stores what the two updates need and nothing else.

use xper_bodies::BodySet;
pub use xper_geometry::ContactRow;
use xper_math::buffer::refill;
use xper_math::{tangent, Real, Vector, DOFS};
use xper_solver::{Block2, ContactOperator, Frame2};

/// Working state of one body: generalised velocity and inverse masses per degree of freedom.
#[derive(Clone, Copy, Debug, Default)]
#[repr(C, align(16))]
pub struct SolverBody {
    /// Generalised velocity (vx, vy, w).
    pub velocity: [Real; DOFS],
    /// Inverse mass per degree of freedom (0 where imposed or infinite).
    pub inv_mass: [Real; DOFS],
}

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
    pub impulses: Vec<[Real; 2]>,
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

    /// The local velocity `(U_N, U_T)` of row `a` for the velocities of the bodies of `set`
    /// instead of the working ones (e.g. those at the beginning of the step, which a body
    /// set holds until the step's update).
    #[inline(always)]
    pub fn local_velocity_at(&self, a: usize, set: &BodySet) -> [Real; 2] {
        let row = &self.rows[a];
        let vi = set.generalized_velocity(row.bodies[0] as usize);
        let vj = set.generalized_velocity(row.bodies[1] as usize);
        relative_velocity(row, &vi, &vj)
    }

    /// Generalised impulses `(on body i, on body j)` of a local impulse `r` at a row.
    #[inline(always)]
    pub fn generalized_impulses(row: &ContactRow, r: [Real; 2]) -> ([Real; DOFS], [Real; DOFS]) {
        let n = Vector::new(row.normal[0], row.normal[1]);
        let p = n * r[0] + tangent(&n) * r[1];
        let a = &row.arms;
        (
            [-p.x, -p.y, -(a[0] * r[0] + a[1] * r[1])],
            [p.x, p.y, a[2] * r[0] + a[3] * r[1]],
        )
    }
}

impl ContactOperator for RigidContactOperator {
    type Frame = Frame2;
    #[inline(always)]
    fn contact_count(&self) -> usize {
        self.rows.len()
    }

    #[inline(always)]
    fn diagonal_block(&self, a: usize) -> Block2 {
        self.rows[a].full_block()
    }

    #[inline(always)]
    fn local_velocity(&self, a: usize) -> [Real; 2] {
        let row = &self.rows[a];
        let vi = &self.bodies[row.bodies[0] as usize].velocity;
        let vj = &self.bodies[row.bodies[1] as usize].velocity;
        relative_velocity(row, vi, vj)
    }

    #[inline(always)]
    fn apply_impulse(&mut self, a: usize, d: [Real; 2]) {
        push_bodies(&mut self.bodies, &self.rows[a], d);
    }

    /// The row and the two bodies' velocities are read once for the local velocity and the
    /// update.
    #[inline(always)]
    fn update_contact(
        &mut self,
        a: usize,
        solve: impl FnOnce(&Block2, [Real; 2]) -> [Real; 2],
    ) -> (Block2, [Real; 2]) {
        let row = &self.rows[a];
        let vi = self.bodies[row.bodies[0] as usize].velocity;
        let vj = self.bodies[row.bodies[1] as usize].velocity;
        let block = row.full_block();
        let d = solve(&block, relative_velocity(row, &vi, &vj));
        if d[0] != 0.0 || d[1] != 0.0 {
            push_bodies(&mut self.bodies, row, d);
        }
        (block, d)
    }
}

/// The local velocity `(U_N, U_T)` of `row` from the generalised velocities of its bodies.
#[inline(always)]
fn relative_velocity(row: &ContactRow, vi: &[Real; DOFS], vj: &[Real; DOFS]) -> [Real; 2] {
    let [nx, ny] = row.normal;
    let (dx, dy) = (vj[0] - vi[0], vj[1] - vi[1]);
    let a = &row.arms;
    [
        nx * dx + ny * dy + vj[2] * a[2] - vi[2] * a[0],
        -ny * dx + nx * dy + vj[2] * a[3] - vi[2] * a[1],
    ]
}

/// Adds the local impulse `d` of `row` to the velocities of its two bodies (`-d` on the first).
#[inline(always)]
fn push_bodies(bodies: &mut [SolverBody], row: &ContactRow, d: [Real; 2]) {
    let [nx, ny] = row.normal;
    let (px, py) = (nx * d[0] - ny * d[1], ny * d[0] + nx * d[1]);
    let a = row.arms;
    let bi = &mut bodies[row.bodies[0] as usize];
    bi.velocity[0] -= bi.inv_mass[0] * px;
    bi.velocity[1] -= bi.inv_mass[1] * py;
    bi.velocity[2] -= bi.inv_mass[2] * (a[0] * d[0] + a[1] * d[1]);
    let bj = &mut bodies[row.bodies[1] as usize];
    bj.velocity[0] += bj.inv_mass[0] * px;
    bj.velocity[1] += bj.inv_mass[1] * py;
    bj.velocity[2] += bj.inv_mass[2] * (a[2] * d[0] + a[3] * d[1]);
}
