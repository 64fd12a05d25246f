//! Processes and what they exchange, independent of the physics and of the dimension.
//!
//! - [`Communicator`]: a group of processes, as threads of this process
//!   ([`ThreadCommunicator`], for tests) or over Open MPI (`MpiCommunicator`, cargo feature
//!   `mpi`); reductions in rank order, so results do not depend on timing.
//! - [`nscdd`]: the non-smooth contact domain decomposition of Visseq, Martin, Iceta, Azema,
//!   Dureisseix and Alart (Comput. Mech. 49, 2012, 709): Gauss-Seidel inside each process on
//!   any [`xper_solver::ContactOperator`] whose bodies carry velocities
//!   ([`nscdd::BodyVelocities`]), the bodies shared by several processes glued by averaging
//!   after every sweep. The engines implement its traits for their operators (rigid bodies in
//!   `xper-nscd`, finite elements in `xper-fracture`); `xper-domain` partitions space and
//!   builds each process's problem.
#![warn(missing_docs)]

pub mod comm;
pub mod nscdd;

#[cfg(feature = "mpi")]
pub use comm::mpi::MpiCommunicator;
pub use comm::threads::{run_on_threads, ThreadCommunicator};
pub use comm::{exchange_by_rank, CommStats, Communicator, SingleProcess};
pub use nscdd::interface::InterfaceMap;
pub use nscdd::{distributed_nlgs, permuted, solve_with_split_masses, BodyVelocities, SplitMasses};

/// What one process holds and did, for the run's load summary.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RankLoad {
    /// Movable bodies owned.
    pub bodies: usize,
    /// Shadow copies of other processes' bodies.
    pub shadows: usize,
    /// Contacts owned (those of the last step).
    pub contacts: usize,
    /// Bodies shared with other processes in the last solve.
    pub interface_bodies: usize,
    /// Bodies received by migration since the start.
    pub migrated_in: u64,
    /// Fluid cells held (runs with a fluid).
    pub cells: usize,
    /// Times the fluid's blocks of rows were cut again (runs with a fluid).
    pub recuts: u64,
}
