//! Contacts that persist across steps, and the detector that produces them.

use crate::broad::BroadPhase;
use crate::narrow::collide;
use serde::{Deserialize, Serialize};
use xper_bodies::BodySet;
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

/// The contacts of one step, in a deterministic order.
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

/// The impulse of a contact of the previous step, kept for the warm start.
#[derive(Clone, Copy, Debug, Default)]
struct CarriedImpulse {
    second_body: u32,
    feature: u32,
    impulse: [Real; 2],
}

/// Detection with its reusable buffers: broad phase, narrow phase, carry-over of impulses.
///
/// Only the non-zero impulses of the previous step are kept between calls (24 bytes each,
/// grouped by first body), not the previous contacts themselves.
#[derive(Clone, Debug, Default)]
pub struct Detector {
    broad: BroadPhase,
    pairs: Vec<(u32, u32)>,
    carried: Vec<CarriedImpulse>,
    carried_start: Vec<u32>,
}

impl Detector {
    /// A detector with empty buffers.
    pub fn new() -> Self {
        Self::default()
    }

    /// Replaces `contacts` by the contacts of the current configuration within `alert`.
    ///
    /// `law_of(group_a, group_b)` gives the law between two groups, or `None` when they do not
    /// interact. Pairs of bodies that contacts cannot move (all inverse masses zero) are
    /// skipped. Impulses of contacts present before (same bodies and features) are kept.
    pub fn detect(
        &mut self,
        bodies: &BodySet,
        alert: Real,
        law_of: impl Fn(u16, u16) -> Option<u16>,
        contacts: &mut ContactSet,
    ) {
        self.carry_impulses(&contacts.contacts, bodies.len());
        contacts.contacts.clear();
        self.pairs.clear();
        self.broad.find_pairs(bodies, alert, &mut self.pairs);
        let immobile = |b: usize| bodies.inv_mass[b].iter().all(|&m| m == 0.0);
        for &(i, j) in &self.pairs {
            let (a, b) = (i as usize, j as usize);
            let Some(law) = law_of(bodies.group[a], bodies.group[b]) else {
                continue;
            };
            if immobile(a) && immobile(b) {
                continue;
            }
            let m = collide(
                &bodies.shape[a],
                &bodies.position[a],
                bodies.angle[a],
                &bodies.shape[b],
                &bodies.position[b],
                bodies.angle[b],
                alert,
            );
            for p in m.as_slice() {
                let impulse = self.previous_impulse(i, j, p.feature);
                contacts.contacts.push(Contact {
                    bodies: [i, j],
                    feature: p.feature,
                    law,
                    point: p.point,
                    normal: p.normal,
                    gap: p.gap,
                    impulse,
                });
            }
        }
    }

    /// Keeps the non-zero impulses of `previous`, grouped by first body (counting sort), for
    /// O(1) look-ups.
    fn carry_impulses(&mut self, previous: &[Contact], n_bodies: usize) {
        let kept = |c: &&Contact| c.impulse != [0.0, 0.0] && (c.bodies[0] as usize) < n_bodies;
        self.carried_start.clear();
        self.carried_start.resize(n_bodies + 1, 0);
        for c in previous.iter().filter(kept) {
            self.carried_start[c.bodies[0] as usize + 1] += 1;
        }
        for b in 0..n_bodies {
            self.carried_start[b + 1] += self.carried_start[b];
        }
        self.carried.clear();
        self.carried.resize(
            self.carried_start[n_bodies] as usize,
            CarriedImpulse::default(),
        );
        for c in previous.iter().filter(kept) {
            let slot = &mut self.carried_start[c.bodies[0] as usize];
            self.carried[*slot as usize] = CarriedImpulse {
                second_body: c.bodies[1],
                feature: c.feature,
                impulse: c.impulse,
            };
            *slot += 1;
        }
        // The fill moved each start to the next group's start: shift back.
        for b in (0..n_bodies).rev() {
            self.carried_start[b + 1] = self.carried_start[b];
        }
        self.carried_start[0] = 0;
    }

    fn previous_impulse(&self, i: u32, j: u32, feature: u32) -> [Real; 2] {
        let (s, e) = (
            self.carried_start[i as usize] as usize,
            self.carried_start[i as usize + 1] as usize,
        );
        self.carried[s..e]
            .iter()
            .find(|c| c.second_body == j && c.feature == feature)
            .map_or([0.0, 0.0], |c| c.impulse)
    }
}
