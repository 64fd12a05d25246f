//! Distributed runs by domain decomposition.
//!
//! Space is partitioned among processes ([`partition::Bisection`], recursive coordinate
//! bisection); each process solves the contacts it owns by Gauss-Seidel on its copies of the
//! bodies, and the bodies touched by contacts of several processes (the interface,
//! [`InterfaceMap`]) have their mass split among the copies and their velocities
//! averaged after each sweep ([`nscdd::distributed_nlgs`]): the non-smooth contact domain
//! decomposition of Visseq, Martin, Iceta, Azema, Dureisseix and Alart, "Dense granular
//! dynamics analysis by a domain decomposition approach", Comput. Mech. 49 (2012) 709, which
//! follows Renouf, Dubois and Alart, J. Comput. Appl. Math. 168 (2004) 375.
//!
//! Grains in a fluid ([`fluid::DistributedFluid`]) split the grid into blocks of rows with
//! halo exchange and solve the pressure by a multigrid over the blocks
//! ([`xper_poisson::StripMultigrid`]).
//!
//! Processes talk through the [`Communicator`] trait: [`ThreadCommunicator`] runs the ranks as
//! threads of one process (tests, no MPI needed), `MpiCommunicator` (cargo feature `mpi`) over
//! Open MPI. The algorithms are tested on the first and run unchanged on the second. The
//! communicators and the NSCDD solve itself, which know neither the physics nor the
//! dimension, live in `xper-parallel`; this crate partitions space and builds each process's
//! problem for the 2D engines.

#[cfg(any(test, feature = "fixtures"))]
pub mod fixtures;
pub mod fluid;
pub mod fracture;
pub mod halo;
pub use xper_decomposition::{nscdd, partition, rigid};

pub use fluid::DistributedFluid;
pub use fracture::DistributedFracture;
pub use nscdd::split::{contact_owner, split_problem, LocalProblem};
pub use partition::Bisection;
pub use rigid::shared_solve::SharedNlgs;
pub use rigid::stepper::{DistributedParams, DistributedStepper, RankLoad};
/// The communicators (threads, MPI), from `xper-parallel`.
pub use xper_parallel::comm;
#[cfg(feature = "mpi")]
pub use xper_parallel::MpiCommunicator;
pub use xper_parallel::{
    distributed_nlgs, solve_with_split_masses, BodyVelocities, InterfaceMap, SplitMasses,
};
pub use xper_parallel::{
    run_on_threads, CommStats, Communicator, SingleProcess, ThreadCommunicator,
};
