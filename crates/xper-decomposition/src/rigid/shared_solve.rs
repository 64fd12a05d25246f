//! The contact solve of a distributed step: what [`xper_nscd::MoreauJean::step_with`] calls
//! instead of NLGS on one process.
//!
//! For each problem of the step (velocities, then positions when the projection runs) the
//! interface is built collectively ([`InterfaceMap::build`]), the shared bodies' masses are split
//! among their copies, [`crate::distributed_nlgs`] solves, and the operator gets its own masses and
//! Delassus blocks back (copied, not recomputed, so they keep their bits).

use crate::comm::Communicator;
use crate::nscdd::interface::InterfaceMap;
use crate::nscdd::solve_with_split_masses;
use xper_math::Real;
use xper_nscd::{Local, RigidContactOperator};
use xper_solver::{CohesiveTerm, ContactSolve, NlgsParams, SolveError, SolveInfo};

/// [`ContactSolve`] by NSCDD over a communicator, for a process whose local bodies (those of
/// the operator, in order) have the global ids `ids`, the owners `owners` and may move
/// (`movable`).
pub struct SharedNlgs<'c, C: Communicator + ?Sized> {
    /// The processes solving together.
    pub comm: &'c C,
    /// Global id of each local body.
    pub ids: Vec<u64>,
    /// Owner rank of each local body.
    pub owners: Vec<u32>,
    /// Whether each local body has a free degree of freedom.
    pub movable: Vec<bool>,
    /// Interface bodies of the last solve (the largest over the step's solves).
    pub shared_bodies: usize,
    /// The ranks holding copies of this process's bodies or owning its copies (the
    /// partition's neighbours); `None`: any rank.
    pub neighbours: Option<Vec<usize>>,
}

impl<'c, C: Communicator + ?Sized> SharedNlgs<'c, C> {
    /// A solver with no bodies yet (filled before each step).
    pub fn new(comm: &'c C) -> Self {
        SharedNlgs {
            comm,
            ids: Vec::new(),
            owners: Vec::new(),
            movable: Vec::new(),
            shared_bodies: 0,
            neighbours: None,
        }
    }
}

impl<C: Communicator + ?Sized> ContactSolve<RigidContactOperator> for SharedNlgs<'_, C> {
    fn solve(
        &mut self,
        op: &mut RigidContactOperator,
        mu: &[Real],
        shift: &[Real],
        cohesion: &[CohesiveTerm],
        impulses: &mut [Local],
        params: &NlgsParams,
    ) -> Result<SolveInfo, SolveError> {
        let me = self.comm.rank() as u32;
        // A copy takes part in the interface when it is this process's body or one of its
        // contacts touches it.
        let mut shared: Vec<bool> = (0..op.bodies.len())
            .map(|b| self.movable[b] && self.owners[b] == me)
            .collect();
        for row in &op.rows {
            for &b in &row.bodies {
                shared[b as usize] |= self.movable[b as usize];
            }
        }
        let among = self.neighbours.as_deref();
        let interface = InterfaceMap::build(self.comm, &self.ids, &self.owners, &shared, among);
        self.shared_bodies = interface.shared_count();
        solve_with_split_masses(
            self.comm, op, &interface, mu, shift, cohesion, impulses, params,
        )
    }

    fn sum(&mut self, values: &mut [f64]) {
        self.comm.all_reduce_sum(values);
    }

    fn max(&mut self, value: Real) -> Real {
        let mut v = [value];
        self.comm.all_reduce_max(&mut v);
        v[0]
    }
}
