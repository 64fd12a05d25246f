//! Non-smooth Gauss-Seidel (NSGS) over contacts of an assembled problem, in 2D and 3D.
//!
//! ```text
//! u = W r + q;  for each contact a in turn (others fixed):
//!   q_a^free = q_a + sum_{b != a} W_ab r_b = u_a - W_aa r_a
//!   r_a <- omega * solve_local(W_aa, q_a^free, mu_a) + (1 - omega) r_a
//! ```
//!
//! (Moreau 1994; Jean, CMAME 177, 1999; Siconos' `fc3d_nsgs`, Acary, Bremond, Huber 2018,
//! section on splitting methods.) `u_a` is recomputed from the CSR rows of contact a's
//! block row, so a contact update costs that block row's non-zeros and a sweep costs
//! `nnz(W)`; no global velocity is kept. The local solve is exact in 2D
//! ([`crate::solve_one_contact`]) and Alart-Curnier's local Newton with Siconos' projection
//! fallback in 3D ([`crate::alart_curnier`]). The contact order may be reshuffled at every
//! sweep with a deterministic seed (splitmix64, Steele, Lea, Flood 2014), as Siconos'
//! "shuffle" option. Convergence is tested every `check_every` sweeps with the shared error.

use crate::alart_curnier::{solve_contact_3d, LocalParams, LocalPath};
use crate::local::solve_one_contact;
use crate::nlgs::SolveError;
use crate::problem::{project_on_cone_nd, FrictionProblem};
use crate::solve::{prepare, scaled_error, SolveReport, SolverKind, SolverParams};
use xper_math::SplitMix64;

/// NSGS tuning (the tolerance, iteration limit and scaling are in [`SolverParams`]).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct NsgsParams {
    /// Relaxation `omega` in (0, 2); a relaxed impulse leaving the cone is projected back.
    pub relaxation: f64,
    /// Reshuffle the contact order at each sweep with this seed; `None` keeps the natural
    /// order.
    pub shuffle_seed: Option<u64>,
    /// Sweeps between two evaluations of the shared error (each costs about one sweep).
    pub check_every: u32,
    /// The one-contact 3D solver.
    pub local: LocalParams,
}

impl Default for NsgsParams {
    fn default() -> Self {
        NsgsParams {
            relaxation: 1.0,
            shuffle_seed: None,
            check_every: 2,
            local: LocalParams::default(),
        }
    }
}

/// Solves `problem` by NSGS from `warm_start` (zero when `None`).
pub fn nsgs(
    problem: &FrictionProblem,
    params: &SolverParams,
    warm_start: Option<&[f64]>,
) -> Result<SolveReport, SolveError> {
    let (blocks, mut r) = prepare(problem, params, warm_start)?;
    let sp = &params.nsgs;
    let omega = sp.relaxation;
    if !(omega > 0.0 && omega < 2.0) || sp.check_every == 0 {
        return Err(SolveError::InvalidParams(format!(
            "relaxation {omega} not in (0, 2) or check_every = 0"
        )));
    }
    let (d, n) = (problem.dim, problem.mu.len());
    let mut u = vec![0.0; r.len()];
    let mut order: Vec<usize> = (0..n).collect();
    let mut rng = sp.shuffle_seed.map(SplitMix64::new);
    let mut fallbacks = 0u64;
    let mut iterations = 0;
    for sweep in 1..=params.max_iterations {
        iterations = sweep;
        if let Some(g) = rng.as_mut() {
            g.shuffle(&mut order);
        }
        for &a in &order {
            if sweep_contact(problem, &blocks[a], a, &mut r, omega, &sp.local) {
                fallbacks += 1;
            }
        }
        if sweep % sp.check_every == 0 || sweep == params.max_iterations {
            let e = scaled_error(problem, &r, &mut u, params.scaling);
            if !e.is_finite() || e < params.tolerance {
                break;
            }
        }
    }
    debug_assert_eq!(r.len(), d * n);
    Ok(SolveReport::new(
        SolverKind::Nlgs,
        problem,
        params,
        iterations,
        fallbacks,
        r,
    ))
}

/// Updates contact `a`; returns whether the 3D local Newton needed the projection fallback.
#[inline]
fn sweep_contact(
    problem: &FrictionProblem,
    block: &[f64; 9],
    a: usize,
    r: &mut [f64],
    omega: f64,
    local: &LocalParams,
) -> bool {
    let d = problem.dim;
    let w = &problem.w;
    let mut qf = [0.0; 3];
    for (k, qk) in qf.iter_mut().enumerate().take(d) {
        let i = d * a + k;
        let (lo, hi) = (w.row_ptr[i], w.row_ptr[i + 1]);
        let mut s = problem.q[i];
        for (&j, &v) in w.col_idx[lo..hi].iter().zip(&w.values[lo..hi]) {
            s += v * r[j];
        }
        *qk = s;
    }
    let ra = &mut r[d * a..d * (a + 1)];
    for k in 0..d {
        qf[k] -= (0..d).map(|l| block[k * d + l] * ra[l]).sum::<f64>();
    }
    let mu = problem.mu[a];
    let mut fallback = false;
    let mut new = [0.0; 3];
    if d == 2 {
        let b = [block[0], block[1], block[2], block[3]];
        let x = solve_one_contact(&b, [qf[0], qf[1]], mu);
        new[..2].copy_from_slice(&x);
    } else {
        new.copy_from_slice(ra);
        fallback = matches!(
            solve_contact_3d(block, qf, mu, &mut new, local),
            LocalPath::Angle | LocalPath::Projection
        );
    }
    if omega == 1.0 {
        ra.copy_from_slice(&new[..d]);
    } else {
        for k in 0..d {
            ra[k] = omega * new[k] + (1.0 - omega) * ra[k];
        }
        if omega > 1.0 {
            project_on_cone_nd(ra, mu);
        }
    }
    fallback
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shuffle_is_a_deterministic_permutation() {
        let mut a: Vec<usize> = (0..20).collect();
        let mut b = a.clone();
        SplitMix64::new(42).shuffle(&mut a);
        SplitMix64::new(42).shuffle(&mut b);
        assert_eq!(a, b);
        assert_ne!(a, (0..20).collect::<Vec<_>>());
        b.sort_unstable();
        assert_eq!(b, (0..20).collect::<Vec<_>>());
    }
}
