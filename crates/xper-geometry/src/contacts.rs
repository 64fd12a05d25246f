//! Contacts that persist across steps, held once: the rows a solver sweeps and, beside them,
//! what identifies a contact from one step to the next, its gap and its impulse.
//!
//! A contact set is a structure of arrays. The detector fills it, the stepper lends its rows
//! and impulses to the solver for the step instead of copying them, and the outputs,
//! checkpoints and a distributed run's migration read it; [`Contact`] is one contact as a
//! value, for code that handles contacts one at a time.

use crate::ContactRow;
use serde::{Deserialize, Serialize};
use xper_math::{Real, DIM};

/// What recognises a contact from one step to the next besides its bodies. (Its interaction
/// law is that of its bodies' groups, looked up where needed, not stored.)
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct ContactKey {
    /// Feature pair (which vertex or face of each body).
    pub feature: u32,
}

/// One contact as a value: between bodies `bodies[0]` and `bodies[1]` (normal from the first
/// to the second), with its gap and last impulse.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Contact {
    /// The row: bodies (first < second), normal, lever arms at detection, block.
    pub row: ContactRow,
    /// Feature pair.
    pub key: ContactKey,
    /// Gap (m), negative when overlapping.
    pub gap: Real,
    /// Impulse in the contact frame (`[R_N, R_T]` in 2D, N s per m; `[R_N, R_T1, R_T2]` in 3D,
    /// N s) of the last step it was solved in; the warm start.
    pub impulse: [Real; DIM],
}

/// The contacts of one step, in ascending `(first body, second body)` order (the points of a
/// pair in the narrow phase's order), as parallel arrays.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct ContactSet {
    /// Row per contact.
    pub rows: Vec<ContactRow>,
    /// Feature pair per contact.
    pub keys: Vec<ContactKey>,
    /// Gap per contact (m), negative when overlapping: the detected one, which a time stepper
    /// replaces by the linearised gap at the end of its step.
    pub gaps: Vec<Real>,
    /// Impulse per contact in its frame (see [`Contact::impulse`]): the last step's, the next
    /// one's warm start.
    pub impulses: Vec<[Real; DIM]>,
}

impl ContactSet {
    /// Number of contacts.
    pub fn len(&self) -> usize {
        self.keys.len()
    }

    /// Whether there is no contact.
    pub fn is_empty(&self) -> bool {
        self.keys.is_empty()
    }

    /// Removes every contact.
    pub fn clear(&mut self) {
        self.rows.clear();
        self.keys.clear();
        self.gaps.clear();
        self.impulses.clear();
    }

    /// Contact `k` as a value.
    #[inline]
    pub fn get(&self, k: usize) -> Contact {
        Contact {
            row: self.rows[k],
            key: self.keys[k],
            gap: self.gaps[k],
            impulse: self.impulses[k],
        }
    }

    /// Appends a contact.
    #[inline]
    pub fn push(&mut self, c: Contact) {
        self.rows.push(c.row);
        self.keys.push(c.key);
        self.gaps.push(c.gap);
        self.impulses.push(c.impulse);
    }

    /// The contacts as values, in order.
    pub fn iter(&self) -> impl ExactSizeIterator<Item = Contact> + '_ {
        (0..self.len()).map(|k| self.get(k))
    }

    /// Keeps the contacts for which `keep` holds, in order.
    pub fn retain(&mut self, mut keep: impl FnMut(&Contact) -> bool) {
        let mut kept = 0;
        for k in 0..self.len() {
            let c = self.get(k);
            if keep(&c) {
                self.rows[kept] = c.row;
                self.keys[kept] = c.key;
                self.gaps[kept] = c.gap;
                self.impulses[kept] = c.impulse;
                kept += 1;
            }
        }
        self.rows.truncate(kept);
        self.keys.truncate(kept);
        self.gaps.truncate(kept);
        self.impulses.truncate(kept);
    }
}

impl FromIterator<Contact> for ContactSet {
    fn from_iter<I: IntoIterator<Item = Contact>>(contacts: I) -> Self {
        let mut set = ContactSet::default();
        for c in contacts {
            set.push(c);
        }
        set
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn retain_keeps_the_chosen_contacts_in_order() {
        let mut set: ContactSet = (0..10u32)
            .map(|k| Contact {
                row: ContactRow {
                    bodies: [k, k + 1],
                    ..Default::default()
                },
                key: ContactKey { feature: k },
                gap: k as Real,
                impulse: std::array::from_fn(|c| if c == 0 { k as Real } else { 0.0 }),
            })
            .collect();
        set.retain(|c| c.key.feature % 3 == 0);
        let kept: Vec<u32> = set.iter().map(|c| c.row.bodies[0]).collect();
        assert_eq!(kept, [0, 3, 6, 9]);
        assert_eq!(set.gaps, [0.0, 3.0, 6.0, 9.0]);
        assert_eq!(set.impulses.len(), 4);
    }
}
