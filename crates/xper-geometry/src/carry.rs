//! The contacts of a detection written over the previous ones, in the same buffers.
//!
//! A new contact takes the impulse of the previous contact with the same bodies and feature:
//! the warm start of the next solve. In 3D the impulse is carried as a vector of the world
//! ([`ContactRow::carry_out`]) and expressed in the new contact's frame by the caller
//! ([`ContactRow::carry_in`]), since the tangents turn with the normal; in 2D both are the
//! identity (the tangent is the normal turned by a quarter). Both lists are in ascending order of bodies, so one pass
//! merges them, writing the new contacts from the front of the buffers while reading the
//! previous ones ahead of them. Where the new contacts get ahead (more of them than of the
//! previous ones so far), the previous contacts in their way are moved aside into a short
//! queue, read first. No copy of the previous contacts is made (the set's own buffers hold the
//! new ones) and none is moved but those few.

use crate::contacts::{Contact, ContactSet};
#[cfg(doc)]
use crate::ContactRow;
use crate::MANIFOLD_POINTS;
use std::collections::VecDeque;
use xper_math::{Real, DIM};

/// The most points a pair of bodies has (a narrow phase's manifold).
const POINTS_PER_PAIR: usize = MANIFOLD_POINTS;

/// A previous contact moved aside: its bodies, feature and carried impulse.
type Aside = ([u32; 2], u32, [Real; DIM]);

/// A merge in progress over a contact set: `[0, written)` holds the new contacts; the previous
/// contacts not yet read are `aside`, then `[read, end)`.
pub(crate) struct CarryOver<'a> {
    set: &'a mut ContactSet,
    written: usize,
    read: usize,
    end: usize,
    aside: VecDeque<Aside>,
}

impl<'a> CarryOver<'a> {
    /// Starts a merge over `set`, which holds the previous contacts in ascending order of
    /// bodies, as a detection leaves them (not checked: that would read them all once more;
    /// a previous contact out of order only passes its impulse on to no new contact).
    pub fn new(set: &'a mut ContactSet) -> Self {
        let end = set.len();
        CarryOver {
            set,
            written: 0,
            read: 0,
            end,
            aside: VecDeque::new(),
        }
    }

    /// The carried impulses ([`ContactRow::carry_out`]) of the previous contacts of pair
    /// `bodies`, as `(feature, impulse)`; the previous contacts of the pairs before it are
    /// dropped. Pairs come in ascending order.
    pub fn previous_of(
        &mut self,
        bodies: [u32; 2],
    ) -> ([(u32, [Real; DIM]); POINTS_PER_PAIR], usize) {
        let mut found = [(0, [0.0; DIM]); POINTS_PER_PAIR];
        let mut count = 0;
        let mut keep = |feature: u32, impulse: [Real; DIM]| {
            if count < POINTS_PER_PAIR {
                found[count] = (feature, impulse);
                count += 1;
            }
        };
        while let Some(&(b, feature, impulse)) = self.aside.front() {
            if b > bodies {
                return (found, count);
            }
            if b == bodies {
                keep(feature, impulse);
            }
            self.aside.pop_front();
        }
        let set = &*self.set;
        while self.read < self.end && set.rows[self.read].bodies <= bodies {
            if set.rows[self.read].bodies == bodies {
                let row = &set.rows[self.read];
                keep(
                    set.keys[self.read].feature,
                    row.carry_out(set.impulses[self.read]),
                );
            }
            self.read += 1;
        }
        (found, count)
    }

    /// Appends a new contact.
    pub fn push(&mut self, c: Contact) {
        let set = &mut *self.set;
        let k = self.written;
        if k == self.read && self.read < self.end {
            // A previous contact not yet read is in the way: aside with it.
            let b = set.rows[k].bodies;
            let carried = set.rows[k].carry_out(set.impulses[k]);
            self.aside.push_back((b, set.keys[k].feature, carried));
            self.read += 1;
        }
        if k < set.rows.len() {
            set.rows[k] = c.row;
            set.keys[k] = c.key;
            set.gaps[k] = c.gap;
            set.impulses[k] = c.impulse;
        } else {
            if set.rows.len() == set.rows.capacity() {
                // Grown by a sixty-fourth, not doubled: the count creeps up step by step.
                let more = k / 64 + 16;
                set.rows.reserve_exact(more);
                set.keys.reserve_exact(more);
                set.gaps.reserve_exact(more);
                set.impulses.reserve_exact(more);
            }
            set.push(c);
        }
        self.written += 1;
    }
}

impl Drop for CarryOver<'_> {
    /// Ends the merge: the set holds the new contacts.
    fn drop(&mut self) {
        let (set, n) = (&mut *self.set, self.written);
        set.rows.truncate(n);
        set.keys.truncate(n);
        set.gaps.truncate(n);
        set.impulses.truncate(n);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contacts::ContactKey;
    use crate::ContactRow;

    use xper_math::Vector;

    /// A contact with normal `e_x` and impulse `[r, -r, ...]`.
    fn contact(bodies: [u32; 2], feature: u32, impulse: Real) -> Contact {
        let zero = Vector::zeros();
        Contact {
            row: ContactRow::new(bodies, &zero, &Vector::x(), &zero, &zero),
            key: ContactKey { feature },
            gap: 0.0,
            impulse: std::array::from_fn(|c| if c == 0 { impulse } else { -impulse }),
        }
    }

    fn both(r: Real) -> [Real; DIM] {
        std::array::from_fn(|c| if c == 0 { r } else { -r })
    }

    /// The merge against a plain lookup in a copy of the previous contacts, for new lists
    /// much longer and much shorter than the previous ones (the buffers must grow while
    /// unread previous contacts remain).
    #[test]
    fn every_new_contact_takes_the_impulse_of_its_previous_one() {
        let mut seed = 7u64;
        let mut next = |m: u64| {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 33) % m
        };
        for trial in 0..200 {
            let pairs = |density: u64, next: &mut dyn FnMut(u64) -> u64| {
                let mut list = Vec::new();
                for i in 0..40u32 {
                    for j in i + 1..40 {
                        if next(100) < density {
                            for f in 0..1 + next(2) as u32 {
                                list.push(([i, j], f));
                            }
                        }
                    }
                }
                list
            };
            let (before, after) = (next(30), next(30));
            let previous: Vec<Contact> = pairs(before, &mut next)
                .into_iter()
                .enumerate()
                .map(|(k, (b, f))| contact(b, f, 1.0 + k as Real))
                .collect();
            let mut set: ContactSet = previous.iter().copied().collect();
            let new = pairs(after, &mut next);
            {
                let mut merge = CarryOver::new(&mut set);
                let mut k = 0;
                while k < new.len() {
                    let bodies = new[k].0;
                    let (found, count) = merge.previous_of(bodies);
                    while k < new.len() && new[k].0 == bodies {
                        let f = new[k].1;
                        let r = found[..count]
                            .iter()
                            .find(|e| e.0 == f)
                            .map_or(0.0, |e| e.1[0]);
                        merge.push(contact(bodies, f, r));
                        k += 1;
                    }
                }
            }
            assert_eq!(set.len(), new.len(), "trial {trial}");
            for (c, &(bodies, f)) in set.iter().zip(&new) {
                let expected = (previous.iter())
                    .find(|p| p.row.bodies == bodies && p.key.feature == f)
                    .map_or(0.0, |p| p.impulse[0]);
                assert_eq!((c.row.bodies, c.key.feature), (bodies, f), "trial {trial}");
                let carried = c.row.carry_in(c.row.carry_out(both(expected)));
                let error = (0..DIM)
                    .map(|k| (c.impulse[k] - carried[k]).abs())
                    .fold(0.0, Real::max);
                assert!(error <= 1e-12 * expected.abs(), "trial {trial} {bodies:?}");
            }
        }
    }

    #[test]
    fn a_previous_contact_out_of_order_only_loses_its_impulse() {
        let mut set: ContactSet = [contact([2, 3], 0, 5.0), contact([0, 1], 0, 4.0)]
            .into_iter()
            .collect();
        let mut merge = CarryOver::new(&mut set);
        assert_eq!(merge.previous_of([0, 1]).1, 0);
        merge.push(contact([0, 1], 0, 0.0));
        let (found, count) = merge.previous_of([2, 3]);
        assert_eq!(count, 1);
        let row = contact([2, 3], 0, 0.0).row;
        let back = row.carry_in(found[0].1);
        assert!(
            (0..DIM).all(|k| (back[k] - both(5.0)[k]).abs() < 1e-14),
            "{back:?}"
        );
        merge.push(contact([2, 3], 0, 5.0));
        drop(merge);
        assert_eq!(set.impulses, [both(0.0), both(5.0)]);
    }
}
