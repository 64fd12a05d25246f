//! What one process holds of a velocity problem: the contacts it owns, the bodies it owns and
//! copies of the other bodies those contacts touch.
//!
//! A contact belongs to the owner of its first body, or of its second when the first is
//! immovable (a wall, whose copies are identical everywhere and never exchanged). In a
//! distributed run each process detects its own contacts among its bodies and their shadow
//! copies; [`split_problem`] builds the same local problem from a whole one, which is how the
//! decomposition is tested against the undivided solve.

use xper_nscd::{RigidContactOperator, RigidProblem, SolverBody};
use xper_parallel::InterfaceMap;

/// One process's part of a [`RigidProblem`].
#[derive(Clone, Debug, Default)]
pub struct LocalProblem {
    /// Local bodies (free velocities, unsplit inverse masses) and rows with local indices.
    pub problem: RigidProblem,
    /// Global index of each local body.
    pub global_ids: Vec<u64>,
    /// Owner rank of each local body.
    pub owners: Vec<u32>,
    /// Global index of each local row.
    pub global_rows: Vec<u32>,
}

impl LocalProblem {
    /// Whether a body's velocity can change (some inverse mass is non-zero): only those are
    /// shared and exchanged.
    pub fn movable(body: &SolverBody) -> bool {
        xper_nscd::is_movable(body)
    }

    /// The operator of this process: masses of shared bodies split by `interface`, blocks
    /// recomputed, zero impulses applied.
    pub fn operator(&self, interface: &InterfaceMap) -> RigidContactOperator {
        let mut op = RigidContactOperator {
            bodies: self.problem.bodies.clone(),
            rows: self.problem.rows.clone(),
            cell: None,
        };
        split_masses(interface, &mut op.bodies);
        op.refresh_blocks();
        op
    }

    /// Which local bodies take part in the interface exchange.
    pub fn shared(&self) -> Vec<bool> {
        self.problem.bodies.iter().map(Self::movable).collect()
    }
}

/// The owner of a contact between bodies `i` and `j`.
pub fn contact_owner(bodies: &[SolverBody], owners: &[u32], i: usize, j: usize) -> u32 {
    if LocalProblem::movable(&bodies[i]) {
        owners[i]
    } else {
        owners[j]
    }
}

/// The part of `whole` held by `rank` when body `b` is owned by `owners[b]`.
pub fn split_problem(whole: &RigidProblem, owners: &[u32], rank: u32) -> LocalProblem {
    let mut local_of = vec![u32::MAX; whole.bodies.len()];
    let mut local = LocalProblem::default();
    let mut take = |b: usize, local: &mut LocalProblem| {
        if local_of[b] == u32::MAX {
            local_of[b] = local.global_ids.len() as u32;
            local.global_ids.push(b as u64);
            local.owners.push(owners[b]);
            local.problem.bodies.push(whole.bodies[b]);
        }
        local_of[b]
    };
    for (b, &owner) in owners.iter().enumerate() {
        if owner == rank {
            take(b, &mut local);
        }
    }
    for (a, row) in whole.rows.iter().enumerate() {
        let [i, j] = [row.bodies[0] as usize, row.bodies[1] as usize];
        if contact_owner(&whole.bodies, owners, i, j) != rank {
            continue;
        }
        let mut row = *row;
        row.bodies = [take(i, &mut local), take(j, &mut local)];
        local.problem.rows.push(row);
        local.problem.mu.push(whole.mu[a]);
        local.problem.shift.push(whole.shift[a]);
        local.problem.impulses.push(whole.impulses[a]);
        local.global_rows.push(a as u32);
    }
    local
}

/// Multiplies the inverse masses of the shared bodies by their multiplicity.
fn split_masses(interface: &InterfaceMap, bodies: &mut [SolverBody]) {
    for (body, &m) in bodies.iter_mut().zip(&interface.multiplicity) {
        if m > 1 {
            body.scale_inverse_mass(m as f64);
        }
    }
}
