//! Who solves the interface problem of a step: NLGS on one process, or a domain-decomposition
//! solver when the model is a part of a distributed one (the `xper-domain` crate). The
//! stepper also asks it to sum the step's totals over the processes.

use xper_solver::{nlgs_with_cohesion, CohesiveTerm, NlgsParams, SolveError, SolveInfo};

use crate::operator::ElementContactOperator;

/// The interface solve of a step and the sums over the processes sharing the model.
pub trait InterfaceSolve {
    /// Solves the problem of `op` (element velocities at their free values, no impulse
    /// applied; `cohesion` the adhesive term of each row): `impulses` holds the warm start on
    /// entry and the solution on exit, the element velocities end at their new values.
    fn solve(
        &mut self,
        op: &mut ElementContactOperator,
        mu: &[f64],
        shift: &[f64],
        cohesion: &[CohesiveTerm],
        impulses: &mut [[f64; 2]],
        params: &NlgsParams,
    ) -> Result<SolveInfo, SolveError>;

    /// Replaces each value by its sum over the processes sharing the model (identity on one).
    fn sum(&mut self, values: &mut [f64]);
}

/// [`InterfaceSolve`] by [`nlgs_with_cohesion`] on a whole model.
#[derive(Clone, Copy, Debug, Default)]
pub struct SerialInterfaceSolve;

impl InterfaceSolve for SerialInterfaceSolve {
    fn solve(
        &mut self,
        op: &mut ElementContactOperator,
        mu: &[f64],
        shift: &[f64],
        cohesion: &[CohesiveTerm],
        impulses: &mut [[f64; 2]],
        params: &NlgsParams,
    ) -> Result<SolveInfo, SolveError> {
        nlgs_with_cohesion(op, mu, shift, cohesion, impulses, params)
    }

    fn sum(&mut self, _values: &mut [f64]) {}
}
