//! Contacts that persist across steps, held once: the rows a solver sweeps and, beside them,
//! what identifies a contact from one step to the next, its gap and its impulse.
//!
//! A contact set is a structure of arrays. The detector fills it, the stepper lends its rows
//! and impulses to the solver for the step instead of copying them, and the outputs,
//! checkpoints and a distributed run's migration read it; [`Contact`] is one contact as a
//! value, for code that handles contacts one at a time.

use serde::{Deserialize, Serialize};
use xper_math::{cross, tangent, Real, Vector, DOFS};

/// What a solver sweep reads of a contact (80 bytes): its bodies, normal, lever arms and
/// diagonal Delassus block.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct ContactRow {
    /// Bodies `[i, j]`; the normal points from `i` to `j`.
    pub bodies: [u32; 2],
    /// Unit normal.
    pub normal: [Real; 2],
    /// `[r_i x n, r_i x t, r_j x n, r_j x t]` (m), lever arms from each body's position to the
    /// contact point, with `t` the normal turned by +90 degrees.
    pub arms: [Real; 4],
    /// `W_aa = G_i^T M_i^-1 G_i + G_j^T M_j^-1 G_j` (velocity per unit impulse, m/kg for
    /// bodies of unit depth), symmetric, as `[W_NN, W_NT, W_TT]`; filled by the stepper at each step (zero as the
    /// detector leaves it).
    pub block: [Real; 3],
}

impl ContactRow {
    /// The row of a contact at `point` with unit `normal` between `bodies` at positions
    /// `position_i` and `position_j`, its block zero.
    #[inline]
    pub fn new(
        bodies: [u32; 2],
        point: &Vector,
        normal: &Vector,
        position_i: &Vector,
        position_j: &Vector,
    ) -> Self {
        let t = tangent(normal);
        let (ri, rj) = (point - position_i, point - position_j);
        ContactRow {
            bodies,
            normal: [normal.x, normal.y],
            arms: [
                cross(&ri, normal),
                cross(&ri, &t),
                cross(&rj, normal),
                cross(&rj, &t),
            ],
            block: [0.0; 3],
        }
    }

    /// The unit normal as a vector.
    #[inline]
    pub fn normal(&self) -> Vector {
        Vector::new(self.normal[0], self.normal[1])
    }

    /// The contact point of the first body at `position_i`: its lever arm is
    /// `r_i = (r_i x t) n - (r_i x n) t`.
    #[inline]
    pub fn point(&self, position_i: &Vector) -> Vector {
        let n = self.normal();
        position_i + n * self.arms[1] - tangent(&n) * self.arms[0]
    }

    /// Recomputes `W_aa = G_i^T M_i^-1 G_i + G_j^T M_j^-1 G_j` from the inverse masses per
    /// degree of freedom of each body (`inv_mass(b)`), e.g. after a domain decomposition has
    /// split the mass of shared bodies.
    #[inline]
    pub fn refresh_block(&mut self, inv_mass: impl Fn(usize) -> [Real; DOFS]) {
        let n = self.normal();
        let t = tangent(&n);
        let arms = self.arms;
        let mut block = [0.0; 3];
        for (m, an, at) in [
            (inv_mass(self.bodies[0] as usize), arms[0], arms[1]),
            (inv_mass(self.bodies[1] as usize), arms[2], arms[3]),
        ] {
            block[0] += m[0] * n.x * n.x + m[1] * n.y * n.y + m[2] * an * an;
            block[1] += m[0] * n.x * t.x + m[1] * n.y * t.y + m[2] * an * at;
            block[2] += m[0] * t.x * t.x + m[1] * t.y * t.y + m[2] * at * at;
        }
        self.block = block;
    }

    /// `W_aa` as a 2x2 block `[W_NN, W_NT, W_TN, W_TT]`.
    #[inline(always)]
    pub fn full_block(&self) -> [Real; 4] {
        let [nn, nt, tt] = self.block;
        [nn, nt, nt, tt]
    }

    /// Sets `W_aa` from a 2x2 block, which must be symmetric (as a Delassus block is).
    pub fn set_full_block(&mut self, block: [Real; 4]) {
        debug_assert_eq!(block[1], block[2], "a Delassus block is symmetric");
        self.block = [block[0], block[1], block[3]];
    }
}

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
    /// Impulse `[R_N, R_T]` (N s per m) of the last step it was solved in; the warm start.
    pub impulse: [Real; 2],
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
    /// Impulse `[R_N, R_T]` per contact (N s per m): the last step's, the next one's warm
    /// start.
    pub impulses: Vec<[Real; 2]>,
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
    fn the_point_is_recovered_from_the_lever_arms() {
        let (pi, pj) = (Vector::new(0.3, -1.2), Vector::new(0.9, 0.4));
        for k in 0..100 {
            let angle = k as Real * 0.37;
            let normal = Vector::new(angle.cos(), angle.sin());
            let point = Vector::new(0.5 + 0.01 * k as Real, -0.2);
            let row = ContactRow::new([0, 1], &point, &normal, &pi, &pj);
            assert!((row.point(&pi) - point).norm() < 1e-15, "{k}");
        }
    }

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
                impulse: [k as Real, 0.0],
            })
            .collect();
        set.retain(|c| c.key.feature % 3 == 0);
        let kept: Vec<u32> = set.iter().map(|c| c.row.bodies[0]).collect();
        assert_eq!(kept, [0, 3, 6, 9]);
        assert_eq!(set.gaps, [0.0, 3.0, 6.0, 9.0]);
        assert_eq!(set.impulses.len(), 4);
    }
}
