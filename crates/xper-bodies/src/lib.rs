//! Rigid bodies: shapes, mass properties, driven degrees of freedom and the body set.
//!
//! Bodies live in a [`BodySet`] stored as a structure of arrays indexed by [`BodyHandle`], so
//! that the contact solver streams only what it needs (positions and velocities; inverse
//! masses are computed from the masses and the imposed degrees of freedom).
//! Each body carries a global `id` and an [`Ownership`] so that a domain-decomposed run can
//! hold shadow copies of bodies owned by another process without changing this layout.

mod drive;
mod set;
#[cfg(feature = "dim2")]
mod shape;
#[cfg(feature = "dim3")]
#[path = "shape3d.rs"]
mod shape;

pub use drive::{Drive, ExtentFactor, PressureDrive, TimeFunction};
#[cfg(feature = "dim3")]
pub use set::isotropic_inertia;
pub use set::{Body, BodyHandle, BodySet, Configuration, InverseMass, Ownership};
#[cfg(feature = "dim2")]
pub use shape::{ConvexPolygon, Shape};
#[cfg(feature = "dim3")]
pub use shape::{ConvexPolyhedron, Shape};
