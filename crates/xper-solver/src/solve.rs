//! One entry point for the solvers of assembled problems [`FrictionProblem`]
//! (`u = W r + q`, Signorini-Coulomb per contact), and the checks they share.
//!
//! ```text
//! find r:  u = W r + q,  K*_a ∋ u_a + mu_a |u_T,a| e_n  ⊥  r_a ∈ K_a   for every contact a
//! ```
//!
//! with `K_a = {|r_T| <= mu_a r_N}` the Coulomb cone (De Saxcé's formulation, as in Acary,
//! Bremond, Huber 2018). Every solver is judged by the shared [`error_measure`] under the
//! [`ErrorScaling`] chosen in [`SolverParams`]; a solver that stops above the tolerance returns
//! a report with `converged = false` (never silently), and a problem it cannot start on
//! (sizes, non-finite data, `W_nn <= 0`) is an [`SolveError`], never a panic.
//!
//! | solver | method | use |
//! |---|---|---|
//! | [`SolverKind::Nlgs`] | non-smooth Gauss-Seidel over contacts ([`crate::nsgs`]) | robust default, rigid bodies |
//! | [`SolverKind::Newton`] | semi-smooth Newton on Alart-Curnier's function ([`crate::newton`]) | full-rank `W` |
//! | [`SolverKind::ProximalNewton`] | proximal point around the Newton solver ([`crate::proximal`]) | rank-deficient `W` |
//! | [`SolverKind::Lemke`] | Lemke's pivoting on the 2D LCP ([`crate::lemke`]) | exact reference, small 2D |

use crate::lemke::{lemke, LemkeParams};
use crate::newton::{newton, NewtonParams};
use crate::nlgs::SolveError;
use crate::nsgs::{nsgs, NsgsParams};
use crate::problem::{error_measure, FrictionProblem, ProblemErrorMeasure};
use crate::proximal::{proximal_newton, ProximalParams};

/// Which solver [`solve`] runs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum SolverKind {
    /// Non-smooth (non-linear) Gauss-Seidel over contacts.
    #[default]
    Nlgs,
    /// Generalized Newton on the Alart-Curnier function, sparse LU, line search.
    Newton,
    /// Proximal-point iterations, each solved by the generalized Newton method.
    ProximalNewton,
    /// Lemke's complementary pivoting on the LCP form of 2D Coulomb friction (2D only).
    Lemke,
}

impl SolverKind {
    /// Short name used in reports: the name a scene's `[solver] kind` gives it (the command
    /// line accepts it too).
    pub fn name(self) -> &'static str {
        match self {
            SolverKind::Nlgs => "nlgs",
            SolverKind::Newton => "newton",
            SolverKind::ProximalNewton => "proximal_newton",
            SolverKind::Lemke => "lemke",
        }
    }
}

/// Which scaling of the shared error decides convergence.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum ErrorScaling {
    /// `|e|`, unscaled.
    Absolute,
    /// `|e| / |q|` (Acary, Bremond, Huber 2018).
    RelativeQ,
    /// `|e| / max(|q|, |r|, |u|)` (Siconos since 2020).
    #[default]
    RelativeMax,
}

impl ErrorScaling {
    /// The value of `e` under this scaling.
    pub fn pick(self, e: &ProblemErrorMeasure) -> f64 {
        match self {
            ErrorScaling::Absolute => e.absolute,
            ErrorScaling::RelativeQ => e.relative_q,
            ErrorScaling::RelativeMax => e.relative_max,
        }
    }
}

/// Tuning of [`solve`]: the fields every solver reads, then each solver's own.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct SolverParams {
    /// The solver.
    pub kind: SolverKind,
    /// Convergence when the shared error, scaled by `scaling`, is below this (default 1e-8,
    /// the tolerance of the published comparisons on Siconos' problems).
    pub tolerance: f64,
    /// Iteration limit: sweeps (NSGS), Newton iterations (Newton; proximal steps for the
    /// proximal method) or pivots (Lemke; 0 means the automatic bound).
    pub max_iterations: u32,
    /// Scaling of the error compared to `tolerance`.
    pub scaling: ErrorScaling,
    /// NSGS relaxation, shuffling, local solver.
    pub nsgs: NsgsParams,
    /// Generalized Newton: rho, line search.
    pub newton: NewtonParams,
    /// Proximal point: sigma strategy, inner iterations.
    pub proximal: ProximalParams,
    /// Lemke: pivot tolerance.
    pub lemke: LemkeParams,
}

impl Default for SolverParams {
    fn default() -> Self {
        SolverParams {
            kind: SolverKind::Nlgs,
            tolerance: 1e-8,
            max_iterations: 10_000,
            scaling: ErrorScaling::RelativeMax,
            nsgs: NsgsParams::default(),
            newton: NewtonParams::default(),
            proximal: ProximalParams::default(),
            lemke: LemkeParams::default(),
        }
    }
}

impl SolverParams {
    /// Default parameters for `kind`, with the iteration limit suited to it.
    pub fn with_kind(kind: SolverKind) -> Self {
        let max_iterations = match kind {
            SolverKind::Nlgs => 10_000,
            SolverKind::Newton => 200,
            SolverKind::ProximalNewton => 100,
            SolverKind::Lemke => 0,
        };
        SolverParams {
            kind,
            max_iterations,
            ..Default::default()
        }
    }
}

/// The outcome of a solve that ran.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct SolveReport {
    /// Solver name ([`SolverKind::name`]).
    pub solver: String,
    /// Iterations done (sweeps, Newton iterations, proximal steps or pivots).
    pub iterations: u32,
    /// Inner iterations (Newton iterations of the proximal method; local Newton failures
    /// rescued by the projection for NSGS; 0 otherwise).
    pub inner_iterations: u64,
    /// The shared error of `r` under both scalings.
    pub error: ProblemErrorMeasure,
    /// Whether the error (scaled as asked) is below the tolerance.
    pub converged: bool,
    /// Impulses, `dim n`.
    pub r: Vec<f64>,
    /// Local velocities `u = W r + q`.
    pub u: Vec<f64>,
}

impl SolveReport {
    /// A report for `r`, with `u` and the error computed from the problem.
    pub(crate) fn new(
        kind: SolverKind,
        problem: &FrictionProblem,
        params: &SolverParams,
        iterations: u32,
        inner_iterations: u64,
        r: Vec<f64>,
    ) -> Self {
        let u = problem.velocity(&r);
        let error = error_measure(problem.dim, &problem.q, &u, &r, &problem.mu);
        let e = params.scaling.pick(&error);
        SolveReport {
            solver: kind.name().to_string(),
            iterations,
            inner_iterations,
            error,
            converged: e.is_finite() && e < params.tolerance,
            r,
            u,
        }
    }
}

/// Solves `problem` with the solver of `params.kind`, starting from `warm_start` (zero when
/// `None`; Lemke ignores it).
pub fn solve(
    problem: &FrictionProblem,
    params: &SolverParams,
    warm_start: Option<&[f64]>,
) -> Result<SolveReport, SolveError> {
    match params.kind {
        SolverKind::Nlgs => nsgs(problem, params, warm_start),
        SolverKind::Newton => newton(problem, params, warm_start),
        SolverKind::ProximalNewton => proximal_newton(problem, params, warm_start),
        SolverKind::Lemke => lemke(problem, params),
    }
}

/// [`solve`] from zero with the solver `kind`, tolerance `tol` under `scaling` and at most
/// `max_iter` iterations (the solver's default when `None`); returns the report and the wall
/// time of the solve (s).
pub fn solve_timed(
    problem: &FrictionProblem,
    kind: SolverKind,
    tol: f64,
    max_iter: Option<u32>,
    scaling: ErrorScaling,
) -> Result<(SolveReport, f64), SolveError> {
    let mut params = SolverParams::with_kind(kind);
    params.tolerance = tol;
    params.scaling = scaling;
    if let Some(n) = max_iter {
        params.max_iterations = n;
    }
    let start = std::time::Instant::now();
    let report = solve(problem, &params, None)?;
    Ok((report, start.elapsed().as_secs_f64()))
}

/// Checks the problem, the parameters and the warm start; returns the diagonal blocks of `W`
/// (row-major `dim x dim` in a `[f64; 9]`) and the starting `r`.
pub(crate) fn prepare(
    problem: &FrictionProblem,
    params: &SolverParams,
    warm_start: Option<&[f64]>,
) -> Result<(Vec<[f64; 9]>, Vec<f64>), SolveError> {
    check_params(params)?;
    let blocks = check_problem(problem)?;
    let m = problem.q.len();
    let r = match warm_start {
        None => vec![0.0; m],
        Some(r0) => {
            if r0.len() != m {
                return Err(SolveError::SizeMismatch {
                    what: format!("warm start of length {} for {m} unknowns", r0.len()),
                });
            }
            if let Some(k) = r0.iter().position(|x| !x.is_finite()) {
                return Err(SolveError::InvalidData {
                    contact: k / problem.dim,
                    what: format!("warm start r[{k}] = {}", r0[k]),
                });
            }
            r0.to_vec()
        }
    };
    Ok((blocks, r))
}

pub(crate) fn check_params(params: &SolverParams) -> Result<(), SolveError> {
    if !(params.tolerance.is_finite() && params.tolerance > 0.0) {
        return Err(SolveError::InvalidParams(format!(
            "tolerance {} is not a positive number",
            params.tolerance
        )));
    }
    if params.max_iterations == 0 && params.kind != SolverKind::Lemke {
        return Err(SolveError::InvalidParams("max_iterations is 0".into()));
    }
    Ok(())
}

/// Checks sizes, CSR structure, finiteness and `W_nn > 0`; returns the diagonal blocks.
pub(crate) fn check_problem(problem: &FrictionProblem) -> Result<Vec<[f64; 9]>, SolveError> {
    let d = problem.dim;
    if d != 2 && d != 3 {
        return Err(SolveError::InvalidData {
            contact: 0,
            what: format!("dimension {d} is not 2 or 3"),
        });
    }
    let n = problem.mu.len();
    let m = d * n;
    let w = &problem.w;
    if w.nrows != m || w.ncols != m || problem.q.len() != m {
        return Err(SolveError::SizeMismatch {
            what: format!(
                "{n} contacts in {d}D: W {} x {}, q of length {}",
                w.nrows,
                w.ncols,
                problem.q.len()
            ),
        });
    }
    let csr_ok = w.row_ptr.len() == m + 1
        && w.row_ptr[0] == 0
        && w.row_ptr.windows(2).all(|p| p[0] <= p[1])
        && w.row_ptr[m] == w.col_idx.len()
        && w.col_idx.len() == w.values.len()
        && (0..m).all(|i| {
            let cols = &w.col_idx[w.row_ptr[i]..w.row_ptr[i + 1]];
            cols.windows(2).all(|c| c[0] < c[1]) && cols.iter().all(|&j| j < m)
        });
    if !csr_ok {
        return Err(SolveError::SizeMismatch {
            what: "W is not a valid CSR matrix (pointers, sorted column indices)".into(),
        });
    }
    let mut blocks = vec![[0.0; 9]; n];
    for (a, block) in blocks.iter_mut().enumerate() {
        let mu = problem.mu[a];
        if !(mu.is_finite() && mu >= 0.0) {
            return Err(SolveError::InvalidData {
                contact: a,
                what: format!("friction coefficient {mu}"),
            });
        }
        for k in 0..d {
            let i = d * a + k;
            if !problem.q[i].is_finite() {
                return Err(SolveError::InvalidData {
                    contact: a,
                    what: format!("q[{i}] = {}", problem.q[i]),
                });
            }
            for e in w.row_ptr[i]..w.row_ptr[i + 1] {
                let (j, v) = (w.col_idx[e], w.values[e]);
                if !v.is_finite() {
                    return Err(SolveError::InvalidData {
                        contact: a,
                        what: format!("W[{i}, {j}] = {v}"),
                    });
                }
                if j / d == a {
                    block[k * d + j % d] = v;
                }
            }
        }
        if block[0] <= 0.0 {
            return Err(SolveError::InvalidData {
                contact: a,
                what: format!("W_nn = {} is not positive", block[0]),
            });
        }
    }
    Ok(blocks)
}

/// The error of `r` under `scaling`, computing `u` into `u`.
pub(crate) fn scaled_error(
    problem: &FrictionProblem,
    r: &[f64],
    u: &mut [f64],
    scaling: ErrorScaling,
) -> f64 {
    u.copy_from_slice(&problem.q);
    problem.w.mul_add(r, u);
    scaling.pick(&error_measure(problem.dim, &problem.q, u, r, &problem.mu))
}
