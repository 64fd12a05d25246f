//! Rigid bodies over several processes: [`stepper::DistributedStepper`] runs the steps of a
//! world (partition, migration, detection, the NSCDD solve of [`crate::nscdd`] through
//! [`shared_solve::SharedNlgs`], gathering), keeping its local bodies between steps.

pub(crate) mod local_bodies;
#[cfg(feature = "dim2")]
#[path = "message2d.rs"]
mod message;
#[cfg(feature = "dim3")]
#[path = "message3d.rs"]
mod message;
pub mod shared_solve;
pub mod stepper;
