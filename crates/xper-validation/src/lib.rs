//! The validation cases of xper: small runs compared with exact answers, published data or an
//! independent method, each comparison a [`Case`] (name, reference with its source, measured
//! value, error, tolerance). The tests of this crate assert them at reduced resolution;
//! `xper validate` ([`report::write_report`]) runs them and regenerates VALIDATION.md.
//!
//! * [`rigid`]: rigid bodies (incline, drop, Newton's cradle, column, deposits);
//! * [`fracture`]: deformable elements and cohesive zones (patch test, cohesive laws, bar,
//!   wave speed, plasticity);
//! * [`periodic`]: periodic homogenization (effective tensors, cells under macroscopic strain
//!   or stress, cracks across the sides);
//! * [`fluid`]: the MAC fluid and immersed grains (Taylor-Green, Ghia's cavity, projection,
//!   Schaefer-Turek, a resting and a settling grain);
//! * [`paper`]: the paper's fracture applications at its resolution (`--full`);
//! * [`suite`]: the external contact problems of `../shared/fclib`.

mod case;
pub mod fluid;
mod fluid_report;
pub mod fracture;
pub mod paper;
pub mod periodic;
pub mod report;
pub mod rigid;
pub mod robustness;
pub mod suite;

pub use case::Case;
pub use xper_simulation::RunError;
