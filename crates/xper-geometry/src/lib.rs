//! Contact detection: a cell-grid broad phase, a narrow phase with one file per shape pair,
//! and a contact set that persists impulses across steps for warm starting.
//!
//! Every contact point has a unit normal from the first body to the second, a gap (signed
//! distance, negative when overlapping) and the point midway between the surfaces, which a
//! contact set keeps as the lever arms from the two bodies' positions. Pairs farther apart
//! than the alert distance produce no contact.

mod broad;
mod carry;
mod contacts;
mod detector;
pub mod narrow;

pub use broad::{BroadPhase, OuterBox};
pub use contacts::{Contact, ContactKey, ContactRow, ContactSet};
pub use detector::{Detector, DetectorStats, SKIN_CAP_OVER_SIZE, TARGET_STEPS_PER_BUILD};
pub use narrow::{collide, ContactPoint, Manifold};
