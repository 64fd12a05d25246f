//! Anderson acceleration of the NLGS fixed-point iteration.
//!
//! A Gauss-Seidel sweep is a map `R -> G(R)` whose fixed point is the solution. Anderson's
//! method (type II; D. G. Anderson, J. ACM 12, 1965; H. F. Walker and P. Ni, SIAM J. Numer.
//! Anal. 49, 2011) replaces the iterate after `G` by the combination of the last `m + 1` images
//! that best cancels their residuals `f_k = G(R_k) - R_k`:
//!
//! ```text
//! gamma = argmin | f_k - dF gamma |_2,   R_k+1 = G(R_k) - dG gamma,
//! dF = [f_i+1 - f_i],  dG = [G(R_i+1) - G(R_i)]  (the last m differences)
//! ```
//!
//! Here `G` is `period` NLGS sweeps and the mixed impulses are projected back on the Coulomb
//! cones (adhesive contacts excepted) before the next sweep. Near the solution the active set
//! is fixed, `G` is affine and the method behaves as GMRES on the Gauss-Seidel iteration
//! (Walker and Ni, section 2), which removes the slowly converging long-wavelength modes of a
//! dense granular bed that plain Gauss-Seidel damps one contact layer per sweep. Convergence is
//! still judged on a plain sweep, so the tolerance keeps its meaning.

use serde::{Deserialize, Serialize};

use crate::frame::{ContactFrame, Frame2};

/// The largest history depth `m`.
pub const MAX_ANDERSON_DEPTH: u32 = 8;

/// Acceleration of the NLGS sweeps.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum Acceleration {
    /// Plain NLGS.
    #[default]
    None,
    /// Anderson mixing of the impulses every `period` sweeps with the last `depth`
    /// differences (`1 <= depth <= MAX_ANDERSON_DEPTH`, `period >= 1`).
    Anderson {
        /// History depth `m`.
        depth: u32,
        /// Sweeps between two mixings.
        period: u32,
    },
}

impl Acceleration {
    /// Anderson mixing with the depth and period that served the granular and fracture
    /// scenes best (3 and 3; see BENCHMARKS.md).
    pub const ANDERSON: Acceleration = Acceleration::Anderson {
        depth: 3,
        period: 3,
    };

    /// Whether the parameters are in range.
    pub fn is_valid(&self) -> bool {
        match *self {
            Acceleration::None => true,
            Acceleration::Anderson { depth, period } => {
                (1..=MAX_ANDERSON_DEPTH).contains(&depth) && period >= 1
            }
        }
    }
}

const MAX_DEPTH: usize = MAX_ANDERSON_DEPTH as usize;

/// The history of one solve: impulses after the last mixing, the last residual and image, and
/// the ring of the last `depth` differences with their Gram matrix. In a distributed solve each
/// process mixes its own contacts with coefficients found from sums over all processes
/// ([`AndersonMixer::mix_reduced`]), so every process keeps the same history of the Gram matrix.
/// Impulses are local vectors of the contact frame `F`.
pub struct AndersonMixer<F: ContactFrame = Frame2> {
    depth: usize,
    /// Sweeps between two mixings.
    period: u32,
    /// Impulses right after the last mixing (or the start): `R_k`.
    x: Vec<F::Vector>,
    /// Residual and image of the last mixing.
    f_prev: Vec<F::Vector>,
    g_prev: Vec<F::Vector>,
    /// `depth` slots of `n` differences each, rounded to single precision: they only steer
    /// the mixing (the next sweep and the convergence test work in double precision), and
    /// halving them saves 8 bytes per component, contact and slot.
    df: Vec<F::Stored>,
    dg: Vec<F::Stored>,
    /// `dF^T dF`, by slot.
    gram: [[f64; MAX_DEPTH]; MAX_DEPTH],
    /// Slots filled, next slot to write, whether `f_prev`/`g_prev` hold a previous mixing.
    len: usize,
    head: usize,
    have_prev: bool,
    /// `|f|^2` of the last mixing (the restart test).
    last_residual: f64,
    /// Mixings done.
    mixings: u32,
}

impl<F: ContactFrame> AndersonMixer<F> {
    /// A mixer of depth `depth`, mixing every `period` sweeps, starting from `impulses`.
    pub fn new(depth: u32, period: u32, impulses: &[F::Vector]) -> Self {
        let (depth, n) = (depth.clamp(1, MAX_ANDERSON_DEPTH) as usize, impulses.len());
        AndersonMixer {
            depth,
            period: period.max(1),
            x: impulses.to_vec(),
            f_prev: vec![F::Vector::default(); n],
            g_prev: vec![F::Vector::default(); n],
            df: vec![F::Stored::default(); depth * n],
            dg: vec![F::Stored::default(); depth * n],
            gram: [[0.0; MAX_DEPTH]; MAX_DEPTH],
            len: 0,
            head: 0,
            have_prev: false,
            last_residual: f64::INFINITY,
            mixings: 0,
        }
    }

    /// The mixer of a solve with `params` starting from `impulses`; `None` for plain sweeps.
    pub fn for_params(params: &crate::NlgsParams, impulses: &[F::Vector]) -> Option<Self> {
        match params.acceleration {
            Acceleration::None => None,
            Acceleration::Anderson { depth, period } => {
                Some(AndersonMixer::new(depth, period, impulses))
            }
        }
    }

    /// Whether the solve mixes after sweep `sweep` of at most `max_sweeps`: every `period`
    /// sweeps, never after the last, so that the answer returned is always a checked sweep's.
    pub fn mixes_after(&self, sweep: u32, max_sweeps: u32) -> bool {
        sweep.is_multiple_of(self.period) && sweep < max_sweeps
    }

    /// Mixings done so far.
    pub fn mixings(&self) -> u32 {
        self.mixings
    }

    /// Mixes the impulses `g = G(R_k)` in place: `constrain_apply(a, old, mixed)` receives
    /// each contact's impulse before and after mixing, must return the admissible impulse (on
    /// its cone) and apply the change to the operator. Does nothing but record the history
    /// when there is none yet, when the residual grew since the last mixing (the history then
    /// restarts from here) or when the least-squares problem is degenerate.
    pub fn mix(
        &mut self,
        impulses: &mut [F::Vector],
        constrain_apply: impl FnMut(usize, F::Vector, F::Vector) -> F::Vector,
    ) {
        self.mix_reduced(impulses, |_| {}, constrain_apply);
    }

    /// [`Self::mix`] where `impulses` are one process's share of the contacts: `reduce`
    /// replaces its argument (the new Gram row, the right-hand side and the squared residual
    /// of this share, `2 k + 1` values with `k` the same on every process) by its sum over the
    /// processes, in the same order everywhere.
    pub fn mix_reduced(
        &mut self,
        impulses: &mut [F::Vector],
        reduce: impl FnOnce(&mut [f64]),
        mut constrain_apply: impl FnMut(usize, F::Vector, F::Vector) -> F::Vector,
    ) {
        let n = impulses.len();
        let (depth, s) = (self.depth, self.head);
        let record = self.have_prev;
        let filled = if record { (self.len + 1).min(depth) } else { 0 };
        // Pass 1: residual, new differences in slot s, the Gram row of s and dF^T f.
        let mut row = [0.0; MAX_DEPTH];
        let mut rhs = [0.0; MAX_DEPTH];
        let mut residual = 0.0;
        for (a, &g) in impulses.iter().enumerate() {
            let f = F::sub(g, self.x[a]);
            residual += F::dot(&f, &f);
            if record {
                // The Gram matrix is that of the stored (rounded) differences.
                let stored = F::to_stored(F::sub(f, self.f_prev[a]));
                self.df[s * n + a] = stored;
                self.dg[s * n + a] = F::to_stored(F::sub(g, self.g_prev[a]));
                let d = F::from_stored(stored);
                for j in 0..filled {
                    let dj = F::from_stored(self.df[j * n + a]);
                    row[j] += F::dot(&d, &dj);
                    rhs[j] += F::dot(&dj, &f);
                }
            }
            self.f_prev[a] = f;
            self.g_prev[a] = g;
        }
        self.have_prev = true;
        let mut sums = [0.0; 2 * MAX_DEPTH + 1];
        sums[..filled].copy_from_slice(&row[..filled]);
        sums[filled..2 * filled].copy_from_slice(&rhs[..filled]);
        sums[2 * filled] = residual;
        reduce(&mut sums[..2 * filled + 1]);
        row[..filled].copy_from_slice(&sums[..filled]);
        rhs[..filled].copy_from_slice(&sums[filled..2 * filled]);
        let residual = sums[2 * filled];
        if record {
            for (j, &v) in row.iter().enumerate().take(filled) {
                self.gram[s][j] = v;
                self.gram[j][s] = v;
            }
            self.len = filled;
            self.head = (s + 1) % depth;
        }
        // A residual larger than at the last mixing: the history no longer describes the
        // iteration (another active set, or a cycle between two); start it again from here.
        // A looser test (growth by 2 in norm) let a 4-process solve cycle without converging.
        let restart = residual > self.last_residual;
        self.last_residual = residual;
        let gamma = if restart {
            None
        } else {
            self.coefficients(&rhs)
        };
        let Some(gamma) = gamma else {
            if restart {
                self.len = 0;
                self.head = 0;
            }
            self.x.copy_from_slice(impulses);
            return;
        };
        // Pass 2: R_k+1 = G(R_k) - dG gamma, constrained and applied.
        let k = self.len;
        for (a, impulse) in impulses.iter_mut().enumerate() {
            let g = *impulse;
            let mut m = g;
            for (j, &c) in gamma.iter().enumerate().take(k) {
                let d = F::from_stored(self.dg[j * n + a]);
                for (m, &d) in m.as_mut().iter_mut().zip(d.as_ref()) {
                    *m -= c * d;
                }
            }
            let r = constrain_apply(a, g, m);
            *impulse = r;
            self.x[a] = r;
        }
        self.mixings += 1;
    }

    /// `gamma` solving `(dF^T dF + eps I) gamma = dF^T f` by Cholesky, `eps` 1e-10 of the mean
    /// diagonal; `None` without history or when the system is not positive definite. (A ridge
    /// above the differences' single-precision rounding, 1e-6, spoils the finite termination
    /// on linear maps that the test below checks; a mixing made poor by rounding raises the
    /// residual, and the history then restarts.)
    fn coefficients(&self, rhs: &[f64; MAX_DEPTH]) -> Option<[f64; MAX_DEPTH]> {
        let k = self.len;
        if k == 0 {
            return None;
        }
        let mean = (0..k).map(|i| self.gram[i][i]).sum::<f64>() / k as f64;
        if !(mean > 0.0 && mean.is_finite()) {
            return None;
        }
        let mut l = [[0.0; MAX_DEPTH]; MAX_DEPTH];
        for i in 0..k {
            for j in 0..=i {
                let mut v = self.gram[i][j] + if i == j { 1e-10 * mean } else { 0.0 };
                for (a, b) in l[i][..j].iter().zip(&l[j][..j]) {
                    v -= a * b;
                }
                if i == j {
                    if v <= 0.0 {
                        return None;
                    }
                    l[i][i] = v.sqrt();
                } else {
                    l[i][j] = v / l[j][j];
                }
            }
        }
        let mut y = [0.0; MAX_DEPTH];
        for i in 0..k {
            let s = (0..i).fold(rhs[i], |s, p| s - l[i][p] * y[p]);
            y[i] = s / l[i][i];
        }
        let mut gamma = [0.0; MAX_DEPTH];
        for i in (0..k).rev() {
            let s = (i + 1..k).fold(y[i], |s, p| s - l[p][i] * gamma[p]);
            gamma[i] = s / l[i][i];
        }
        gamma[..k].iter().all(|g| g.is_finite()).then_some(gamma)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// On a linear fixed-point map `x -> A x + b` of dimension d, type-II Anderson with a
    /// depth of at least d is GMRES in disguise and reaches the fixed point after d + 1
    /// mixings, while the plain iteration contracts only by the spectral radius per step.
    #[test]
    fn anderson_solves_a_linear_contraction_in_few_mixings() {
        // Two contacts = four unknowns; A has spectral radius 0.99 (slow plain iteration).
        let a = [
            [0.99, 0.0, 0.0, 0.0],
            [0.1, 0.5, 0.0, 0.0],
            [0.0, 0.2, 0.9, 0.0],
            [0.0, 0.0, 0.3, -0.7],
        ];
        let b = [1.0, -2.0, 0.5, 3.0];
        let map = |x: &[[f64; 2]]| -> Vec<[f64; 2]> {
            let v = [x[0][0], x[0][1], x[1][0], x[1][1]];
            let y: Vec<f64> = (0..4)
                .map(|i| b[i] + (0..4).map(|j| a[i][j] * v[j]).sum::<f64>())
                .collect();
            vec![[y[0], y[1]], [y[2], y[3]]]
        };
        // The fixed point, by 20000 plain iterations.
        let mut exact = vec![[0.0; 2]; 2];
        for _ in 0..20000 {
            exact = map(&exact);
        }
        let mut x = vec![[0.0; 2]; 2];
        let mut mixer = AndersonMixer::<Frame2>::new(4, 1, &x);
        for _ in 0..6 {
            x = map(&x);
            mixer.mix(&mut x, |_, _, m| m);
        }
        let err = (0..2)
            .flat_map(|c| (0..2).map(move |d| (c, d)))
            .map(|(c, d)| (x[c][d] - exact[c][d]).abs())
            .fold(0.0, f64::max);
        assert!(err < 1e-9, "Anderson error after 6 maps: {err:e}");
        // The plain iteration after 6 maps is still far off (0.99^6 of the start).
        let mut y = vec![[0.0; 2]; 2];
        for _ in 0..6 {
            y = map(&y);
        }
        assert!((y[0][0] - exact[0][0]).abs() > 1.0);
    }
}
