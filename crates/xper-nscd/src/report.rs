//! What a step reports: stage timings, solver figures and the energy budget, or why it failed.

use xper_math::Real;
use xper_solver::{ConvergenceNorms, SolveError};

/// Wall time of the stages of one step (s).
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct StageTimes {
    /// Broad and narrow phase.
    pub detect: f64,
    /// The velocity problem: NLGS, or assembly of `W` and the assembled problem's solver.
    pub solve: f64,
    /// The position projection.
    pub project: f64,
    /// The whole step.
    pub total: f64,
}

/// What happened during one step.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct StepReport {
    /// Index of the step just done (1-based).
    pub step: u64,
    /// Time at the end of the step (s).
    pub time: Real,
    /// Contacts within the alert distance.
    pub contacts: usize,
    /// Contacts in the velocity problem (predicted gap closed).
    pub active: usize,
    /// NLGS sweeps, or the assembled problem's solver iterations (Newton iterations, ...).
    pub iterations: u32,
    /// Final value of the convergence measure (for an assembled solve: the natural-map
    /// error under the solver's scaling).
    pub residual: Real,
    /// Whether the solver reached the tolerance.
    pub converged: bool,
    /// LMGC90 norms at the last check (zero for an assembled solve).
    pub norms: ConvergenceNorms,
    /// NLGS sweeps of the position projection (0 when it did not run).
    pub projection_iterations: u32,
    /// Largest overlap before projection (m, >= 0).
    pub max_overlap: Real,
    /// Kinetic energy (J/m).
    pub kinetic: Real,
    /// Potential energy (J/m).
    pub potential: Real,
    /// Dissipated energy since the start (J/m).
    pub dissipated: Real,
    /// External work since the start (J/m).
    pub external_work: Real,
    /// Potential energy added by position projections since the start (J/m).
    pub projection_work: Real,
    /// Energy balance error (J/m).
    pub energy_error: Real,
    /// Stage timings.
    pub times: StageTimes,
}

/// A step that could not be completed; the world is left as it was after the failing stage.
#[derive(Clone, Debug, PartialEq)]
pub enum StepError {
    /// The solver refused the problem.
    Solver(SolveError),
    /// A position or velocity became NaN or infinite.
    NonFinite {
        /// Body index.
        body: usize,
    },
    /// The energy balance error exceeded the scale of the energy budget.
    EnergyBlowUp {
        /// Balance error (J/m).
        error: Real,
        /// Budget scale (J/m).
        scale: Real,
    },
}

impl std::fmt::Display for StepError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            StepError::Solver(e) => write!(f, "contact solver: {e}"),
            StepError::NonFinite { body } => write!(f, "body {body} has a non-finite position or velocity"),
            StepError::EnergyBlowUp { error, scale } => write!(
                f,
                "energy blow-up: balance error {error:.3e} J/m exceeds the energy scale {scale:.3e} J/m"
            ),
        }
    }
}

impl std::error::Error for StepError {}

/// Whether a step's energy balance error shows a blow-up: an error above the scale of the
/// energy budget (`scale`, J/m), or an error or a scale that is not finite (energies that
/// overflowed, as under an absurd gravity, must stop the run rather than compare false).
pub fn energy_blown_up(error: Real, scale: Real) -> bool {
    !(error.is_finite() && scale.is_finite() && error <= scale.max(1e-12))
}
