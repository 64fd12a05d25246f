//! `xper check` and `xper run` for fracture scenes (a scene with a `[mesh]` section): the
//! model built from the scene, the time loop with its progress bar, frames, series,
//! checkpoints, summary and plots.

use std::path::{Path, PathBuf};
use std::time::Instant;

use serde::{Deserialize, Serialize};
use xper_fem::MaterialState;
use xper_fracture::{FractureEnergy, FractureModel, FractureStepError, PointState};
use xper_io::{write_atomic, write_json_atomic, write_vtu, PvdCollection, SeriesTable};
use xper_scene::{FractureScene, MeshSource};

use crate::fracture_frames::{elements_grid, interfaces_grid};
use crate::fracture_outputs::{
    series_columns, series_row, summary, write_crack_pattern, write_force_displacement,
    write_series_plot, FractureSummary,
};
use crate::run::RunOptions;
use crate::run_fracture_distributed::{
    compare_serial, DistributedFractureRun, FractureRun, SerialFracture,
};
use crate::CliError;

fn io_err(e: std::io::Error) -> CliError {
    CliError::Runtime(e.to_string())
}

fn bad(e: impl std::fmt::Display) -> CliError {
    CliError::BadInput(e.to_string())
}

/// Reads a fracture scene and builds its model; every problem is a bad-input error naming
/// the scene file (and the place in it).
pub fn load_model(path: &Path) -> Result<(FractureScene, FractureModel), CliError> {
    let (scene, model, _) = load(path)?;
    Ok((scene, model))
}

/// The scene, its model and the notes of its build (rule-of-thumb stiffnesses).
fn load(path: &Path) -> Result<(FractureScene, FractureModel, Vec<String>), CliError> {
    let scene = match xper_scene::load_any_scene(path).map_err(bad)? {
        xper_scene::AnyScene::Fracture(s) => s,
        xper_scene::AnyScene::Rigid(_) => {
            return Err(CliError::BadInput(format!(
                "{}: not a fracture scene (it has no [mesh] section)",
                path.display()
            )))
        }
    };
    let setup = scene.build().map_err(bad)?;
    let model = FractureModel::new(setup.mesh, setup.spec).map_err(|e| {
        CliError::BadInput(format!(
            "{}: cannot build the fracture model: {e}",
            path.display()
        ))
    })?;
    Ok((scene, model, setup.notes))
}

/// `xper check` on a fracture scene: builds the model and prints what it holds.
pub fn check(path: &Path) -> Result<(), CliError> {
    let (scene, model, notes) = load(path)?;
    let mesh = &model.mesh;
    println!(
        "{}: fracture scene `{}` is valid: {} elements, {} nodes, {} interfaces ({} broken at \
         start), {} steps of {:e} s",
        path.display(),
        scene.name,
        model.elements.len(),
        mesh.nodes.len(),
        model.interfaces.len(),
        model.broken_interfaces(),
        scene.steps,
        scene.dt
    );
    for (r, region) in mesh.regions.iter().enumerate() {
        let n = model
            .elements
            .iter()
            .filter(|e| e.region as usize == r)
            .count();
        println!("region `{}`: {n} elements", region.name);
    }
    for load in &model.spec.loads {
        println!("load `{}`: {} nodes", load.name, load.nodes.len());
    }
    for note in notes {
        println!("note: {note}");
    }
    Ok(())
}

/// The evolving state of one element, as checkpointed.
#[derive(Serialize, Deserialize)]
struct ElementState {
    displacement: [f64; 6],
    velocity: [f64; 6],
    state: MaterialState,
    internal_force: [f64; 6],
    stiffness: [[f64; 6]; 6],
}

/// A checkpoint: the scene's hash and everything of the model that evolves.
#[derive(Serialize, Deserialize)]
struct Checkpoint {
    scene_hash: u64,
    step: u64,
    time: f64,
    energy: FractureEnergy,
    elements: Vec<ElementState>,
    points: Vec<[PointState; 2]>,
}

impl Checkpoint {
    fn of(m: &FractureModel, scene_hash: u64) -> Self {
        Checkpoint {
            scene_hash,
            step: m.step,
            time: m.time,
            energy: m.energy,
            elements: (m.elements.iter())
                .map(|e| ElementState {
                    displacement: e.displacement,
                    velocity: e.velocity,
                    state: e.state,
                    internal_force: e.internal_force,
                    stiffness: e.stiffness,
                })
                .collect(),
            points: m.interfaces.iter().map(|i| i.points).collect(),
        }
    }

    /// Overwrites the evolving state of a freshly built model.
    fn restore(self, m: &mut FractureModel, file: &Path) -> Result<(), CliError> {
        if self.elements.len() != m.elements.len() || self.points.len() != m.interfaces.len() {
            return Err(CliError::BadInput(format!(
                "{}: the checkpoint holds {} elements and {} interfaces, the scene builds {} and {}",
                file.display(),
                self.elements.len(),
                self.points.len(),
                m.elements.len(),
                m.interfaces.len()
            )));
        }
        for (el, s) in m.elements.iter_mut().zip(self.elements) {
            el.displacement = s.displacement;
            el.velocity = s.velocity;
            el.state = s.state;
            el.internal_force = s.internal_force;
            el.stiffness = s.stiffness;
        }
        for (i, p) in m.interfaces.iter_mut().zip(self.points) {
            i.points = p;
        }
        m.step = self.step;
        m.time = self.time;
        m.energy = self.energy;
        Ok(())
    }
}

/// The step and the nodal displacements of each element (m) held by the checkpoint of a
/// fracture run in `dir` (for comparing runs).
pub fn checkpoint_displacements(dir: &Path) -> Result<(u64, Vec<[f64; 6]>), CliError> {
    let path = dir.join("checkpoint.bin");
    let bytes = std::fs::read(&path)
        .map_err(|e| CliError::BadInput(format!("{}: cannot read: {e}", path.display())))?;
    let c: Checkpoint = bincode::deserialize(&bytes).map_err(|e| {
        CliError::BadInput(format!(
            "{}: not a fracture checkpoint of xper: {e}",
            path.display()
        ))
    })?;
    Ok((c.step, c.elements.iter().map(|e| e.displacement).collect()))
}

/// FNV-1a hash of the scene text and, for a mesh file, of its bytes.
fn scene_hash(scene: &FractureScene) -> Result<u64, CliError> {
    let mut bytes = std::fs::read(&scene.file).map_err(|e| {
        CliError::BadInput(format!("{}: cannot read scene: {e}", scene.file.display()))
    })?;
    if let MeshSource::File(mesh) = &scene.mesh.source {
        bytes.extend(std::fs::read(mesh).map_err(|e| {
            CliError::BadInput(format!("{}: cannot read mesh: {e}", mesh.display()))
        })?);
    }
    Ok(bytes.iter().fold(0xcbf29ce484222325u64, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x100000001b3)
    }))
}

struct Outputs {
    dir: PathBuf,
    series: SeriesTable,
    pvd: PvdCollection,
    scene_hash: u64,
}

impl Outputs {
    fn write_frame(&mut self, m: &FractureModel) -> Result<(), CliError> {
        let frames = self.dir.join("frames");
        self.pvd.truncate_after(m.time - 0.5 * m.spec.dt);
        let parts = [
            ("elements", elements_grid(m)),
            ("interfaces", interfaces_grid(m)),
        ];
        for (part, (name, grid)) in parts.iter().enumerate() {
            let file = format!("{name}_{:08}.vtu", m.step);
            write_vtu(&frames.join(&file), grid).map_err(io_err)?;
            self.pvd.push(m.time, part as u32, format!("frames/{file}"));
        }
        self.pvd.write(&self.dir.join("result.pvd")).map_err(io_err)
    }

    fn write_checkpoint(&self, m: &FractureModel) -> Result<(), CliError> {
        let bytes = bincode::serialize(&Checkpoint::of(m, self.scene_hash))
            .map_err(|e| CliError::Runtime(e.to_string()))?;
        write_atomic(&self.dir.join("checkpoint.bin"), &bytes).map_err(io_err)?;
        self.series
            .write_csv(&self.dir.join("series.csv"))
            .map_err(io_err)
    }

    fn resume(&mut self, m: &mut FractureModel) -> Result<(), CliError> {
        let path = self.dir.join("checkpoint.bin");
        let bytes = std::fs::read(&path)
            .map_err(|e| CliError::BadInput(format!("{}: cannot resume: {e}", path.display())))?;
        let c: Checkpoint = bincode::deserialize(&bytes).map_err(|e| {
            CliError::BadInput(format!(
                "{}: not a fracture checkpoint of xper: {e}",
                path.display()
            ))
        })?;
        if c.scene_hash != self.scene_hash {
            return Err(CliError::BadInput(format!(
                "{}: the checkpoint was written for a different scene or mesh file (changed since)",
                path.display()
            )));
        }
        c.restore(m, &path)?;
        self.series = SeriesTable::read_csv(&self.dir.join("series.csv")).map_err(bad)?;
        self.series
            .truncate_rows_where_first_column_greater_than(m.step as f64);
        self.pvd = PvdCollection::read(&self.dir.join("result.pvd")).map_err(bad)?;
        Ok(())
    }
}

/// Runs a fracture scene (see [`RunOptions`]); `quiet` hides the progress bar.
pub fn run(opts: &RunOptions, quiet: bool) -> Result<(), CliError> {
    run_with_summary(opts, quiet).map(|_| ())
}

/// [`run`], returning the run's summary (as written to `summary.json`).
pub fn run_with_summary(opts: &RunOptions, quiet: bool) -> Result<FractureSummary, CliError> {
    run_on(opts, quiet, None)
}

/// [`run`] on the processes of `comm` when it has several (every process calls it; rank 0
/// writes the outputs, and the summary it returns is the run's), on this process otherwise.
pub fn run_on(
    opts: &RunOptions,
    quiet: bool,
    comm: Option<&dyn xper_domain::Communicator>,
) -> Result<FractureSummary, CliError> {
    let (scene, mut model) = load_model(&opts.scene)?;
    let distributed = comm.filter(|c| c.size() > 1);
    let root = distributed.is_none_or(|c| c.rank() == 0);
    if root {
        crate::run::create_output_dir(&opts.out.join("frames"))?;
    }
    let names: Vec<String> = model.spec.loads.iter().map(|l| l.name.clone()).collect();
    let columns = series_columns(&names);
    let columns: Vec<&str> = columns.iter().map(String::as_str).collect();
    let mut out = Outputs {
        dir: opts.out.clone(),
        series: SeriesTable::new(&columns),
        pvd: PvdCollection::default(),
        scene_hash: scene_hash(&scene)?,
    };
    if opts.resume {
        out.resume(&mut model)?;
    } else if root {
        // A checkpoint of an earlier run in the same directory is not this run's.
        let _ = std::fs::remove_file(opts.out.join("checkpoint.bin"));
        out.write_frame(&model)?;
    }
    let last = opts
        .stop_at_step
        .map_or(scene.steps, |s| s.min(scene.steps));
    let bar = crate::run::progress_bar(quiet || !root, scene.steps, model.step);
    let compare_from =
        (opts.compare_serial && root && distributed.is_some()).then(|| model.clone());
    let mut runner: Box<dyn FractureRun + '_> = match distributed {
        Some(comm) => Box::new(DistributedFractureRun::new(comm, &model)),
        None => Box::<SerialFracture>::default(),
    };
    let started = Instant::now();
    let mut stepping = 0.0;
    let mut failure = None;
    while model.step < last {
        let (step, error) = match runner.step(&mut model) {
            Ok(report) => {
                stepping += report.wall_time;
                out.series.push(series_row(&report));
                let step = model.step;
                let frame = step % scene.output.frame_every == 0 || step == scene.steps;
                let checkpoint = step % scene.output.checkpoint_every == 0;
                if frame || checkpoint {
                    runner.sync(&mut model);
                }
                if frame && root {
                    out.write_frame(&model)?;
                }
                if checkpoint && root {
                    out.write_checkpoint(&model)?;
                }
                if step % 10 == 0 || step == last {
                    bar.set_position(step);
                    bar.set_message(format!(
                        "t = {:.4e} s, {} broken points, {} sweeps",
                        model.time, report.broken_points, report.iterations
                    ));
                }
                continue;
            }
            Err(e @ FractureStepError::Diverging(_)) => {
                // Every process meets it together. The diverged state is shown, not
                // checkpointed.
                runner.sync(&mut model);
                if root {
                    out.write_frame(&model)?;
                }
                (model.step, e.to_string())
            }
            Err(e) => {
                if let Some(comm) = distributed {
                    // This process may be alone in failing: the others would wait for it.
                    comm.abort(&format!("step {}: {e}", model.step + 1), 1);
                }
                (model.step + 1, e.to_string())
            }
        };
        let checkpoint = opts.out.join("checkpoint.bin");
        let kept = if checkpoint.exists() {
            format!("the last checkpoint is kept in {}", checkpoint.display())
        } else {
            "no checkpoint was written".to_string()
        };
        failure = Some(format!(
            "step {step} (t = {:.6e} s): {error}; {kept}",
            step as f64 * model.spec.dt
        ));
        break;
    }
    bar.finish_and_clear();
    let wall = started.elapsed().as_secs_f64();
    if failure.is_none() {
        runner.sync(&mut model);
    }
    let ranks = runner.rank_summaries(wall);
    let processes = runner.processes();
    let comparison = match compare_from.filter(|_| failure.is_none()) {
        Some(start) => Some(compare_serial(start, &model, stepping, processes)?),
        None => None,
    };
    let status = crate::run::run_status(failure.is_some(), model.step == scene.steps);
    let message = failure.clone().unwrap_or_default();
    let mut s = summary(
        &model,
        &out.series,
        (&scene.name, &opts.scene),
        status,
        message,
    );
    (s.processes, s.ranks, s.serial_comparison) = (processes, ranks, comparison);
    if !root {
        return match failure {
            Some(message) => Err(CliError::Runtime(message)),
            None => Ok(s),
        };
    }
    if failure.is_none() {
        out.write_checkpoint(&model)?;
    } else {
        out.series
            .write_csv(&opts.out.join("series.csv"))
            .map_err(io_err)?;
    }
    write_json_atomic(&opts.out.join("summary.json"), &s).map_err(io_err)?;
    write_series_plot(&out.series, &opts.out.join("series.png"), &scene.name).map_err(io_err)?;
    let fd = opts.out.join("force_displacement.png");
    write_force_displacement(&model, &out.series, &fd, &scene.name).map_err(io_err)?;
    write_crack_pattern(&model, &opts.out.join("crack_pattern.png"), &scene.name)
        .map_err(io_err)?;
    if !quiet {
        eprintln!(
            "{status}: {} of {} steps in {wall:.2} s on {processes} process(es), {} broken points, \
             outputs in {}",
            model.step,
            scene.steps,
            model.broken_points(),
            opts.out.display()
        );
    }
    match failure {
        Some(message) => Err(CliError::Runtime(message)),
        None => Ok(s),
    }
}
