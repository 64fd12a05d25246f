//! Who solves the contact problem of a step: NLGS on this process alone
//! ([`OneProcessSolve`]), or a solver shared with other processes (a domain decomposition,
//! in `xper_domain`), for rigid bodies and deformable elements alike: the steppers of both
//! (`xper_nscd::MoreauJean::step_with`, `xper_fracture::FractureStepper::step_with`) take a
//! `&mut dyn ContactSolve<TheirOperator>`.

use crate::cohesive::CohesiveTerm;
use crate::nlgs::{NlgsParams, SolveError, SolveInfo};
use crate::operator::{ContactOperator, VectorOf};
use crate::sweeps::nlgs_with_cohesion;

/// The contact solve of a step and the reductions over the processes sharing it.
pub trait ContactSolve<O: ContactOperator> {
    /// Solves the problem of `op` (zero impulses applied; `cohesion` empty or the adhesive
    /// term of each row; `impulses` the warm start on entry and the solution on exit) as
    /// [`crate::nlgs_with_cohesion`] does, together with the other processes; every process
    /// gets the same outcome.
    fn solve(
        &mut self,
        op: &mut O,
        mu: &[f64],
        shift: &[f64],
        cohesion: &[CohesiveTerm],
        impulses: &mut [VectorOf<O>],
        params: &NlgsParams,
    ) -> Result<SolveInfo, SolveError>;
    /// Replaces each value by its sum over the processes (identity on one).
    fn sum(&mut self, values: &mut [f64]);
    /// The largest `value` over the processes, for decisions they must all take alike.
    fn max(&mut self, value: f64) -> f64;
}

/// [`ContactSolve`] on this process alone: [`nlgs_with_cohesion`], reductions the identity.
#[derive(Clone, Copy, Debug, Default)]
pub struct OneProcessSolve;

impl<O: ContactOperator> ContactSolve<O> for OneProcessSolve {
    fn solve(
        &mut self,
        op: &mut O,
        mu: &[f64],
        shift: &[f64],
        cohesion: &[CohesiveTerm],
        impulses: &mut [VectorOf<O>],
        params: &NlgsParams,
    ) -> Result<SolveInfo, SolveError> {
        nlgs_with_cohesion(op, mu, shift, cohesion, impulses, params)
    }
    fn sum(&mut self, _values: &mut [f64]) {}
    fn max(&mut self, value: f64) -> f64 {
        value
    }
}
