//! The one-contact problem of a cohesive interface (frictional cohesive zone, NSFD).
//!
//! The impulse of a cohesive contact is split into a unilateral-frictional part and an
//! adhesive part linear in the local velocity (M. Raous, L. Cangemi, M. Cocou, CMAME 177,
//! 1999; F. Perales, S. Bourgeois, A. Chrysochoos, Y. Monerie, EFM 75, 2008):
//!
//! `R = R_c - (o + K U)`, `K = diag(k_N, k_T) >= 0`,
//!
//! where `o` (impulse) and `K` (impulse per velocity) come from the cohesive law with the
//! intensity frozen over the step (for a theta-method, `K = h^2 theta^2 A beta C` and
//! `o = h A beta C ([u]_i + h theta (1 - theta) U_i)`, A the tributary area). With
//! `U = u_free + W R`, eliminating the adhesive part gives a Signorini-Coulomb problem for
//! `R_c` alone: `U = W' R_c + q'`, `W' = (I + W K)^-1 W = (W^-1 + K)^-1` (symmetric positive
//! when `W` is) and `q' = (I + W K)^-1 (u_free - W o)`, solved exactly by
//! [`solve_one_contact`](crate::solve_one_contact).

#[cfg(test)]
use crate::local::solve_one_contact;
use crate::local::{solve_one_contact_factored, LocalFactors};
use crate::operator::Block2;

/// The adhesive part `-(offset + stiffness U)` of a contact's impulse.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct CohesiveTerm {
    /// `[k_N, k_T]`, impulse per unit local velocity (>= 0; zero for a broken interface).
    pub stiffness: [f64; 2],
    /// `[o_N, o_T]`, impulse at zero velocity.
    pub offset: [f64; 2],
}

impl CohesiveTerm {
    /// Whether the term vanishes (a plain Signorini-Coulomb contact).
    #[inline(always)]
    pub fn is_zero(&self) -> bool {
        self.stiffness == [0.0, 0.0] && self.offset == [0.0, 0.0]
    }
}

/// Solves one cohesive contact exactly; returns the total impulse `R = R_c - (o + K U)`.
///
/// `u_free` is the local velocity without the contact's own impulse (normal shift included).
#[inline]
pub fn solve_one_cohesive_contact(
    w: &Block2,
    u_free: [f64; 2],
    mu: f64,
    term: &CohesiveTerm,
) -> [f64; 2] {
    PreparedCohesiveContact::new(w, term).solve(u_free, mu)
}

/// The parts of a cohesive contact's local solve that depend only on `W_aa` and the term,
/// computed once per solve instead of once per sweep: `(I + W K)^-1`, `W'` and
/// `(I + W K)^-1 W o`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PreparedCohesiveContact {
    inverse: Block2,
    w_eff: Block2,
    offset_velocity: [f64; 2],
    term: CohesiveTerm,
    factors: LocalFactors,
}

#[inline(always)]
fn mul(m: &Block2, x: [f64; 2]) -> [f64; 2] {
    [m[0] * x[0] + m[1] * x[1], m[2] * x[0] + m[3] * x[1]]
}

impl PreparedCohesiveContact {
    /// Prepares the local solve of a contact with block `w` and adhesive part `term` (the
    /// friction coefficient is [`Self::solve`]'s).
    pub fn new(w: &Block2, term: &CohesiveTerm) -> Self {
        let [k0, k1] = term.stiffness;
        let [w0, w1, w2, w3] = *w;
        // A = I + W K and its inverse.
        let a = [1.0 + w0 * k0, w1 * k1, w2 * k0, 1.0 + w3 * k1];
        let det = a[0] * a[3] - a[1] * a[2];
        let inverse = [a[3] / det, -a[1] / det, -a[2] / det, a[0] / det];
        let w_eff = [
            inverse[0] * w0 + inverse[1] * w2,
            inverse[0] * w1 + inverse[1] * w3,
            inverse[2] * w0 + inverse[3] * w2,
            inverse[2] * w1 + inverse[3] * w3,
        ];
        let offset_velocity = mul(&inverse, mul(w, term.offset));
        PreparedCohesiveContact {
            inverse,
            w_eff,
            offset_velocity,
            term: *term,
            factors: LocalFactors::new(&w_eff),
        }
    }

    /// The total impulse `R = R_c - (o + K U)` for the free local velocity `u_free` and the
    /// friction coefficient `mu`.
    #[inline(always)]
    pub fn solve(&self, u_free: [f64; 2], mu: f64) -> [f64; 2] {
        let qi = mul(&self.inverse, u_free);
        let q = [
            qi[0] - self.offset_velocity[0],
            qi[1] - self.offset_velocity[1],
        ];
        let [k0, k1] = self.term.stiffness;
        let [o0, o1] = self.term.offset;
        if q[0] >= 0.0 {
            // Opening: no unilateral impulse, U = q.
            return [-o0 - k0 * q[0], -o1 - k1 * q[1]];
        }
        let rc = solve_one_contact_factored(&self.w_eff, &self.factors, q, mu);
        let wr = mul(&self.w_eff, rc);
        let u = [q[0] + wr[0], q[1] + wr[1]];
        [rc[0] - o0 - k0 * u[0], rc[1] - o1 - k1 * u[1]]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Checks `R = R_c - (o + K U)` with `(R_c, U)` a Signorini-Coulomb solution.
    fn check(w: &Block2, uf: [f64; 2], mu: f64, term: &CohesiveTerm) {
        let r = solve_one_cohesive_contact(w, uf, mu, term);
        let u = [
            uf[0] + w[0] * r[0] + w[1] * r[1],
            uf[1] + w[2] * r[0] + w[3] * r[1],
        ];
        let rc = [
            r[0] + term.offset[0] + term.stiffness[0] * u[0],
            r[1] + term.offset[1] + term.stiffness[1] * u[1],
        ];
        let tol = 1e-12 * (1.0 + uf[0].abs() + uf[1].abs() + rc[0].abs() + rc[1].abs());
        assert!(rc[0] >= -tol && u[0] >= -tol, "{rc:?} {u:?}");
        assert!((rc[0] * u[0]).abs() <= tol, "complementarity {rc:?} {u:?}");
        assert!(rc[1].abs() <= mu * rc[0] + tol, "cone {rc:?}");
        if rc[1].abs() < mu * rc[0] - tol {
            assert!(u[1].abs() <= tol, "stick {u:?}");
        } else if u[1].abs() > tol {
            assert!(rc[1] * u[1] <= tol * u[1].abs(), "dissipation {rc:?} {u:?}");
        }
    }

    #[test]
    fn zero_term_is_the_plain_contact() {
        let w = [2.0, 0.3, 0.3, 1.5];
        for uf in [[-1.0, 0.2], [0.5, -0.3], [-0.2, 3.0]] {
            let plain = solve_one_contact(&w, uf, 0.4);
            let coh = solve_one_cohesive_contact(&w, uf, 0.4, &CohesiveTerm::default());
            assert!((plain[0] - coh[0]).abs() < 1e-14 && (plain[1] - coh[1]).abs() < 1e-14);
        }
    }

    #[test]
    fn opening_interface_is_pulled_back_by_its_stiffness() {
        // Frictionless, opening free velocity: R_c = 0, so R = -(o + K U) with U = uf + W R.
        let (w, uf) = ([2.0, 0.0, 0.0, 2.0], [1.0, 0.0]);
        let term = CohesiveTerm {
            stiffness: [3.0, 3.0],
            offset: [0.5, 0.0],
        };
        let r = solve_one_cohesive_contact(&w, uf, 0.0, &term);
        // U_N = 1 + 2 R_N, R_N = -(0.5 + 3 U_N)  =>  R_N = -3.5 / 7.
        assert!((r[0] + 0.5).abs() < 1e-14, "{r:?}");
        assert_eq!(r[1], 0.0);
    }

    #[test]
    fn random_cases_satisfy_the_law() {
        let mut s = 0x1234_5678_u64;
        let mut next = || {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (s >> 11) as f64 * 2f64.powi(-53)
        };
        for _ in 0..2000 {
            let (d0, d1) = (0.1 + 2.0 * next(), 0.1 + 2.0 * next());
            let off = 0.9 * (d0 * d1).sqrt() * (2.0 * next() - 1.0);
            let w = [d0, off, off, d1];
            let uf = [4.0 * next() - 2.0, 4.0 * next() - 2.0];
            let term = CohesiveTerm {
                stiffness: [5.0 * next(), 5.0 * next()],
                offset: [2.0 * next() - 1.0, 2.0 * next() - 1.0],
            };
            check(&w, uf, 0.6 * next(), &term);
        }
    }
}
