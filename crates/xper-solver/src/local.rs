//! The exact solution of the 2D one-contact Signorini-Coulomb problem.
//!
//! Given `U = u_free + W R` with `W` a 2x2 block (positive diagonal), find `R` with
//! `U_N >= 0, R_N >= 0, U_N R_N = 0` and Coulomb `|R_T| <= mu R_N`, `R_T = -mu R_N sign(U_T)`
//! when sliding. The cases are enumerated in closed form as in LMGC90's 2D NLGS
//! (M. Jean, CMAME 177, 1999, section 5): take-off, stick, slide in either direction.

use crate::operator::Block2;

/// Solves one contact exactly. Returns `[R_N, R_T]`.
///
/// When the Coulomb cases have no consistent solution (possible for strongly non-symmetric
/// coupling `W_nt`), the sliding solution opposing the free tangential velocity is returned.
/// A solver that revisits the contact with the same `w` and `mu` prepares [`LocalFactors`]
/// once and calls [`solve_one_contact_factored`].
#[inline]
pub fn solve_one_contact(w: &Block2, u_free: [f64; 2], mu: f64) -> [f64; 2] {
    solve_one_contact_factored(w, &LocalFactors::new(w), u_free, mu)
}

/// The reciprocal [`solve_one_contact_factored`] multiplies by instead of dividing, computed
/// once per block (a sweep revisits the same contact many times, and a division on the
/// update's critical path costs several multiplications): `1 / det W`, 8 bytes per contact.
///
/// The sliding cases need `1 / (W_nn + s mu W_nt)`. When `W_nt` is negligible (a disk's
/// contact: its normal passes through the centres, so `W_nt` is round-off) that is
/// `W_tt / det W` to a relative 1e-12, a multiplication; the contacts of polygons and of
/// finite elements, whose `W_nt` is not small, divide when they slide. A stored reciprocal
/// per sliding direction would cost 16 bytes more per contact for every contact.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LocalFactors {
    /// `1 / det W`, or 0 when `det W <= 0` (no sticking solution is tried).
    inv_det: f64,
}

impl LocalFactors {
    /// The factors of block `w`.
    pub fn new(w: &Block2) -> Self {
        let [wnn, wnt, wtn, wtt] = *w;
        let det = wnn * wtt - wnt * wtn;
        LocalFactors {
            inv_det: if det > 0.0 { 1.0 / det } else { 0.0 },
        }
    }

    /// `1 / (W_nn + s mu W_nt)` for the sliding direction `s`, or 0 where that denominator is
    /// `<= 0` (see [`LocalFactors`]).
    #[inline(always)]
    fn inv_slide(&self, w: &Block2, mu: f64, s: f64) -> f64 {
        let [wnn, wnt, _, wtt] = *w;
        // `W_tt / det W = 1 / (W_nn - W_nt^2 / W_tt)`: within a relative 1e-12 of the
        // denominator wanted when `|W_nt| (mu W_tt + |W_nt|) <= 1e-12 W_nn W_tt`.
        let coupling = wnt.abs() * (mu * wtt + wnt.abs());
        if self.inv_det > 0.0 && coupling <= 1e-12 * wnn * wtt {
            return wtt * self.inv_det;
        }
        let d = wnn + s * mu * wnt;
        if d > 0.0 {
            1.0 / d
        } else {
            0.0
        }
    }
}

/// [`solve_one_contact`] with the reciprocal of `factors`, made by [`LocalFactors::new`] from
/// the same `w`: take-off, stick, then sliding with `R_T = s mu R_N`, `U_N = 0`.
#[inline(always)]
pub fn solve_one_contact_factored(
    w: &Block2,
    factors: &LocalFactors,
    u_free: [f64; 2],
    mu: f64,
) -> [f64; 2] {
    let [wnn, wnt, wtn, wtt] = *w;
    let [ufn, uft] = u_free;
    if ufn >= 0.0 || wnn <= 0.0 {
        return [0.0, 0.0];
    }
    if factors.inv_det > 0.0 {
        let rn = (-ufn * wtt + uft * wnt) * factors.inv_det;
        let rt = (-uft * wnn + ufn * wtn) * factors.inv_det;
        if rn >= 0.0 && rt.abs() <= mu * rn {
            return [rn, rt];
        }
    }
    for s in [-1.0, 1.0] {
        let inv = factors.inv_slide(w, mu, s);
        if inv <= 0.0 {
            continue;
        }
        let rn = -ufn * inv;
        let ut = uft + (wtn + s * mu * wtt) * rn;
        if rn >= 0.0 && s * ut <= 0.0 {
            return [rn, s * mu * rn];
        }
    }
    let s = if uft > 0.0 { -1.0 } else { 1.0 };
    let denom = (wnn + s * mu * wnt).max(wnn);
    let rn = -ufn / denom;
    [rn, s * mu * rn]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Uniform numbers in [-1, 1) from a linear congruential generator seeded with `seed`.
    fn uniform(mut seed: u64) -> impl FnMut() -> f64 {
        move || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        }
    }

    fn check_solution(w: &Block2, uf: [f64; 2], mu: f64) {
        let r = solve_one_contact(w, uf, mu);
        let u = [
            uf[0] + w[0] * r[0] + w[1] * r[1],
            uf[1] + w[2] * r[0] + w[3] * r[1],
        ];
        let scale = 1e-12 * (1.0 + uf[0].abs() + uf[1].abs());
        assert!(r[0] >= 0.0 && u[0] >= -scale, "{r:?} {u:?}");
        assert!(
            (r[0] * u[0]).abs() <= scale * (1.0 + r[0]),
            "complementarity {r:?} {u:?}"
        );
        assert!(r[1].abs() <= mu * r[0] * (1.0 + 1e-12) + 1e-300);
        if u[1].abs() > scale {
            assert!((r[1] + mu * r[0] * u[1].signum()).abs() <= scale * (1.0 + r[0]));
        }
    }

    #[test]
    fn cases_take_off_stick_slide() {
        let w = [2.0, 0.3, 0.3, 1.5];
        assert_eq!(solve_one_contact(&w, [1.0, 5.0], 0.3), [0.0, 0.0]);
        check_solution(&w, [-1.0, 0.1], 0.5); // stick
        check_solution(&w, [-1.0, 3.0], 0.2); // slide backward
        check_solution(&w, [-1.0, -3.0], 0.2); // slide forward
        check_solution(&w, [-1.0, -3.0], 0.0); // frictionless
    }

    #[test]
    fn random_blocks_satisfy_the_law() {
        let mut rnd = uniform(7);
        for _ in 0..10_000 {
            let (a, b, c) = (rnd() * 2.0, rnd() * 2.0, rnd());
            // symmetric positive definite: L L^T with L = [[a,0],[c,b]] + diagonal shift
            let (l11, l21, l22) = (a.abs() + 0.1, c, b.abs() + 0.1);
            let w = [l11 * l11, l11 * l21, l11 * l21, l21 * l21 + l22 * l22];
            check_solution(&w, [rnd(), rnd() * 3.0], rnd().abs());
        }
    }

    /// A disk's block has a `W_nt` of round-off: its sliding cases multiply by `W_tt / det W`
    /// instead of dividing by `W_nn + s mu W_nt`, and must land within 1e-12 of the division.
    #[test]
    fn sliding_on_a_decoupled_block_matches_the_division() {
        let mut rnd = uniform(5);
        let mut sliding = 0;
        for _ in 0..10_000 {
            let (wnn, wtt) = (rnd().abs() + 0.1, 3.0 * (rnd().abs() + 0.1));
            let wnt = 1e-17 * rnd();
            let w = [wnn, wnt, wnt, wtt];
            let (uf, mu) = ([-rnd().abs() - 0.01, 5.0 * rnd()], rnd().abs());
            let r = solve_one_contact(&w, uf, mu);
            if (r[1].abs() - mu * r[0]).abs() > 1e-14 * r[0] {
                continue;
            }
            sliding += 1;
            let exact = -uf[0] / (wnn + r[1].signum() * mu * wnt);
            assert!(
                (r[0] - exact).abs() <= 1e-12 * exact.abs(),
                "{w:?} {uf:?} {mu}: {r:?}, R_N by division {exact}"
            );
        }
        assert!(sliding > 1000, "{sliding} sliding cases");
    }
}
