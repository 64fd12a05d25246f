//! Proximal-point stabilisation of the generalized Newton method, for rank-deficient `W`.
//!
//! ```text
//! r_0 = warm start, e_0 its error
//! r_k+1 solves  u = (W + sigma_k I) r + (q - sigma_k r_k),  Signorini-Coulomb(u, r)
//!               (Newton on Alart-Curnier's function, crate::newton, started at r_k,
//!                at most `inner_iterations`, to the tolerance e_k / inner_ratio)
//! inner solve reached its tolerance:  sigma_k+1 = max(c s_W e_k+1^nu, sigma_k / max_decrease)
//! otherwise:  r_k+1 = the better of r_k and the inner solve's best iterate,
//!             sigma_k+1 = 10 sigma_k
//! ```
//!
//! A fixed point `r_k+1 = r_k` solves the original problem, and `W + sigma I` is non-singular
//! for `sigma > 0`, so each Newton matrix is invertible even when `W` has more rows than the
//! bodies have degrees of freedom. This is the proximal-point method of Acary, Bremond,
//! Huber (2018, section "proximal point algorithm"; Siconos' `fc3d_proximal`, "PROX"
//! strategy: `sigma = 5 e^1`, tenfold increase after a failed inner solve). Differences, all
//! measured on the FCLib problems (Capsules, BoxesStack, spheres, 2D granular flows):
//! - `sigma` is proportional to `s_W`, the mean diagonal of `W`, so that the method does not
//!   depend on units; the factor `c = 0.1` (larger values stall on BoxesStack, smaller ones
//!   make inner solves fail on the 2D granular flows);
//! - `sigma` decreases at most fourfold per step: dropping it with the error (by 100x at
//!   once) made the next inner solve fail and cost more than it saved;
//! - a failed inner solve does not move the center to its last (possibly worse) iterate.
//!
//! Each inner solve also stops as soon as the original problem's error reaches the
//! tolerance, and the report holds the iterate of smallest original error.

use crate::newton::NewtonCore;
use crate::nlgs::SolveError;
use crate::problem::FrictionProblem;
use crate::solve::{prepare, scaled_error, SolveReport, SolverKind, SolverParams};

/// Tuning of the proximal-point method.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ProximalParams {
    /// `c` in `sigma = c s_W e^nu`.
    pub sigma_factor: f64,
    /// Exponent `nu` of the error in `sigma`.
    pub nu: f64,
    /// Bounds of `sigma / s_W`.
    pub sigma_min: f64,
    /// Upper bound of `sigma / s_W`.
    pub sigma_max: f64,
    /// Newton iterations per proximal step.
    pub inner_iterations: u32,
    /// The inner tolerance is the current error divided by this.
    pub inner_ratio: f64,
    /// After a successful proximal step `sigma` decreases at most by this factor.
    pub max_decrease: f64,
}

impl Default for ProximalParams {
    fn default() -> Self {
        ProximalParams {
            sigma_factor: 0.1,
            nu: 1.0,
            sigma_min: 1e-10,
            sigma_max: 1e6,
            inner_iterations: 10,
            inner_ratio: 10.0,
            max_decrease: 4.0,
        }
    }
}

/// Solves `problem` by proximal-point iterations around the generalized Newton method,
/// from `warm_start` (zero when `None`). `params.max_iterations` bounds the proximal steps.
pub fn proximal_newton(
    problem: &FrictionProblem,
    params: &SolverParams,
    warm_start: Option<&[f64]>,
) -> Result<SolveReport, SolveError> {
    let (blocks, mut r) = prepare(problem, params, warm_start)?;
    let kind = SolverKind::ProximalNewton;
    if problem.mu.is_empty() {
        return Ok(SolveReport::new(kind, problem, params, 0, 0, r));
    }
    let pp = &params.proximal;
    if !(pp.sigma_factor > 0.0
        && pp.sigma_min > 0.0
        && pp.sigma_max >= pp.sigma_min
        && pp.inner_ratio >= 1.0
        && pp.inner_iterations > 0
        && pp.nu.is_finite())
    {
        return Err(SolveError::InvalidParams(format!("{pp:?}")));
    }
    let d = problem.dim;
    let s_w = blocks.iter().map(|b| b[0]).sum::<f64>() / blocks.len() as f64
        + blocks
            .iter()
            .map(|b| (1..d).map(|k| b[k * d + k].max(0.0)).sum::<f64>())
            .sum::<f64>()
            / (blocks.len() * (d - 1)) as f64;
    let s_w = 0.5 * s_w;
    let sigma_of =
        |e: f64| s_w * (pp.sigma_factor * e.powf(pp.nu)).clamp(pp.sigma_min, pp.sigma_max);
    let mut core = NewtonCore::new(problem, &blocks, &params.newton)?;
    let mut u = vec![0.0; r.len()];
    let mut error = scaled_error(problem, &r, &mut u, params.scaling);
    let mut best = (error, r.clone());
    let mut sigma = sigma_of(error.min(1.0));
    let mut q_eff = vec![0.0; r.len()];
    let mut center = r.clone();
    let mut inner_total = 0u64;
    let mut steps = 0;
    for step in 1..=params.max_iterations {
        if error < params.tolerance || error.is_nan() {
            break;
        }
        steps = step;
        center.copy_from_slice(&r);
        for i in 0..r.len() {
            q_eff[i] = problem.q[i] - sigma * r[i];
        }
        let inner_tol = (error / pp.inner_ratio).max(0.1 * params.tolerance);
        let out = core.run(
            &q_eff,
            sigma,
            &mut r,
            pp.inner_iterations,
            params.tolerance,
            inner_tol,
            params.scaling,
        );
        inner_total += u64::from(out.iterations);
        if out.best_error < best.0 {
            best = (out.best_error, core.best().to_vec());
        }
        if out.inner_converged || out.error < params.tolerance {
            error = out.error;
            sigma = sigma_of(error).max(sigma / pp.max_decrease);
        } else {
            // Failed inner solve: restart from the better of the center and the inner
            // solve's best iterate, with a stronger regularization.
            if out.best_error < error {
                error = out.best_error;
                r.copy_from_slice(core.best());
            } else {
                r.copy_from_slice(&center);
            }
            sigma = (10.0 * sigma).min(s_w * pp.sigma_max);
        }
    }
    Ok(SolveReport::new(
        kind,
        problem,
        params,
        steps,
        inner_total,
        best.1,
    ))
}
