//! Outputs of a rigid run besides the frames: `series.csv` columns and rows, `summary.json`,
//! `series.png` and the contact problems of the steps listed in `[output] dump_problems`.

use crate::comparison::SerialComparison;
use crate::ranks::RankSummary;
use crate::run_outputs::{self as outputs, io_err, mean, series_curve};
use crate::RunError;
use serde::Serialize;
use std::path::{Path, PathBuf};
use xper_io::{plot_panels, Curve, SeriesTable};
use xper_nscd::StepReport;

/// Columns of `series.csv`, one row per step.
pub const SERIES_COLUMNS: [&str; 18] = [
    "step",
    "time",
    "kinetic_energy",
    "potential_energy",
    "dissipated_energy",
    "external_work",
    "projection_work",
    "energy_error",
    "contacts",
    "active_contacts",
    "iterations",
    "residual",
    "converged",
    "projection_iterations",
    "max_overlap",
    "wall_time",
    "detect_time",
    "solve_time",
];

/// The `series.csv` row of a step.
pub fn series_row(r: &StepReport) -> Vec<f64> {
    vec![
        r.step as f64,
        r.time,
        r.kinetic,
        r.potential,
        r.dissipated,
        r.external_work,
        r.projection_work,
        r.energy_error,
        r.contacts as f64,
        r.active as f64,
        r.iterations as f64,
        r.residual,
        r.converged as u8 as f64,
        r.projection_iterations as f64,
        r.max_overlap,
        r.times.total,
        r.times.detect,
        r.times.solve,
    ]
}

/// Summary of a rigid run (`summary.json`).
#[derive(Serialize)]
pub struct Summary {
    /// Scene name.
    pub scene: String,
    /// Scene file as given.
    pub scene_file: String,
    /// Velocity solver (`nlgs`, `newton`, `proximal_newton`).
    pub solver: &'static str,
    /// `completed`, `stopped` or `failed`.
    pub status: &'static str,
    /// Why the run failed (empty otherwise).
    pub message: String,
    /// Bodies of the whole world.
    pub bodies: usize,
    /// Time step (s).
    pub dt: f64,
    /// The step this invocation started from: 0, or the checkpoint's on `--resume` (the
    /// series, and so `wall_time_s`, cover every step from 0).
    pub first_step: u64,
    /// Steps done.
    pub steps: u64,
    /// Simulated time (s).
    pub simulated_time: f64,
    /// Averages over the series.
    #[serde(flatten)]
    pub figures: SeriesFigures,
    /// Peak heap or resident memory (bytes), where known.
    pub peak_memory_bytes: Option<u64>,
    /// Version of xper.
    pub xper_version: &'static str,
    /// Processes of the run.
    pub processes: usize,
    /// Per-process load, communication and efficiency (distributed runs only).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub ranks: Vec<RankSummary>,
    /// The serial comparison, when asked for.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub serial_comparison: Option<SerialComparison>,
}

/// The summary's averages over the series.
#[derive(Serialize)]
pub struct SeriesFigures {
    /// Sum of the steps' wall times (s).
    pub wall_time_s: f64,
    /// Mean solver iterations per step.
    pub average_iterations: f64,
    /// Largest solver iterations in a step.
    pub max_iterations: f64,
    /// Steps whose solver did not converge.
    pub non_converged_steps: usize,
    /// Mean contacts per step.
    pub average_contacts: f64,
    /// Largest contacts in a step.
    pub max_contacts: f64,
}

impl SeriesFigures {
    /// The figures of a rigid run's series.
    pub fn of(series: &SeriesTable) -> Self {
        let col = |name: &str| series.column(name).unwrap_or_default();
        let max = |v: &[f64]| v.iter().copied().fold(0.0, f64::max);
        let (iterations, contacts) = (col("iterations"), col("contacts"));
        SeriesFigures {
            wall_time_s: col("wall_time").iter().sum(),
            average_iterations: mean(&iterations),
            max_iterations: max(&iterations),
            non_converged_steps: col("converged").iter().filter(|&&c| c == 0.0).count(),
            average_contacts: mean(&contacts),
            max_contacts: max(&contacts),
        }
    }
}

/// The name of a solver kind in summaries.
pub fn solver_name(kind: xper_scene::VelocitySolverKind) -> &'static str {
    match kind {
        xper_scene::VelocitySolverKind::Nlgs => "nlgs",
        xper_scene::VelocitySolverKind::Newton => "newton",
        xper_scene::VelocitySolverKind::ProximalNewton => "proximal_newton",
    }
}

/// `series.png`: energies, solver sweeps, residual and contacts against time.
pub fn write_plot(series: &SeriesTable, path: &Path, title: &str) -> Result<(), RunError> {
    let curve = |name: &str, label: &str| series_curve(series, "time", name, label);
    let potential0 = series
        .column("potential_energy")
        .and_then(|p| p.first().copied())
        .unwrap_or(0.0);
    let mut potential = curve("potential_energy", "potential - initial potential");
    potential.points.iter_mut().for_each(|p| p.1 -= potential0);
    let panel = |title: &str, y: &str, curves: Vec<Curve>, log_y: bool| {
        outputs::panel(title, "time (s)", y, curves, log_y)
    };
    let panels = [
        panel(
            "Energy budget",
            "energy (J/m)",
            vec![
                curve("kinetic_energy", "kinetic"),
                potential,
                curve("dissipated_energy", "dissipated"),
                curve("external_work", "external work"),
                curve("energy_error", "balance error"),
            ],
            false,
        ),
        panel(
            "Contact solver",
            "iterations",
            vec![curve(
                "iterations",
                "NLGS sweeps or Newton iterations per step",
            )],
            false,
        ),
        panel(
            "Solver residual",
            "residual",
            vec![curve("residual", "final residual")],
            true,
        ),
        panel(
            "Contacts",
            "count",
            vec![
                curve("contacts", "within alert distance"),
                curve("active_contacts", "active"),
            ],
            false,
        ),
    ];
    plot_panels(path, title, &panels, 1000, 300).map_err(io_err)
}

/// The file of the problem of step `step` (1-based) under the output directory `out`.
pub fn problem_path(out: &Path, step: u64) -> PathBuf {
    out.join("problems").join(format!("step_{step:06}.hdf5"))
}

/// Writes the problem of `step` in FCLib's HDF5 local form, atomically.
#[cfg(feature = "hdf5")]
pub fn write_problem(
    out: &Path,
    step: u64,
    problem: &xper_solver::FrictionProblem,
) -> Result<(), RunError> {
    xper_fclib::write_fclib_local(problem_path(out, step), problem)
        .map_err(|e| RunError::Runtime(format!("problem of step {step}: {e}")))
}

/// Without HDF5 no problem is captured (dumps are refused before the run starts).
#[cfg(not(feature = "hdf5"))]
pub fn write_problem(
    out: &Path,
    step: u64,
    _problem: &xper_solver::FrictionProblem,
) -> Result<(), RunError> {
    Err(RunError::BadInput(format!(
        "{}: problem of step {step}: built without HDF5 support: rebuild with --features hdf5",
        problem_path(out, step).display()
    )))
}
