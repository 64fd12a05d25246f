//! What a solve reports: [`SolveInfo`] when it ran (sweeps, residual, LMGC90's norms), and
//! [`SolveError`] when it refused to start or broke down.

use crate::error::{ConvergenceNorms, NormAccumulator};
use crate::nlgs::{ConvergenceNorm, NlgsParams};

/// Outcome of a solve that ran.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct SolveInfo {
    /// Sweeps performed.
    pub iterations: u32,
    /// Value of the chosen measure at the last check, comparable to the tolerance
    /// (for the LMGC90 norms: the largest of the three, times the tolerance).
    pub residual: f64,
    /// Whether the chosen measure went below the tolerance.
    pub converged: bool,
    /// LMGC90's norms at the last check.
    pub norms: ConvergenceNorms,
}

impl SolveInfo {
    /// Records the convergence check after `sweep` from the check sweep's sums `acc` and, for
    /// [`ConvergenceNorm::NaturalMap`], the scaled natural-map error (evaluated only for that
    /// norm); returns whether the solve stops here (converged, or a non-finite residual).
    pub fn record_check(
        &mut self,
        sweep: u32,
        acc: &NormAccumulator,
        params: &NlgsParams,
        natural_map: impl FnOnce() -> f64,
    ) -> bool {
        self.iterations = sweep;
        self.norms = acc.norms(params.tolerance);
        let (residual, converged) = match params.norm {
            ConvergenceNorm::Quad | ConvergenceNorm::Maxm => {
                let m = self.norms.worst(params.norm == ConvergenceNorm::Maxm);
                (m * params.tolerance, m < 1.0)
            }
            ConvergenceNorm::NaturalMap => {
                let e = natural_map();
                (e, e < params.tolerance)
            }
        };
        self.residual = residual;
        self.converged = converged;
        converged || !residual.is_finite()
    }
}

/// A problem the solver refuses to start on.
#[derive(Clone, Debug, PartialEq)]
pub enum SolveError {
    /// Input sizes differ.
    SizeMismatch {
        /// Description.
        what: String,
    },
    /// A non-finite or negative value in the data of a contact.
    InvalidData {
        /// Contact index.
        contact: usize,
        /// Description.
        what: String,
    },
    /// Invalid parameters.
    InvalidParams(String),
    /// The solver does not handle this kind of problem (e.g. Lemke's method in 3D).
    Unsupported(String),
    /// The solver stopped without a usable answer (e.g. Lemke's ray termination).
    Breakdown(String),
}

impl std::fmt::Display for SolveError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            SolveError::SizeMismatch { what } => write!(f, "size mismatch: {what}"),
            SolveError::InvalidData { contact, what } => write!(f, "contact {contact}: {what}"),
            SolveError::InvalidParams(s) => write!(f, "invalid solver parameters: {s}"),
            SolveError::Unsupported(s) => write!(f, "unsupported problem: {s}"),
            SolveError::Breakdown(s) => write!(f, "solver breakdown: {s}"),
        }
    }
}

impl std::error::Error for SolveError {}
