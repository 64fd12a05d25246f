//! The Delassus operator of rigid bodies in factorised form `W = H^T M^-1 H`.
//!
//! The operator keeps one working velocity per body; applying an impulse to a contact updates
//! the velocities of its two bodies, and a local velocity is read from them, so a contact
//! update costs O(1) whatever the number of contacts (LMGC90's rigid NLGS). Per contact it
//! stores what the two updates need and nothing else.

pub use crate::dimension::SolverBody;
use crate::dimension::{generalized_impulses, local_of, push_bodies, relative_velocity, Local};
use xper_bodies::BodySet;
pub use xper_geometry::ContactRow;
use xper_math::buffer::refill;
use xper_math::{Real, Tensor, Vector, DIM, DOFS};
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
    /// In a periodic cell, how its rows move with the cell; `None` otherwise.
    pub cell: Option<CellCoupling>,
}

/// A periodic cell's part in the operator (see `crate::cell`): bodies other than walls move
/// with the cell's homogeneous flow `L (x - o)` besides their own velocity (the one the
/// operator holds), and the second body of a row may be an image `x_j + H n`, so a row's local
/// velocity is `U = G^T v + F^T (L d)` with `d` the difference of the two bodies' positions
/// in the flow (`x_j + H n - x_i`, the branch vector, between two such bodies; a wall's term
/// is left out: walls do not follow the flow). The components of `L` under an imposed stress
/// are unknowns of the problem, with an inertia, that the rows' impulses push like a body's
/// velocity: `L_kl += I_kl^-1 p_k d_l` for the impulse `p` on the second body (M. Parrinello,
/// A. Rahman, "Polymorphic transitions in single crystals: a new molecular dynamics method",
/// J. Appl. Phys. 52:7182, 1981, for the cell as a degree of freedom).
#[derive(Clone, Debug, Default)]
pub struct CellCoupling {
    /// Per row, `d`: the second body's position in the flow less the first's (m).
    pub spans: Vec<Vector>,
    /// Per row, `F^T (L d)` when every component of `L` is imposed (`L` at the end of the
    /// step, m/s): constant during the solve; empty when some component is under stress.
    pub offsets: Vec<Local>,
    /// The cell's velocity gradient `L` (1/s): the working one, the end of the step's.
    pub gradient: Tensor,
    /// `L` at the beginning of the step (1/s).
    pub begin: Tensor,
    /// Inverse inertia of each component of `L` (1 / (kg m^2) per m), 0 where it is imposed.
    pub inv_inertia: Tensor,
    /// Whether some component of `L` is under stress (an unknown).
    pub free: bool,
}

impl CellCoupling {
    /// The flow's relative velocity at row `a`, `F^T (L d)`, with the working `L`.
    #[inline(always)]
    fn offset(&self, row: &ContactRow, a: usize) -> Local {
        if self.free {
            local_of(row, &(self.gradient * self.spans[a]))
        } else {
            self.offsets[a]
        }
    }

    /// Adds the row's local impulse `d` to the free components of `L`.
    #[inline(always)]
    fn push(&mut self, row: &ContactRow, a: usize, d: Local) {
        if self.free {
            let p = row.world_impulse(d);
            let s = self.spans[a];
            self.gradient += self.inv_inertia.component_mul(&(p * s.transpose()));
        }
    }
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

    /// Fills the Delassus blocks of the rows from the inverse masses of the bodies (and, in
    /// a periodic cell, the inverse inertia of the free components of its gradient: `W_ab +=
    /// sum_kl I_kl^-1 (e_a)_k (e_b)_k d_l^2` over the frame's axes `e`).
    pub fn refresh_blocks(&mut self) {
        let bodies = &self.bodies;
        for row in &mut self.rows {
            row.refresh_block(|b| bodies[b].inv_mass);
        }
        let Some(cell) = self.cell.as_ref().filter(|c| c.free) else {
            return;
        };
        for (row, s) in self.rows.iter_mut().zip(&cell.spans) {
            if s.iter().all(|&x| x == 0.0) {
                continue;
            }
            let axes: [Vector; DIM] = std::array::from_fn(|a| {
                row.world_impulse(std::array::from_fn(|k| (k == a) as u8 as Real))
            });
            // w_k = sum_l I_kl^-1 d_l^2: the cell's inverse inertia seen along axis k.
            let w = Vector::from_fn(|k, _| {
                (0..DIM)
                    .map(|l| cell.inv_inertia[(k, l)] * s[l] * s[l])
                    .sum()
            });
            let mut block = row.full_block();
            // The upper triangle, mirrored: the block stays exactly symmetric.
            for (a, ea) in axes.iter().enumerate() {
                for (b, eb) in axes.iter().enumerate().skip(a) {
                    let added = ea.component_mul(&w).dot(eb);
                    block[a * DIM + b] += added;
                    if b != a {
                        block[b * DIM + a] += added;
                    }
                }
            }
            row.set_full_block(block);
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
        let mut u = relative_velocity(row, &vi, &vj);
        if let Some(cell) = &self.cell {
            add(&mut u, local_of(row, &(cell.begin * cell.spans[a])));
        }
        u
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
        let mut u = relative_velocity(row, vi, vj);
        if let Some(cell) = &self.cell {
            add(&mut u, cell.offset(row, a));
        }
        u
    }

    #[inline(always)]
    fn apply_impulse(&mut self, a: usize, d: Local) {
        push_bodies(&mut self.bodies, &self.rows[a], d);
        if let Some(cell) = &mut self.cell {
            cell.push(&self.rows[a], a, d);
        }
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
        let mut u = relative_velocity(row, &vi, &vj);
        if let Some(cell) = &self.cell {
            add(&mut u, cell.offset(row, a));
        }
        let d = solve(&block, u);
        if d.iter().any(|&x| x != 0.0) {
            push_bodies(&mut self.bodies, row, d);
            if let Some(cell) = &mut self.cell {
                cell.push(row, a, d);
            }
        }
        (block, d)
    }
}

/// `u += v`.
#[inline(always)]
fn add(u: &mut Local, v: Local) {
    for (x, y) in u.iter_mut().zip(v) {
        *x += y;
    }
}
