//! Contact detection: a cell-grid broad phase, a narrow phase with one file per shape pair,
//! and a contact set that persists impulses across steps for warm starting.
//!
//! Every contact point has a unit normal from the first body to the second, a gap (signed
//! distance, negative when overlapping) and the point midway between the surfaces, which a
//! contact set keeps as the lever arms from the two bodies' positions. Pairs farther apart
//! than the alert distance produce no contact.
//!
//! One source, two builds: `xper-geometry` (2D) and `xper-geometry3d` (3D, feature `dim3`),
//! which so far holds the broad phase, the narrow phase of spheres, polyhedra and planes
//! (every pair), the contact row, the contact set, the warm-start carry and the detector:
//! all of it.

mod broad;
mod carry;
mod contacts;
mod detector;
pub mod narrow;
mod periodic;
#[cfg(feature = "dim2")]
#[path = "pose2d.rs"]
mod pose;
#[cfg(feature = "dim3")]
#[path = "pose3d.rs"]
mod pose;
#[cfg(feature = "dim2")]
mod row2d;
#[cfg(feature = "dim3")]
mod row3d;

pub use broad::{BroadPhase, OuterBox};
pub use contacts::{Contact, ContactKey, ContactSet};
pub use detector::{Detector, DetectorStats, SKIN_CAP_OVER_SIZE, TARGET_STEPS_PER_BUILD};
pub use narrow::{collide, ContactPoint, Manifold, MANIFOLD_POINTS};
pub use periodic::{Image, Lattice, Periodic};
#[cfg(feature = "dim2")]
pub use row2d::ContactRow;
#[cfg(feature = "dim3")]
pub use row3d::ContactRow;
