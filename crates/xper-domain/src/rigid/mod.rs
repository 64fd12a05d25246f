//! Rigid bodies over several processes: [`stepper::DistributedStepper`] runs the steps of a
//! world (partition, migration, detection, the NSCDD solve of [`crate::nscdd`] through
//! [`shared_solve::SharedNlgs`], gathering), keeping its local bodies between steps.

pub(crate) mod local_bodies;
pub mod shared_solve;
pub mod stepper;
