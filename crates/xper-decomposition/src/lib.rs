//! Space partition and the rigid-body run over several processes.
//!
//! Space is cut among processes by recursive coordinate bisection ([`partition::Bisection`]);
//! [`rigid::stepper::DistributedStepper`] steps a rigid world over a communicator (migration,
//! shadow copies, detection, the NSCDD solve of `xper-parallel` through
//! [`rigid::shared_solve::SharedNlgs`], gathering), each process holding its share of the
//! problem ([`nscdd::split`]). `xper-domain` re-exports all of it beside the distributed fluid
//! and fracture runs.
//!
//! One source, two builds: `xper-decomposition` (2D) and `xper-decomposition3d` (feature
//! `dim3`); what the two dimensions exchange differently (a body's state, a contact) is in
//! `rigid/message2d.rs` and `rigid/message3d.rs`.

pub mod nscdd;
pub mod partition;
pub mod rigid;

pub use xper_parallel::comm;
pub use xper_parallel::{distributed_nlgs, run_on_threads, solve_with_split_masses};
