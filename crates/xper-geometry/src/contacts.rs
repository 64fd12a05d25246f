//! Contacts that persist across steps.

use serde::{Deserialize, Serialize};
use xper_math::{Real, Vector};

/// A contact point between bodies `bodies[0]` and `bodies[1]` (normal from the first to the
/// second) with the interaction law that governs it and its last impulse.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Contact {
    /// The two bodies, first < second.
    pub bodies: [u32; 2],
    /// Feature pair, so that a contact is recognised from one step to the next.
    pub feature: u32,
    /// Index of the interaction law in the law table.
    pub law: u16,
    /// Point midway between the surfaces (m).
    pub point: Vector,
    /// Unit normal from the first body to the second.
    pub normal: Vector,
    /// Gap (m), negative when overlapping.
    pub gap: Real,
    /// Impulse `[R_N, R_T]` (N s per m) of the last step it was solved in; the warm start.
    pub impulse: [Real; 2],
}

/// The contacts of one step, in ascending `(first body, second body)` order (the points of a
/// pair in the narrow phase's order).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct ContactSet {
    /// The contacts.
    pub contacts: Vec<Contact>,
}

impl ContactSet {
    /// Number of contacts.
    pub fn len(&self) -> usize {
        self.contacts.len()
    }
    /// Whether there is no contact.
    pub fn is_empty(&self) -> bool {
        self.contacts.is_empty()
    }
}
