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
