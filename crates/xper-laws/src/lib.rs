//! Interaction laws and the table that picks one per pair of body groups (LMGC90's
//! "see table", with names that explain themselves).
//!
//! The only law today is Signorini-Coulomb with Newton restitution:
//! unilateral contact `U_N + e min(U_N^-, 0) >= 0 _|_ R_N >= 0` (velocity form of Moreau,
//! with Newton's impact law, J.J. Moreau, "Unilateral contact and dry friction in finite
//! freedom dynamics", CISM 302, 1988; M. Jean, "The non-smooth contact dynamics method",
//! CMAME 177, 1999) and Coulomb friction `|R_T| <= mu R_N`, sliding opposite to `U_T`.

use serde::{Deserialize, Serialize};

pub mod cohesive;

/// Signorini-Coulomb law with Newton restitution.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct SignoriniCoulomb {
    /// Coulomb friction coefficient mu (dimensionless, >= 0).
    pub friction: f64,
    /// Newton restitution coefficient e in [0, 1] (0: perfectly inelastic impacts).
    pub restitution: f64,
}

/// An interaction law.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum InteractionLaw {
    /// Unilateral contact with Coulomb friction and Newton restitution.
    SignoriniCoulomb(SignoriniCoulomb),
}

/// Laws per unordered pair of groups; pairs without a law do not interact.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct LawTable {
    groups: usize,
    /// `groups x groups` entries, symmetric; index into `laws`.
    entries: Vec<Option<u16>>,
    laws: Vec<InteractionLaw>,
}

impl LawTable {
    /// A table for `groups` groups with no law yet.
    pub fn new(groups: usize) -> Self {
        LawTable {
            groups,
            entries: vec![None; groups * groups],
            laws: Vec::new(),
        }
    }

    /// Sets the law between groups `a` and `b` (either order); returns its index.
    pub fn set(&mut self, a: usize, b: usize, law: InteractionLaw) -> u16 {
        let k = self.laws.len() as u16;
        self.laws.push(law);
        self.entries[a * self.groups + b] = Some(k);
        self.entries[b * self.groups + a] = Some(k);
        k
    }

    /// The law index between two groups, if any.
    #[inline]
    pub fn between(&self, a: u16, b: u16) -> Option<u16> {
        self.entries[a as usize * self.groups + b as usize]
    }

    /// The law of an index returned by [`LawTable::between`].
    #[inline]
    pub fn law(&self, k: u16) -> &InteractionLaw {
        &self.laws[k as usize]
    }

    /// Number of groups.
    pub fn group_count(&self) -> usize {
        self.groups
    }

    /// Number of laws, in the order they were set.
    pub fn len(&self) -> usize {
        self.laws.len()
    }

    /// Whether no law is set.
    pub fn is_empty(&self) -> bool {
        self.laws.is_empty()
    }

    /// The law of index `k`, to change its coefficients between steps.
    pub fn law_mut(&mut self, k: u16) -> &mut InteractionLaw {
        &mut self.laws[k as usize]
    }

    /// The two groups law `k` was set between (smaller first).
    pub fn groups_of(&self, k: u16) -> [usize; 2] {
        let at = (self.entries.iter())
            .position(|&e| e == Some(k))
            .unwrap_or(0);
        [at / self.groups.max(1), at % self.groups.max(1)]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_is_symmetric_and_sparse() {
        let mut t = LawTable::new(3);
        let law = InteractionLaw::SignoriniCoulomb(SignoriniCoulomb {
            friction: 0.3,
            restitution: 0.0,
        });
        let k = t.set(0, 2, law);
        assert_eq!(t.between(2, 0), Some(k));
        assert_eq!(t.between(0, 2), Some(k));
        assert_eq!(t.between(1, 1), None);
        assert_eq!(*t.law(k), law);
        let k2 = t.set(1, 1, law);
        assert_eq!(
            (t.len(), t.groups_of(k), t.groups_of(k2)),
            (2, [0, 2], [1, 1])
        );
        let InteractionLaw::SignoriniCoulomb(l) = t.law_mut(k2);
        l.friction = 0.7;
        let InteractionLaw::SignoriniCoulomb(l) = t.law(t.between(1, 1).unwrap());
        assert_eq!(l.friction, 0.7);
    }
}
