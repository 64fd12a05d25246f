//! Error measures of a contact solution.
//!
//! - The natural-map error used to compare solvers across codes (Acary, Bremond, Huber 2018;
//!   FCLib): `e_a = r_a - P_K(r_a - u_a - mu |u_T,a| e_n)`, `error = |e| / scale`.
//! - LMGC90's quadratic and max norms, accumulated during a check sweep (see
//!   `../shared/BRIEF.md`, section 2): for contact a with reactions `r` and `r'` before and
//!   after its local solve and velocities `u`, `u'`, `du = u - u'`, `rm = (r + r')/2`,
//!   `WRR = (r.W r + r'.W r')/2`, `WRWR = (|W r|^2 + |W r'|^2)/2`, summed over the `N`
//!   contacts with a non-zero mean reaction `rm` (as LMGC90's `nlgs` counts them: a contact
//!   whose reaction drops to zero in the check sweep still counts).

use crate::frame::{is_zero, ContactFrame, Frame2};
use crate::operator::Block2;

/// Projection of `(n, t)` on the Coulomb cone `|t| <= mu n`.
#[inline]
pub fn project_on_cone(x: [f64; 2], mu: f64) -> [f64; 2] {
    let [n, t] = x;
    if mu * t.abs() <= -n {
        [0.0, 0.0]
    } else if t.abs() <= mu * n {
        x
    } else {
        let np = (mu * t.abs() + n) / (mu * mu + 1.0);
        [np, mu * np * t.signum()]
    }
}

/// Natural-map error `sqrt(sum_a |e_a|^2)` (unscaled) for 2D local velocities `u` and
/// impulses `r`.
pub fn natural_map_error(u: &[[f64; 2]], r: &[[f64; 2]], mu: &[f64]) -> f64 {
    natural_map_error_of::<Frame2>(u, r, mu)
}

/// [`natural_map_error`] in frame `F`.
pub fn natural_map_error_of<F: ContactFrame>(u: &[F::Vector], r: &[F::Vector], mu: &[f64]) -> f64 {
    u.iter()
        .zip(r)
        .zip(mu)
        .map(|((u, r), &mu)| F::natural_map_error2(*u, *r, mu))
        .sum::<f64>()
        .sqrt()
}

/// LMGC90's convergence norms of one check sweep, relative to the tolerance `tol`.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ConvergenceNorms {
    /// `sqrt(sum |du|^2 / N) / (QuadWR tol)`.
    pub quad_dv: f64,
    /// `sqrt(sum |du|^2 |rm|^2 / N) / (MeanWRR tol)`.
    pub quad_dvr: f64,
    /// `sum rm.du / (sum WRR tol)`.
    pub mean_dvor: f64,
    /// `sqrt(max |du|^2) / (QuadWR tol)`.
    pub maxm_dv: f64,
    /// `sqrt(max |du|^2 |rm|^2) / (MeanWRR tol)`.
    pub maxm_dvr: f64,
    /// Contacts with a non-zero mean reaction `(r + r')/2`.
    pub active: usize,
}

impl ConvergenceNorms {
    /// The largest of LMGC90's three criteria (converged below 1): `|MeanDVoR|` with
    /// `QuadDV` and `QuadDVR`, or with their max forms when `max_forms` is set.
    pub fn worst(&self, max_forms: bool) -> f64 {
        let (dv, dvr) = if max_forms {
            (self.maxm_dv, self.maxm_dvr)
        } else {
            (self.quad_dv, self.quad_dvr)
        };
        self.mean_dvor.abs().max(dv).max(dvr)
    }
}

/// Sums accumulated over a check sweep, from which LMGC90's norms are formed. Accumulators of
/// several processes combine by [`NormAccumulator::to_sums`] and [`NormAccumulator::from_sums`]
/// (sums added, the two maxima taken as maxima), so a distributed solve judges convergence by
/// the norms of all contacts.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct NormAccumulator {
    sum_du2: f64,
    sum_du2_rm2: f64,
    max_du2: f64,
    max_du2_rm2: f64,
    sum_wrr: f64,
    sum_wrwr: f64,
    sum_rm_du: f64,
    active: usize,
}

impl NormAccumulator {
    /// Adds one contact's local update (2D).
    #[inline(always)]
    pub fn add(&mut self, w: &Block2, r: [f64; 2], r_new: [f64; 2], du: [f64; 2]) {
        self.add_in::<Frame2>(w, r, r_new, du);
    }

    /// Adds one contact's local update in frame `F`: block `w`, impulses `r` before and
    /// `r_new` after, velocity change `du`.
    #[inline(always)]
    pub fn add_in<F: ContactFrame>(
        &mut self,
        w: &F::Block,
        r: F::Vector,
        r_new: F::Vector,
        du: F::Vector,
    ) {
        let mut rm = r;
        for (m, &n) in rm.as_mut().iter_mut().zip(r_new.as_ref()) {
            *m = (*m + n) / 2.0;
        }
        if is_zero(&rm) {
            return;
        }
        let (wr, wr2) = (F::block_mul(w, r), F::block_mul(w, r_new));
        let du2 = F::dot(&du, &du);
        let rm2 = F::dot(&rm, &rm);
        self.sum_du2 += du2;
        self.max_du2 = self.max_du2.max(du2);
        self.sum_du2_rm2 += du2 * rm2;
        self.max_du2_rm2 = self.max_du2_rm2.max(du2 * rm2);
        // Summed term by term from the first (the order of the 2D code's expressions).
        let mut wrr = F::dot(&r, &wr);
        let mut wrwr = F::dot(&wr, &wr);
        for (a, b) in r_new.as_ref().iter().zip(wr2.as_ref()) {
            wrr += a * b;
        }
        for a in wr2.as_ref() {
            wrwr += a * a;
        }
        self.sum_wrr += wrr / 2.0;
        self.sum_wrwr += wrwr / 2.0;
        self.sum_rm_du += F::dot(&rm, &du);
        self.active += 1;
    }

    /// The additive sums `[sum |du|^2, sum |du|^2 |Rm|^2, sum W R.R, sum |W R|^2, sum Rm.du,
    /// active]` and the maxima `[max |du|^2, max |du|^2 |Rm|^2]`.
    pub fn to_sums(&self) -> ([f64; 6], [f64; 2]) {
        (
            [
                self.sum_du2,
                self.sum_du2_rm2,
                self.sum_wrr,
                self.sum_wrwr,
                self.sum_rm_du,
                self.active as f64,
            ],
            [self.max_du2, self.max_du2_rm2],
        )
    }

    /// The accumulator of the given sums and maxima (the inverse of [`Self::to_sums`]).
    pub fn from_sums(sums: [f64; 6], maxima: [f64; 2]) -> Self {
        NormAccumulator {
            sum_du2: sums[0],
            sum_du2_rm2: sums[1],
            sum_wrr: sums[2],
            sum_wrwr: sums[3],
            sum_rm_du: sums[4],
            active: sums[5] as usize,
            max_du2: maxima[0],
            max_du2_rm2: maxima[1],
        }
    }

    /// The norms relative to `tol`; all zero when no contact carries a reaction.
    pub fn norms(&self, tol: f64) -> ConvergenceNorms {
        if self.active == 0 || self.sum_wrr <= 0.0 {
            return ConvergenceNorms {
                active: self.active,
                ..Default::default()
            };
        }
        let n = self.active as f64;
        let quad_wr = (self.sum_wrwr / n).sqrt();
        let mean_wrr = self.sum_wrr / n;
        ConvergenceNorms {
            quad_dv: (self.sum_du2 / n).sqrt() / (quad_wr * tol),
            quad_dvr: (self.sum_du2_rm2 / n).sqrt() / (mean_wrr * tol),
            mean_dvor: self.sum_rm_du / (self.sum_wrr * tol),
            maxm_dv: self.max_du2.sqrt() / (quad_wr * tol),
            maxm_dvr: self.max_du2_rm2.sqrt() / (mean_wrr * tol),
            active: self.active,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Regression: a contact whose reaction dropped to zero during the check sweep was left
    /// out of the norms; LMGC90 counts every contact with a non-zero mean reaction.
    #[test]
    fn a_contact_that_opens_in_the_check_sweep_counts_in_the_norms() {
        let w = [2.0, 0.0, 0.0, 3.0];
        let mut acc = NormAccumulator::default();
        acc.add(&w, [1.0, 0.2], [0.0, 0.0], [-2.0, -0.6]);
        let sums = acc.to_sums().0;
        assert_eq!(sums[5], 1.0, "one contact counted");
        assert!((sums[0] - 4.36).abs() < 1e-12, "sum |du|^2 = {}", sums[0]);
        // A contact without reaction before and after adds nothing.
        acc.add(&w, [0.0, 0.0], [0.0, 0.0], [0.0, 0.0]);
        assert_eq!(acc.to_sums().0[5], 1.0);
    }

    #[test]
    fn cone_projection_cases() {
        assert_eq!(project_on_cone([1.0, 0.2], 0.5), [1.0, 0.2]);
        assert_eq!(project_on_cone([-1.0, 0.2], 0.5), [0.0, 0.0]);
        let p = project_on_cone([1.0, 2.0], 0.5);
        assert!((p[1] - 0.5 * p[0]).abs() < 1e-15);
        // The projection is orthogonal: (x - p) . p = 0.
        assert!(((1.0 - p[0]) * p[0] + (2.0 - p[1]) * p[1]).abs() < 1e-14);
    }

    #[test]
    fn natural_map_is_zero_at_solutions() {
        // sliding: r on the cone boundary, u_n = 0, u_t opposite to r_t.
        let u = [[0.0, -2.0], [3.0, 1.0], [0.0, 0.0]];
        let r = [[1.0, 0.5], [0.0, 0.0], [2.0, -0.2]];
        assert!(natural_map_error(&u, &r, &[0.5, 0.3, 0.4]) < 1e-15);
        assert!(natural_map_error(&[[-1.0, 0.0]], &[[0.0, 0.0]], &[0.3]) > 0.5);
    }
}
