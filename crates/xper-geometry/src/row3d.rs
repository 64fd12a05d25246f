//! The row of a 3D contact: what a solver sweep reads of it.
//!
//! A contact at point `x` between bodies `i` and `j` (normal `n` from `i` to `j`) has the
//! frame `(n, t1, t2)` of [`xper_math::tangents`] and the local velocity
//!
//! ```text
//! U = F^T (v_j + w_j x r_j - v_i - w_i x r_i),   F = [n t1 t2],  r_b = x - p_b,
//! ```
//!
//! so that an impulse `R` (in the frame) changes the bodies' velocities by
//! `dv_j = M_j^-1 F R`, `dw_j = I_j^-1 (r_j x F R)` and the opposite on `i`. The diagonal
//! block is `W_aa = sum_b (F^T M_b^-1 F + (r_b x F)^T I_b^-1 (r_b x F))`, symmetric.

use serde::{Deserialize, Serialize};
use xper_bodies::InverseMass;
use xper_math::{tangents, Real, Vector};

/// What a solver sweep reads of a 3D contact (152 bytes): its bodies, frame, lever arms and
/// diagonal Delassus block.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct ContactRow {
    /// Bodies `[i, j]`; the normal points from `i` to `j`.
    pub bodies: [u32; 2],
    /// Unit normal `n`.
    pub normal: [Real; 3],
    /// First tangent `t1` (the second is `n x t1`).
    pub tangent: [Real; 3],
    /// Lever arms `[r_i, r_j]` from each body's position to the contact point (m).
    pub arms: [[Real; 3]; 2],
    /// `W_aa`, velocity per unit impulse (1/kg), symmetric, as
    /// `[NN, NT1, NT2, T1T1, T1T2, T2T2]`; filled by the stepper at each step (zero as the
    /// detector leaves it).
    pub block: [Real; 6],
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
        let [t1, _] = tangents(normal);
        let (ri, rj) = (point - position_i, point - position_j);
        ContactRow {
            bodies,
            normal: [normal.x, normal.y, normal.z],
            tangent: [t1.x, t1.y, t1.z],
            arms: [[ri.x, ri.y, ri.z], [rj.x, rj.y, rj.z]],
            block: [0.0; 6],
        }
    }

    /// The unit normal as a vector.
    #[inline]
    pub fn normal(&self) -> Vector {
        Vector::from(self.normal)
    }

    /// The frame `[n, t1, t2]`.
    #[inline]
    pub fn frame(&self) -> [Vector; 3] {
        let (n, t1) = (self.normal(), Vector::from(self.tangent));
        [n, t1, n.cross(&t1)]
    }

    /// The contact point of the first body at `position_i`.
    #[inline]
    pub fn point(&self, position_i: &Vector) -> Vector {
        position_i + Vector::from(self.arms[0])
    }

    /// The lever arms `[r_i, r_j]` from each body's position to the contact point (m), as
    /// detected.
    #[inline]
    pub fn arm_vectors(&self) -> [Vector; 2] {
        self.arms.map(Vector::from)
    }

    /// An impulse of this contact (in its frame) as the next detection carries it to the
    /// contact that replaces it: the world vector `F R`, since the new contact's tangents are
    /// not this one's (they turn with the normal).
    #[inline]
    pub fn carry_out(&self, impulse: [Real; 3]) -> [Real; 3] {
        let [n, t1, t2] = self.frame();
        (n * impulse[0] + t1 * impulse[1] + t2 * impulse[2]).into()
    }

    /// An impulse `[r_n, r_t1, r_t2]` of this contact as a world vector (the frame of
    /// [`ContactRow::carry_out`]): what the second body receives.
    #[inline]
    pub fn world_impulse(&self, impulse: [Real; 3]) -> Vector {
        Vector::from(self.carry_out(impulse))
    }

    /// A carried world impulse ([`ContactRow::carry_out`]) in this contact's frame, `F^T R`:
    /// its normal part is the component along this normal, its tangential part the projection
    /// on this tangent plane.
    #[inline]
    pub fn carry_in(&self, carried: [Real; 3]) -> [Real; 3] {
        let r = Vector::from(carried);
        self.frame().map(|a| a.dot(&r))
    }

    /// Recomputes `W_aa` (see the module documentation) from each body's inverse mass
    /// (`inv_mass(b)`), e.g. after a domain decomposition has split the mass of shared bodies.
    pub fn refresh_block(&mut self, inv_mass: impl Fn(usize) -> InverseMass) {
        let frame = self.frame();
        let mut w = [[0.0; 3]; 3];
        for (b, arm) in self.bodies.iter().zip(self.arms) {
            let m = inv_mass(*b as usize);
            let r = Vector::from(arm);
            let turn = frame.map(|a| r.cross(&a));
            for k in 0..3 {
                for l in k..3 {
                    let linear: Real = (0..3)
                        .map(|c| m.linear[c] * frame[k][c] * frame[l][c])
                        .sum();
                    w[k][l] += linear + turn[k].dot(&(m.angular * turn[l]));
                }
            }
        }
        self.block = [w[0][0], w[0][1], w[0][2], w[1][1], w[1][2], w[2][2]];
    }

    /// `W_aa` as a row-major 3x3 block.
    #[inline(always)]
    pub fn full_block(&self) -> [Real; 9] {
        let [nn, n1, n2, t11, t12, t22] = self.block;
        [nn, n1, n2, n1, t11, t12, n2, t12, t22]
    }

    /// Sets `W_aa` from a row-major 3x3 block, which must be symmetric.
    pub fn set_full_block(&mut self, w: [Real; 9]) {
        debug_assert!(
            w[1] == w[3] && w[2] == w[6] && w[5] == w[7],
            "a Delassus block is symmetric"
        );
        self.block = [w[0], w[1], w[2], w[4], w[5], w[8]];
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use xper_math::{AngMatrix, Rotation, SplitMix64};

    /// The block against `H^T M^-1 H` assembled as dense matrices (6 generalised velocity
    /// components per body, an independent computation), for random frames, lever arms and
    /// inverse masses with imposed components; the point from the lever arm.
    #[test]
    fn block_is_the_assembled_delassus_block() {
        let mut rng = SplitMix64::new(19);
        let unit = |rng: &mut SplitMix64| {
            Vector::new(
                rng.next_f64() - 0.5,
                rng.next_f64() - 0.5,
                rng.next_f64() - 0.5,
            )
        };
        for _ in 0..50 {
            let n = unit(&mut rng).normalize();
            let (pi, pj, x) = (unit(&mut rng), unit(&mut rng), unit(&mut rng));
            let mut row = ContactRow::new([0, 1], &x, &n, &pi, &pj);
            assert!((row.point(&pi) - x).norm() < 1e-15);
            let masses: Vec<InverseMass> = (0..2)
                .map(|b| {
                    let q = Rotation::from_scaled_axis(unit(&mut rng) * 3.0);
                    let r = q.to_rotation_matrix();
                    let body = AngMatrix::from_diagonal(&Vector::new(1.0, 2.0, 3.0));
                    let mut angular = r.matrix() * body * r.matrix().transpose();
                    if b == 1 {
                        // Rotation about the world z axis imposed.
                        for k in 0..3 {
                            angular[(2, k)] = 0.0;
                            angular[(k, 2)] = 0.0;
                        }
                    }
                    InverseMass {
                        linear: [0.5, 0.5, if b == 1 { 0.0 } else { 0.5 }],
                        angular,
                    }
                })
                .collect();
            row.refresh_block(|b| masses[b]);
            // H^T for each body: 3 x 6, rows the frame axes.
            let frame = row.frame();
            let mut w = nalgebra::Matrix3::<Real>::zeros();
            for (b, sign) in [(0usize, -1.0), (1, 1.0)] {
                let r = Vector::from(row.arms[b]);
                let mut h = nalgebra::SMatrix::<Real, 3, 6>::zeros();
                for (k, a) in frame.iter().enumerate() {
                    let t = r.cross(a);
                    for c in 0..3 {
                        h[(k, c)] = sign * a[c];
                        h[(k, 3 + c)] = sign * t[c];
                    }
                }
                let mut minv = nalgebra::SMatrix::<Real, 6, 6>::zeros();
                for c in 0..3 {
                    minv[(c, c)] = masses[b].linear[c];
                }
                minv.fixed_view_mut::<3, 3>(3, 3)
                    .copy_from(&masses[b].angular);
                w += h * minv * h.transpose();
            }
            let full = row.full_block();
            for k in 0..3 {
                for l in 0..3 {
                    assert!((full[3 * k + l] - w[(k, l)]).abs() < 1e-14, "{k} {l}");
                }
            }
            let [a, b, c] = frame;
            assert!((a.dot(&b)).abs() < 1e-15 && (a.cross(&b) - c).norm() < 1e-15);
        }
    }

    /// A carried impulse keeps its world direction: back to the same contact it is the
    /// identity, and across `n_z = 0`, where the tangents of `tangents` jump, the new frame's
    /// components rebuild the same world vector.
    #[test]
    fn carried_impulses_keep_their_world_direction() {
        let zero = Vector::zeros();
        let n = Vector::new(0.3, -0.4, 0.2).normalize();
        let old = ContactRow::new([0, 1], &zero, &n, &zero, &zero);
        let r = [2.0, 0.3, -0.7];
        let world = Vector::from(old.carry_out(r));
        let [a, b, c] = old.frame();
        assert!((world - (a * 2.0 + b * 0.3 - c * 0.7)).norm() < 1e-15);
        let back = old.carry_in(old.carry_out(r));
        assert!((0..3).all(|k| (back[k] - r[k]).abs() < 1e-14), "{back:?}");
        let (up, down) = (Vector::new(1.0, 0.0, 1e-9), Vector::new(1.0, 0.0, -1e-9));
        let before = ContactRow::new([0, 1], &zero, &up.normalize(), &zero, &zero);
        let after = ContactRow::new([0, 1], &zero, &down.normalize(), &zero, &zero);
        let moved = after.carry_in(before.carry_out(r));
        let [n2, t1, t2] = after.frame();
        let rebuilt = n2 * moved[0] + t1 * moved[1] + t2 * moved[2];
        assert!(
            (rebuilt - Vector::from(before.carry_out(r))).norm() < 1e-8,
            "{moved:?}"
        );
    }
}
