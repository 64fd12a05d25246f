//! `xper solve FILE`: read a frictional contact problem written by another code (Siconos text
//! `.dat`, FCLib HDF5 `.hdf5`/`.h5`; local or global form), solve it and print one JSON object.
//!
//! Global problems (`M v = H r + f`, `u = H^T v + w`) are reduced to the local form
//! `W = H^T M^-1 H`, `q = H^T M^-1 f + w` first (see `xper_fclib`). The error printed is the
//! shared natural-map error of `xper_solver::error_measure` under both published scalings
//! (`|q|`, and `max(|q|, |r|, |u|)`), see `../shared/fclib/FORMATS.md`.

use serde::Serialize;
use std::path::{Path, PathBuf};
use std::time::Instant;
use xper_fclib::{read_local, ReadAs};
use xper_simulation::RunError;
use xper_solver::{solve_timed, ErrorScaling, FrictionProblem, ProblemErrorMeasure, SolverKind};

/// Solver names accepted on the command line.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum SolverArg {
    /// Non-smooth Gauss-Seidel (the 2D exact local solve; 3D Alart-Curnier local Newton).
    Nlgs,
    /// Alias of `nlgs`.
    Nsgs,
    /// Generalized Newton on the Alart-Curnier function.
    Newton,
    /// Proximal-point iterations around the generalized Newton (rank-deficient W); also
    /// `proximal_newton`, as scenes and reports write it.
    #[value(alias = "proximal_newton")]
    ProximalNewton,
    /// Lemke's pivoting on the LCP form (2D only; exact reference for small problems).
    Lemke,
}

impl SolverArg {
    /// The library's solver.
    pub fn kind(self) -> SolverKind {
        match self {
            SolverArg::Nlgs | SolverArg::Nsgs => SolverKind::Nlgs,
            SolverArg::Newton => SolverKind::Newton,
            SolverArg::ProximalNewton => SolverKind::ProximalNewton,
            SolverArg::Lemke => SolverKind::Lemke,
        }
    }
}

/// Which scaling of the error decides convergence.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum ScalingArg {
    /// `|e| / |q|` (the published comparisons).
    Q,
    /// `|e| / max(|q|, |r|, |u|)` (Siconos since 2020).
    Max,
}

/// How a `.dat` file is read.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum FormArg {
    /// Decide from the content.
    Auto,
    /// `d, nc, W, q, mu`.
    Local,
    /// `d, nc, M, H, f, w, mu`.
    Global,
}

/// Arguments of `xper solve`.
#[derive(clap::Args, Debug)]
pub struct SolveArgs {
    /// Problem file: Siconos `.dat` or FCLib `.hdf5`/`.h5`.
    pub file: PathBuf,
    /// Solver.
    #[arg(long, value_enum, default_value_t = SolverArg::Nlgs)]
    pub solver: SolverArg,
    /// Tolerance on the scaled error.
    #[arg(long, default_value_t = 1e-8, allow_negative_numbers = true)]
    pub tol: f64,
    /// Iteration limit (sweeps, Newton iterations, proximal steps, pivots); default per solver.
    #[arg(long)]
    pub max_iter: Option<u32>,
    /// Scaling of the error compared with `--tol`.
    #[arg(long, value_enum, default_value_t = ScalingArg::Max)]
    pub scaling: ScalingArg,
    /// Layout of a `.dat` file.
    #[arg(long, value_enum, default_value_t = FormArg::Auto)]
    pub form: FormArg,
    /// Also write the solution (`r`, `u`) as JSON to this file.
    #[arg(long)]
    pub solution: Option<PathBuf>,
}

/// What `xper solve` prints.
#[derive(Clone, Debug, Serialize)]
pub struct SolveOutput {
    /// The problem file.
    pub file: String,
    /// Solver name.
    pub solver: String,
    /// 2 or 3.
    pub dimension: usize,
    /// Number of contacts.
    pub contacts: usize,
    /// "local" or "global" (reduced to local before solving).
    pub form: &'static str,
    /// Iterations of the solver.
    pub iterations: u32,
    /// Inner iterations (see `xper_solver::SolveReport`).
    pub inner_iterations: u64,
    /// The shared error under both scalings (and unscaled).
    pub error: ProblemErrorMeasure,
    /// Tolerance asked.
    pub tolerance: f64,
    /// "q" or "max".
    pub scaling: &'static str,
    /// Whether the error reached the tolerance.
    pub converged: bool,
    /// Wall time of the solve (s), reading and reduction excluded.
    pub wall_time_s: f64,
    /// Wall time of reading the file and reducing a global problem (s).
    pub read_time_s: f64,
}

/// Reads a problem and reduces it to the local form.
pub fn load_local(path: &Path, form: FormArg) -> Result<(FrictionProblem, &'static str), RunError> {
    let how = match form {
        FormArg::Auto => ReadAs::Auto,
        FormArg::Local => ReadAs::Local,
        FormArg::Global => ReadAs::Global,
    };
    read_local(path, how).map_err(RunError::BadInput)
}

/// Runs `xper solve`: prints the JSON; an unconverged solve is an error (exit 1) after printing.
pub fn run_solve(args: &SolveArgs) -> Result<(), RunError> {
    if !(args.tol > 0.0 && args.tol.is_finite()) {
        return Err(RunError::BadInput(format!(
            "--tol {}: must be a positive number{}",
            args.tol,
            if args.tol < 0.0 {
                " (it is negative)"
            } else {
                ""
            }
        )));
    }
    let start = Instant::now();
    let (problem, form) = load_local(&args.file, args.form)?;
    let read_time_s = start.elapsed().as_secs_f64();
    let scaling = match args.scaling {
        ScalingArg::Q => ErrorScaling::RelativeQ,
        ScalingArg::Max => ErrorScaling::RelativeMax,
    };
    let (report, wall_time_s) = solve_timed(
        &problem,
        args.solver.kind(),
        args.tol,
        args.max_iter,
        scaling,
    )
    .map_err(|e| RunError::BadInput(format!("{}: {e}", args.file.display())))?;
    let output = SolveOutput {
        file: args.file.display().to_string(),
        solver: report.solver.clone(),
        dimension: problem.dim,
        contacts: problem.contact_count(),
        form,
        iterations: report.iterations,
        inner_iterations: report.inner_iterations,
        error: report.error,
        tolerance: args.tol,
        scaling: match args.scaling {
            ScalingArg::Q => "q",
            ScalingArg::Max => "max",
        },
        converged: report.converged,
        wall_time_s,
        read_time_s,
    };
    let json = serde_json::to_string_pretty(&output)
        .map_err(|e| RunError::Runtime(format!("JSON: {e}")))?;
    println!("{json}");
    if let Some(path) = &args.solution {
        let solution = serde_json::json!({ "r": report.r, "u": report.u });
        xper_io::write_json_atomic(path, &solution)
            .map_err(|e| RunError::Runtime(format!("{}: {e}", path.display())))?;
    }
    if report.converged {
        Ok(())
    } else {
        Err(RunError::Runtime(format!(
            "{}: {} stopped after {} iterations at error {:.3e} (tolerance {:.1e})",
            args.file.display(),
            report.solver,
            report.iterations,
            scaling.pick(&report.error),
            args.tol
        )))
    }
}
