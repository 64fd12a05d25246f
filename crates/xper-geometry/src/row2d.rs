//! The row of a 2D contact: what a solver sweep reads of it.

use serde::{Deserialize, Serialize};
use xper_bodies::InverseMass;
use xper_math::{cross, tangent, Real, Vector};

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

    /// The lever arms `[r_i, r_j]` from each body's position to the contact point (m), as
    /// detected: `r = (r x t) n - (r x n) t`.
    #[inline]
    pub fn arm_vectors(&self) -> [Vector; 2] {
        let (n, t) = (self.normal(), tangent(&self.normal()));
        [
            n * self.arms[1] - t * self.arms[0],
            n * self.arms[3] - t * self.arms[2],
        ]
    }

    /// An impulse of this contact as the next detection carries it to the contact that
    /// replaces it: in 2D its components, unchanged (the tangent turns with the normal).
    #[inline(always)]
    pub fn carry_out(&self, impulse: [Real; 2]) -> [Real; 2] {
        impulse
    }

    /// An impulse `[r_n, r_t]` of this contact as a world vector `r_n n + r_t t`, with
    /// `t = n` rotated by +90 degrees: what the second body receives.
    #[inline]
    pub fn world_impulse(&self, impulse: [Real; 2]) -> Vector {
        let n = self.normal();
        n * impulse[0] + tangent(&n) * impulse[1]
    }

    /// A carried impulse ([`ContactRow::carry_out`]) in this contact's frame: unchanged in 2D.
    #[inline(always)]
    pub fn carry_in(&self, carried: [Real; 2]) -> [Real; 2] {
        carried
    }

    /// Recomputes `W_aa = G_i^T M_i^-1 G_i + G_j^T M_j^-1 G_j` from the inverse masses per
    /// degree of freedom of each body (`inv_mass(b)`), e.g. after a domain decomposition has
    /// split the mass of shared bodies.
    #[inline]
    pub fn refresh_block(&mut self, inv_mass: impl Fn(usize) -> InverseMass) {
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
}
