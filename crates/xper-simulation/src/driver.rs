//! `xper run`: the time loop with its outputs (frames, series, checkpoints, summary, plot,
//! and the contact problems of the steps listed in `[output] dump_problems`).

use crate::frames::{bodies_grid, contacts_grid};
use crate::run_distributed::{DistributedRun, RigidRun, SerialRun};
use crate::serial_comparison::SerialComparison;
use crate::world_from_scene::world_from_scene;
use crate::CliError;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use serde::Serialize;
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::time::Instant;
use xper_io::{
    plot_panels, write_atomic, write_json_atomic, write_vtu, Curve, Panel, PvdCollection,
    SeriesTable,
};
use xper_nscd::{StepReport, World};

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

/// Options of `xper run`.
pub struct RunOptions {
    /// Scene file.
    pub scene: PathBuf,
    /// Output directory.
    pub out: PathBuf,
    /// Continue from the checkpoint in `out`.
    pub resume: bool,
    /// Stop (with a checkpoint) after this step, as if interrupted.
    pub stop_at_step: Option<u64>,
    /// After a distributed run, run the same steps on one process and report the parallel
    /// efficiency and the largest position difference in `summary.json`.
    pub compare_serial: bool,
}

/// The load of each process of a run (empty for a run on one process).
pub type RankLoads = Vec<crate::run_distributed::RankSummary>;

/// Summary of a run (`summary.json`).
#[derive(Serialize)]
struct Summary {
    scene: String,
    scene_file: String,
    solver: &'static str,
    status: &'static str,
    message: String,
    bodies: usize,
    dt: f64,
    /// The step this invocation started from: 0, or the checkpoint's on `--resume` (the
    /// series, and so `wall_time_s`, cover every step from 0).
    first_step: u64,
    steps: u64,
    simulated_time: f64,
    wall_time_s: f64,
    average_iterations: f64,
    max_iterations: f64,
    non_converged_steps: usize,
    average_contacts: f64,
    max_contacts: f64,
    peak_memory_bytes: Option<u64>,
    xper_version: &'static str,
    /// Processes of the run.
    processes: usize,
    /// Per-process load, communication and efficiency (distributed runs only).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    ranks: RankLoads,
    /// The serial comparison, when asked for.
    #[serde(skip_serializing_if = "Option::is_none")]
    serial_comparison: Option<SerialComparison>,
}

/// FNV-1a hash of the scene text: a checkpoint resumes only the scene it was written for.
fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf29ce484222325u64, |h, &b| {
        (h ^ b as u64).wrapping_mul(0x100000001b3)
    })
}

fn io_err(e: std::io::Error) -> CliError {
    CliError::Runtime(e.to_string())
}

pub(crate) struct Outputs {
    dir: PathBuf,
    series: SeriesTable,
    pvd: PvdCollection,
    scene_hash: u64,
}

impl Outputs {
    pub(crate) fn write_frame(&mut self, world: &World) -> Result<(), CliError> {
        let frames = self.dir.join("frames");
        let parts = [
            ("bodies", bodies_grid(world)),
            ("contacts", contacts_grid(world, false)),
            ("force_chains", contacts_grid(world, true)),
        ];
        self.pvd.truncate_after(world.time - 0.5 * world.params.dt);
        for (part, (name, grid)) in parts.iter().enumerate() {
            let file = format!("frames/{name}_{:08}.vtu", world.step);
            write_vtu(&frames.join(format!("{name}_{:08}.vtu", world.step)), grid)
                .map_err(io_err)?;
            self.pvd.push(world.time, part as u32, file);
        }
        self.pvd.write(&self.dir.join("result.pvd")).map_err(io_err)
    }

    pub(crate) fn write_checkpoint(&self, world: &World) -> Result<(), CliError> {
        let bytes = checkpoint_bytes(self.scene_hash, &world.to_bytes())?;
        write_atomic(&self.dir.join("checkpoint.bin"), &bytes).map_err(io_err)?;
        self.series
            .write_csv(&self.dir.join("series.csv"))
            .map_err(io_err)
    }

    fn push(&mut self, r: &StepReport) {
        self.series.push(vec![
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
        ]);
    }
}

/// First field of `checkpoint.bin` of rigid and fluid runs: "XP" and the version of the
/// layout, raised whenever a type the checkpoint holds changes (version 2: `NlgsParams` gained
/// `acceleration`; version 3: `BodySet` keeps the imposed degrees of freedom instead of the
/// inverse masses; version 4: a contact set holds its contacts' rows, keys, gaps and impulses
/// as parallel arrays). bincode is not self-describing, so without it a checkpoint of another
/// build could be misread instead of refused.
pub(crate) const CHECKPOINT_TAG: u32 = 0x5850_0004;

/// The bytes of `checkpoint.bin`: the tag, the scene hash and the state, by bincode.
pub(crate) fn checkpoint_bytes<T: Serialize>(
    scene_hash: u64,
    state: &T,
) -> Result<Vec<u8>, CliError> {
    bincode::serialize(&(CHECKPOINT_TAG, scene_hash, state))
        .map_err(|e| CliError::Runtime(e.to_string()))
}

/// Reads `dir/checkpoint.bin`, written by [`checkpoint_bytes`], for the scene whose
/// text hashes to `scene_hash`; `what` names the kind of state in the error message.
pub(crate) fn read_checkpoint<T: serde::de::DeserializeOwned>(
    dir: &Path,
    scene_hash: u64,
    what: &str,
) -> Result<T, CliError> {
    let path = dir.join("checkpoint.bin");
    let bytes = std::fs::read(&path)
        .map_err(|e| CliError::BadInput(format!("{}: cannot resume: {e}", path.display())))?;
    let tag: Option<u32> = bytes.get(..4).and_then(|b| bincode::deserialize(b).ok());
    if tag != Some(CHECKPOINT_TAG) {
        return Err(CliError::BadInput(format!(
            "{}: not {what} of this version of xper (its layout differs); run the scene again \
             without --resume",
            path.display()
        )));
    }
    let (_, hash, state): (u32, u64, T) = bincode::deserialize(&bytes)
        .map_err(|e| CliError::BadInput(format!("{}: not {what}: {e}", path.display())))?;
    if hash != scene_hash {
        return Err(CliError::BadInput(format!(
            "{}: the checkpoint was written for a different scene file (the scene changed since)",
            path.display()
        )));
    }
    Ok(state)
}

/// Creates an output directory (and its parents), a bad-input error naming it otherwise.
pub(crate) fn create_output_dir(dir: &Path) -> Result<(), CliError> {
    std::fs::create_dir_all(dir).map_err(|e| {
        CliError::BadInput(format!(
            "{}: cannot create output directory: {e}",
            dir.display()
        ))
    })
}

/// Runs a scene; see [`RunOptions`].
pub fn run(opts: &RunOptions, quiet: bool) -> Result<(), CliError> {
    run_on(opts, quiet, None)
}

/// [`run`] on the processes of `comm` when it has more than one (a distributed run of a rigid
/// scene, outputs written by rank 0 from the gathered world), on this process otherwise.
pub fn run_on(
    opts: &RunOptions,
    quiet: bool,
    comm: Option<&dyn xper_domain::Communicator>,
) -> Result<(), CliError> {
    let text = std::fs::read(&opts.scene).map_err(|e| {
        CliError::BadInput(format!("{}: cannot read scene: {e}", opts.scene.display()))
    })?;
    let mut scene =
        xper_scene::load_scene(&opts.scene).map_err(|e| CliError::BadInput(e.to_string()))?;
    let distributed = comm.filter(|c| c.size() > 1);
    if scene.fluid.is_some() {
        return crate::run_fluid::run(opts, &scene, fnv1a(&text), quiet, distributed);
    }
    let dumps = scene.output.dump_problems.clone();
    if !dumps.is_empty() && !cfg!(feature = "hdf5") {
        return Err(CliError::BadInput(format!(
            "{}: [output] dump_problems: built without HDF5 support: rebuild with --features hdf5",
            opts.scene.display()
        )));
    }
    crate::run_distributed::check_distributable(&scene, &opts.scene, distributed.is_some())?;
    let root = distributed.is_none_or(|c| c.rank() == 0);
    let mut dirs = vec![opts.out.join("frames")];
    if !dumps.is_empty() {
        dirs.push(opts.out.join("problems"));
    }
    for dir in dirs {
        create_output_dir(&dir)?;
    }
    let mut out = Outputs {
        dir: opts.out.clone(),
        series: SeriesTable::new(&SERIES_COLUMNS),
        pvd: PvdCollection::default(),
        scene_hash: fnv1a(&text),
    };
    let world = if opts.resume {
        let bytes: Vec<u8> = read_checkpoint(&opts.out, out.scene_hash, "an xper checkpoint")?;
        let world = World::from_bytes(&bytes).map_err(|e| {
            CliError::BadInput(format!(
                "{}: {e}",
                opts.out.join("checkpoint.bin").display()
            ))
        })?;
        let series_path = opts.out.join("series.csv");
        out.series =
            SeriesTable::read_csv(&series_path).map_err(|e| CliError::BadInput(e.to_string()))?;
        out.series
            .truncate_rows_where_first_column_greater_than(world.step as f64);
        out.pvd = PvdCollection::read(&opts.out.join("result.pvd"))
            .map_err(|e| CliError::BadInput(e.to_string()))?;
        world
    } else {
        let world = world_from_scene(&scene);
        crate::world_from_scene::release_body_descriptions(&mut scene);
        if root {
            out.write_frame(&world)?;
        }
        world
    };
    let last = opts
        .stop_at_step
        .map_or(scene.steps, |s| s.min(scene.steps));
    let bar = progress_bar(quiet || !root, scene.steps, world.step);
    let compare_from =
        (opts.compare_serial && root && distributed.is_some()).then(|| world.clone());
    let mut stepper: Box<dyn RigidRun + '_> = match distributed {
        Some(comm) => Box::new(DistributedRun::new(
            comm,
            world,
            scene.output.checkpoint_every,
        )),
        None => Box::new(SerialRun::new(world, dumps.clone(), opts.out.clone())),
    };
    let started = Instant::now();
    let first_step = stepper.step_index();
    let mut failure = None;
    let mut stepping = 0.0;
    while stepper.step_index() < last {
        match stepper.step()? {
            Ok(report) => {
                stepping += report.times.total;
                out.push(&report);
                let step = report.step;
                if step % scene.output.frame_every == 0 || step == scene.steps {
                    if let Some(world) = stepper.snapshot() {
                        out.write_frame(&world)?;
                    }
                }
                if step % scene.output.checkpoint_every == 0 {
                    if let Some(world) = stepper.snapshot() {
                        out.write_checkpoint(&world)?;
                    }
                }
                if step % 10 == 0 || step == last {
                    bar.set_position(step);
                    bar.set_message(format!(
                        "t = {:.4e} s, {} contacts, {} sweeps",
                        report.time, report.contacts, report.iterations
                    ));
                }
            }
            Err(e) => {
                if let Some(comm) = distributed {
                    // Other processes may be waiting in a collective this one will not reach.
                    comm.abort(&format!("step {}: {e}", stepper.step_index() + 1), 1);
                }
                failure = Some(format!(
                    "step {} (t = {:.6e} s): {e}; the last checkpoint is kept in {}",
                    stepper.step_index() + 1,
                    stepper.time(),
                    opts.out.join("checkpoint.bin").display()
                ));
                break;
            }
        }
    }
    bar.finish_and_clear();
    let ranks = stepper.rank_summaries(started.elapsed().as_secs_f64());
    let final_world = match failure {
        None => stepper.snapshot().map(|w| w.into_owned()),
        Some(_) => None,
    };
    if !root {
        return Ok(());
    }
    match &final_world {
        Some(world) => out.write_checkpoint(world)?,
        None => out
            .series
            .write_csv(&opts.out.join("series.csv"))
            .map_err(io_err)?,
    }
    let (step, time) = (stepper.step_index(), stepper.time());
    let comparison = match (compare_from, &final_world) {
        (Some(start), Some(end)) => Some(compare_serial(
            start,
            end,
            stepping,
            distributed.map_or(1, |c| c.size()),
        )?),
        _ => None,
    };
    let status = run_status(failure.is_some(), step == scene.steps);
    let facts = RunFacts {
        bodies: stepper.body_count(),
        first_step,
        step,
        time,
        ranks,
        comparison,
    };
    write_summary(
        &out,
        &scene,
        &facts,
        status,
        failure.clone().unwrap_or_default(),
        &opts.scene,
    )?;
    write_plot(&out.series, &opts.out.join("series.png"), &scene.name)?;
    if !quiet {
        eprintln!(
            "{}: {} of {} steps in {:.2} s, outputs in {}",
            status,
            step,
            scene.steps,
            started.elapsed().as_secs_f64(),
            opts.out.display()
        );
    }
    match failure {
        Some(message) => Err(CliError::Runtime(message)),
        None => Ok(()),
    }
}

/// What the summary needs of the run's end.
struct RunFacts {
    bodies: usize,
    first_step: u64,
    step: u64,
    time: f64,
    ranks: RankLoads,
    comparison: Option<SerialComparison>,
}

/// Runs `start` on this process up to `end`'s step and compares (`--compare-serial`).
fn compare_serial(
    start: World,
    end: &World,
    distributed_wall: f64,
    processes: usize,
) -> Result<SerialComparison, CliError> {
    let mut stepper = xper_nscd::MoreauJean::new();
    SerialComparison::rerun(
        start,
        end.step,
        |w: &World| w.step,
        |w| stepper.step(w).map(drop),
        |w| largest_position_difference(w, end),
        (distributed_wall, processes),
    )
}

/// The largest distance between a body's positions in two worlds of the same bodies (m).
pub fn largest_position_difference(a: &World, b: &World) -> f64 {
    (a.bodies.position.iter())
        .zip(&b.bodies.position)
        .map(|(p, q)| (p - q).norm())
        .fold(0.0, f64::max)
}

/// The file of the problem of step `step` (1-based) under the output directory `out`.
pub fn problem_path(out: &Path, step: u64) -> PathBuf {
    out.join("problems").join(format!("step_{step:06}.hdf5"))
}

/// Writes the problem of `step` in FCLib's HDF5 local form, atomically.
#[cfg(feature = "hdf5")]
pub(crate) fn write_problem(
    out: &Path,
    step: u64,
    problem: &xper_solver::FrictionProblem,
) -> Result<(), CliError> {
    xper_fclib::write_fclib_local(problem_path(out, step), problem)
        .map_err(|e| CliError::Runtime(format!("problem of step {step}: {e}")))
}

/// Without HDF5 no problem is captured (dumps are refused before the run starts).
#[cfg(not(feature = "hdf5"))]
pub(crate) fn write_problem(
    out: &Path,
    step: u64,
    _problem: &xper_solver::FrictionProblem,
) -> Result<(), CliError> {
    Err(CliError::BadInput(format!(
        "{}: problem of step {step}: built without HDF5 support: rebuild with --features hdf5",
        problem_path(out, step).display()
    )))
}

/// The progress bar of a run: steps/s, ETA and a message; hidden when `quiet`.
pub(crate) fn progress_bar(quiet: bool, steps: u64, position: u64) -> ProgressBar {
    // Under an MPI launcher only stdout may be the terminal (see `interactive` in main.rs).
    let target = if quiet {
        ProgressDrawTarget::hidden()
    } else if std::io::stderr().is_terminal() {
        ProgressDrawTarget::stderr()
    } else {
        ProgressDrawTarget::stdout()
    };
    let bar = ProgressBar::with_draw_target(Some(steps), target);
    let style =
        ProgressStyle::with_template("{bar:30} {pos}/{len} steps, {per_sec}, ETA {eta}, {msg}")
            .unwrap_or_else(|_| ProgressStyle::default_bar());
    bar.set_style(style);
    bar.set_position(position);
    bar
}

fn write_summary(
    out: &Outputs,
    scene: &xper_scene::Scene,
    facts: &RunFacts,
    status: &'static str,
    message: String,
    file: &Path,
) -> Result<(), CliError> {
    let col = |name: &str| out.series.column(name).unwrap_or_default();
    let max = |v: &[f64]| v.iter().copied().fold(0.0, f64::max);
    let (iterations, contacts) = (col("iterations"), col("contacts"));
    let summary = Summary {
        scene: scene.name.clone(),
        scene_file: file.display().to_string(),
        solver: match scene.solver.kind {
            xper_scene::SolverKind::Nlgs => "nlgs",
            xper_scene::SolverKind::Newton => "newton",
            xper_scene::SolverKind::ProximalNewton => "proximal_newton",
        },
        status,
        message,
        bodies: facts.bodies,
        dt: scene.dt,
        first_step: facts.first_step,
        steps: facts.step,
        simulated_time: facts.time,
        wall_time_s: col("wall_time").iter().sum(),
        average_iterations: crate::bench::mean(&iterations),
        max_iterations: max(&iterations),
        non_converged_steps: col("converged").iter().filter(|&&c| c == 0.0).count(),
        average_contacts: crate::bench::mean(&contacts),
        max_contacts: max(&contacts),
        peak_memory_bytes: xper_io::peak_memory_bytes(),
        xper_version: env!("CARGO_PKG_VERSION"),
        processes: facts.ranks.len().max(1),
        ranks: facts.ranks.clone(),
        serial_comparison: facts.comparison.clone(),
    };
    write_json_atomic(&out.dir.join("summary.json"), &summary).map_err(io_err)
}

/// `series.png`: energies, solver sweeps, residual and contacts against time.
pub fn write_plot(series: &SeriesTable, path: &Path, title: &str) -> Result<(), CliError> {
    let time = series.column("time").unwrap_or_default();
    let curve = |name: &str, label: &str| Curve {
        label: label.into(),
        points: time
            .iter()
            .copied()
            .zip(series.column(name).unwrap_or_default())
            .collect(),
    };
    let potential0 = series
        .column("potential_energy")
        .and_then(|p| p.first().copied())
        .unwrap_or(0.0);
    let mut potential = curve("potential_energy", "potential - initial potential");
    potential.points.iter_mut().for_each(|p| p.1 -= potential0);
    let panel = |title: &str, y: &str, curves: Vec<Curve>, log_y: bool| Panel {
        title: title.into(),
        x_label: "time (s)".into(),
        y_label: y.into(),
        curves,
        log_y,
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

/// The status of a run in its summary: `failed`, `completed` (it reached its end) or `stopped`.
pub(crate) fn run_status(failed: bool, complete: bool) -> &'static str {
    match (failed, complete) {
        (true, _) => "failed",
        (false, true) => "completed",
        (false, false) => "stopped",
    }
}
