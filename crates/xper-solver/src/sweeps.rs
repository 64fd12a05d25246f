//! The NLGS iteration, on one process or on many: sweeps, a convergence check every
//! `check_every` sweeps, Anderson mixing every `anderson_period` sweeps.
//!
//! ```text
//! for sweep = 1, 2, ..., max_iterations:
//!     one Gauss-Seidel sweep over the contacts            (exchange: glue shared bodies)
//!     every check_every sweeps: norms of a check pass     (exchange: summed over processes)
//!         (LMGC90's: solve each contact without applying; or, stricter, of the sweep itself)
//!         converged -> stop
//!     every anderson_period sweeps: mix the impulses      (exchange: sums, glue again)
//! ```
//!
//! What differs between one process and a domain decomposition is only the exchange between
//! processes ([`SweepExchange`]): [`nlgs`] passes [`OneProcess`], `xper_domain`'s NSCDD passes
//! the gluing of the interface bodies' velocities and the reductions over processes.

use crate::anderson::AndersonMixer;
use crate::cohesive::CohesiveTerm;
use crate::error::NormAccumulator;
use crate::nlgs::{
    scaled_natural_map_error, CheckPass, ConvergenceNorm, NlgsParams, NlgsSweeper, SolveError,
    SolveInfo,
};
use crate::operator::{ContactOperator, VectorOf};

/// What an NLGS iteration exchanges with other processes.
pub trait SweepExchange<O: ContactOperator> {
    /// One sweep of `sweeper` over every contact of `op`, adding each update to `acc` when
    /// given, with the exchanges it needs.
    fn sweep(
        &mut self,
        sweeper: &NlgsSweeper<O::Frame>,
        op: &mut O,
        impulses: &mut [VectorOf<O>],
        acc: Option<&mut NormAccumulator>,
    );
    /// The check sweep's accumulator over all processes.
    fn reduce_norms(&mut self, acc: &NormAccumulator) -> NormAccumulator;
    /// Sums over all processes, in place.
    fn reduce_sums(&mut self, sums: &mut [f64]);
    /// The natural-map error of all contacts, scaled by `max(|q|, |u|, |r|)`.
    fn natural_map_error(
        &mut self,
        sweeper: &NlgsSweeper<O::Frame>,
        op: &O,
        impulses: &[VectorOf<O>],
    ) -> f64;
    /// After the impulses changed outside a sweep (mixing): make the copies agree again.
    fn after_mixing(&mut self, op: &mut O);
}

/// The exchange of a solve on one process: none.
pub struct OneProcess;

impl<O: ContactOperator> SweepExchange<O> for OneProcess {
    #[inline(always)]
    fn sweep(
        &mut self,
        sweeper: &NlgsSweeper<O::Frame>,
        op: &mut O,
        impulses: &mut [VectorOf<O>],
        acc: Option<&mut NormAccumulator>,
    ) {
        sweeper.sweep_accumulating(op, impulses, acc);
    }
    fn reduce_norms(&mut self, acc: &NormAccumulator) -> NormAccumulator {
        *acc
    }
    fn reduce_sums(&mut self, _sums: &mut [f64]) {}
    fn natural_map_error(
        &mut self,
        sweeper: &NlgsSweeper<O::Frame>,
        op: &O,
        impulses: &[VectorOf<O>],
    ) -> f64 {
        let (mu, shift) = (sweeper.mu(), sweeper.normal_shift());
        scaled_natural_map_error(op, mu, shift, impulses, sweeper.q_norm())
    }
    fn after_mixing(&mut self, _op: &mut O) {}
}

/// Sweeps `sweeper` over `op` until its convergence test passes or `params.max_iterations`
/// sweeps are done (the report says which); `impulses` (warm start applied to `op` by
/// [`NlgsSweeper::new`]) hold the result. The problem has at least one contact on some
/// process.
pub fn sweep_until_converged<O: ContactOperator, X: SweepExchange<O>>(
    sweeper: &NlgsSweeper<O::Frame>,
    op: &mut O,
    impulses: &mut [VectorOf<O>],
    params: &NlgsParams,
    exchange: &mut X,
) -> SolveInfo {
    let mut info = SolveInfo::default();
    let mut anderson = AndersonMixer::for_params(params, impulses);
    for sweep in 1..=params.max_iterations {
        let check = sweep % params.check_every == 0 || sweep == params.max_iterations;
        let in_sweep = check && params.check == CheckPass::Strict;
        let mut acc = NormAccumulator::default();
        exchange.sweep(sweeper, op, impulses, in_sweep.then_some(&mut acc));
        if check {
            // The natural-map error needs no pass of LMGC90's norms.
            if !in_sweep && params.norm != ConvergenceNorm::NaturalMap {
                sweeper.check_pass(op, impulses, 0..impulses.len(), &mut acc);
            }
            let global = exchange.reduce_norms(&acc);
            let error = || exchange.natural_map_error(sweeper, op, impulses);
            if info.record_check(sweep, &global, params, error) {
                return info;
            }
        }
        if let Some(mixer) = anderson.as_mut() {
            if mixer.mixes_after(sweep, params.max_iterations) {
                sweeper.accelerate(op, impulses, mixer, |sums| exchange.reduce_sums(sums));
                exchange.after_mixing(op);
            }
        }
    }
    info.iterations = params.max_iterations;
    info
}

/// Solves the problem of `op` by NLGS.
///
/// `op` must be in the state of zero impulses; `impulses` holds the warm start on entry and the
/// solution on exit (and `op` is left consistent with it). `normal_shift[a]` is added to the
/// normal velocity in the Signorini condition.
pub fn nlgs<O: ContactOperator>(
    op: &mut O,
    mu: &[f64],
    normal_shift: &[f64],
    impulses: &mut [VectorOf<O>],
    params: &NlgsParams,
) -> Result<SolveInfo, SolveError> {
    nlgs_with_cohesion(op, mu, normal_shift, &[], impulses, params)
}

/// [`nlgs`] where contact `a`'s impulse has the adhesive part `cohesion[a]` (see
/// [`CohesiveTerm`]); `cohesion` is empty (no adhesion anywhere) or has one term per contact.
/// `impulses` are the total impulses, adhesive part included.
pub fn nlgs_with_cohesion<O: ContactOperator>(
    op: &mut O,
    mu: &[f64],
    normal_shift: &[f64],
    cohesion: &[CohesiveTerm],
    impulses: &mut [VectorOf<O>],
    params: &NlgsParams,
) -> Result<SolveInfo, SolveError> {
    let sweeper = NlgsSweeper::new(op, mu, normal_shift, cohesion, impulses, params)?;
    if op.contact_count() == 0 {
        return Ok(SolveInfo {
            converged: true,
            ..SolveInfo::default()
        });
    }
    Ok(sweep_until_converged(
        &sweeper,
        op,
        impulses,
        params,
        &mut OneProcess,
    ))
}
