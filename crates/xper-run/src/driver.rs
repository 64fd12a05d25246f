//! The run driver: one time loop for every physics, on one process or on the processes of a
//! communicator. `xper_simulation::run_on` reads the scene, checks its memory estimate and
//! builds its simulation (or restores it from checkpoint.bin); then [`drive`]:
//!
//! ```text
//! first frame (or, on --resume, the tables and result.pvd read back)
//! while the scene is not at its end (and not at --stop-at-step):
//!     step                                    (collective)
//!     every frame_every steps: sync, frame     (the last step too)
//!     every checkpoint_every steps: sync, the tables, then checkpoint.bin (sealed, with
//!                                             the tables' row counts)
//! sync; per-process summaries; --compare-serial
//! checkpoint.bin (or, after a failure, the tables alone), summary.json, plots
//! ```
//!
//! Outputs are events of this loop; what a frame, a checkpoint, a table or a summary holds is
//! the simulation's (see [`Simulation`]).

use crate::checkpoint::{self, Header};
use crate::lock::OutputLock;
use crate::outputs::{create_output_dir, io_err, progress_bar};
use crate::simulation::{run_status, OutputSchedule, RunFacts, RunOptions, Simulation};
use crate::RunError;
use indicatif::ProgressBar;
use std::io::IsTerminal;
use std::path::Path;
use std::time::Instant;
use xper_io::{write_atomic, PvdCollection, SeriesTable};
use xper_parallel::Communicator;

/// What the driver keeps of the scene file: its text (each checkpoint holds it, so that a
/// resume can tell a compatible edit, [`crate::resume`]) and the notes of its reading.
pub struct SceneFile {
    /// The scene file's text.
    pub text: String,
    /// Remarks printed before the run (the edits a resume takes).
    pub notes: Vec<String>,
    /// On `--resume`, the header of the checkpoint resumed (read once, with its table rows).
    pub resumed: Option<Header>,
}

/// Writes the tables, then `checkpoint.bin` with their row counts: a run interrupted between
/// the two leaves tables that reach past the previous checkpoint, never short of one.
fn write_checkpoint(sim: &dyn Simulation, dir: &Path, scene: &SceneFile) -> Result<(), RunError> {
    write_tables(sim, dir)?;
    let header = Header {
        scene_hash: sim.scene_hash(),
        scene_text: scene.text.clone(),
        payload_len: 0,
        tables: (sim.tables().into_iter())
            .map(|(name, table)| (name.to_string(), table.rows.len() as u64))
            .collect(),
    };
    let bytes = checkpoint::seal(header, &sim.checkpoint()?)?;
    write_atomic(&dir.join("checkpoint.bin"), &bytes).map_err(io_err)
}

fn write_tables(sim: &dyn Simulation, dir: &Path) -> Result<(), RunError> {
    for (name, table) in sim.tables() {
        table.write_csv(&dir.join(name)).map_err(io_err)?;
    }
    Ok(())
}

/// Removes what an earlier run left in `dir` that this fresh run would not overwrite: its
/// checkpoint (not this run's), `result.pvd`, `summary.json` and its frames (a longer earlier
/// run's last frames would otherwise sit beside this run's). Tables and plots are rewritten.
fn clear_earlier_run(dir: &Path) -> Result<(), RunError> {
    let remove = |path: &Path| match std::fs::remove_file(path) {
        Err(e) if e.kind() != std::io::ErrorKind::NotFound => Err(io_err(e)),
        _ => Ok(()),
    };
    for name in ["checkpoint.bin", "result.pvd", "summary.json"] {
        remove(&dir.join(name))?;
    }
    let frames = dir.join("frames");
    for entry in std::fs::read_dir(&frames).map_err(io_err)? {
        let path = entry.map_err(io_err)?.path();
        let frame = matches!(
            path.extension().and_then(|e| e.to_str()),
            Some("vtu" | "vtp" | "pvtu")
        );
        if frame && path.is_file() {
            remove(&path)?;
        }
    }
    Ok(())
}

/// Reads back the tables and `result.pvd` of the run being resumed, cut at its checkpoint:
/// each table keeps the rows it had when the checkpoint was written, and one with fewer rows
/// is refused (its rows since an earlier point are lost).
fn read_back(
    sim: &mut dyn Simulation,
    dir: &Path,
    pvd: &mut PvdCollection,
    resumed: Option<&Header>,
) -> Result<(), RunError> {
    let rows = match resumed {
        Some(header) => header.tables.clone(),
        None => checkpoint::open(dir, "cannot resume")?.header.tables,
    };
    let step = sim.step_index();
    for (name, table) in sim.tables_mut() {
        let path = dir.join(name);
        *table = SeriesTable::read_csv(&path).map_err(|e| RunError::BadInput(e.to_string()))?;
        let Some(&(_, kept)) = rows.iter().find(|(n, _)| n == name) else {
            return Err(RunError::BadInput(format!(
                "{}: the checkpoint does not list {name}; run the scene again without --resume",
                dir.join("checkpoint.bin").display()
            )));
        };
        if (table.rows.len() as u64) < kept {
            return Err(RunError::BadInput(format!(
                "{}: {} rows, but the checkpoint at step {step} was written after {kept}: rows \
                 were lost since; run the scene again without --resume",
                path.display(),
                table.rows.len()
            )));
        }
        table.rows.truncate(kept as usize);
    }
    *pvd = PvdCollection::read(&dir.join("result.pvd"))
        .map_err(|e| RunError::BadInput(e.to_string()))?;
    Ok(())
}

/// The time loop of a built simulation with its outputs (see the module's documentation):
/// [`Run::start`], [`Run::advance`] until [`Run::is_over`], [`Run::finish`].
pub fn drive(
    sim: &mut dyn Simulation,
    schedule: OutputSchedule,
    opts: &RunOptions,
    quiet: bool,
    comm: Option<&dyn Communicator>,
    scene: SceneFile,
) -> Result<serde_json::Value, RunError> {
    let mut run = Run::start(sim, schedule, opts.clone(), quiet, comm, scene)?;
    while !run.is_over(sim) {
        run.advance(sim)?;
    }
    run.finish(sim)
}

/// A run under way: the driver's state between the events of its loop. Each stage is a method
/// taking the simulation, which the caller keeps (`xper run` loops in [`drive`]; the Python
/// module steps when asked and reads the state in between).
pub struct Run<'c> {
    schedule: OutputSchedule,
    opts: RunOptions,
    quiet: bool,
    comm: Option<&'c dyn Communicator>,
    scene: SceneFile,
    _lock: Option<OutputLock>,
    pvd: PvdCollection,
    bar: ProgressBar,
    started: Instant,
    first_step: u64,
    stepping: f64,
    failure: Option<String>,
}

impl<'c> Run<'c> {
    /// Takes the output directory (`xper.lock`), writes the first frame (or, on `--resume`,
    /// reads back the tables and `result.pvd` of the run resumed) and starts the clock.
    pub fn start(
        sim: &mut dyn Simulation,
        schedule: OutputSchedule,
        opts: RunOptions,
        quiet: bool,
        comm: Option<&'c dyn Communicator>,
        scene: SceneFile,
    ) -> Result<Self, RunError> {
        let root = sim.is_root();
        let dir = opts.out.as_path();
        let mut lock = None;
        if root {
            let mut notes = scene.notes.clone();
            notes.extend(sim.notes());
            let locked = create_output_dir(&dir.join("frames"))
                .and_then(|()| OutputLock::take(dir, &mut notes));
            match locked {
                Ok(taken) => lock = Some(taken),
                Err(e) => {
                    if let Some(comm) = comm {
                        comm.abort(&e.to_string(), 2);
                    }
                    return Err(e);
                }
            }
            if !quiet {
                for note in notes {
                    eprintln!("xper: note: {note}");
                }
            }
        }
        let mut pvd = PvdCollection::default();
        if opts.resume {
            read_back(sim, dir, &mut pvd, scene.resumed.as_ref())?;
        } else {
            sim.sync();
            if root {
                clear_earlier_run(dir)?;
                sim.write_frame(dir, &mut pvd)?;
            }
        }
        let (steps, position) = sim.progress();
        if root && !quiet && !std::io::stderr().is_terminal() {
            // Batch logs get a first line; the closing line ends them.
            eprintln!(
                "xper: {} {} from step {position} of {steps} on {} process(es), outputs in {}",
                if opts.resume { "resuming" } else { "running" },
                opts.scene.display(),
                sim.processes(),
                dir.display()
            );
        }
        let bar = progress_bar(quiet || !root, steps, position);
        sim.begin();
        Ok(Run {
            schedule,
            quiet,
            comm,
            scene,
            _lock: lock,
            pvd,
            bar,
            started: Instant::now(),
            first_step: sim.step_index(),
            stepping: 0.0,
            failure: None,
            opts,
        })
    }

    /// Whether the loop is over: the scene at its end, `--stop-at-step` reached, or a step
    /// failed.
    pub fn is_over(&self, sim: &dyn Simulation) -> bool {
        self.failure.is_some()
            || sim.is_complete()
            || self
                .opts
                .stop_at_step
                .is_some_and(|s| sim.step_index() >= s)
    }

    /// One step (collective) with the frame and checkpoint the schedule puts after it. A
    /// failed step ends the loop ([`Run::is_over`]; [`Run::finish`] returns the failure) after
    /// showing its state when it asks to; only an output that cannot be written is an error
    /// here.
    pub fn advance(&mut self, sim: &mut dyn Simulation) -> Result<(), RunError> {
        let root = sim.is_root();
        let dir = self.opts.out.as_path();
        match sim.step() {
            Ok(wall) => {
                self.stepping += wall;
                let step = sim.step_index();
                let frame = step % self.schedule.frame_every == 0 || sim.is_complete();
                let checkpoint = step % self.schedule.checkpoint_every == 0;
                if frame || checkpoint {
                    sim.sync();
                }
                if frame && root {
                    sim.write_frame(dir, &mut self.pvd)?;
                }
                if checkpoint && root {
                    write_checkpoint(sim, dir, &self.scene)?;
                }
                if step % 10 == 0 || sim.is_complete() {
                    let (steps, position) = sim.progress();
                    self.bar.set_length(steps);
                    self.bar.set_position(position);
                    self.bar.set_message(sim.status_line());
                }
            }
            Err(f) => {
                if f.show_state {
                    sim.sync();
                    if root {
                        sim.write_frame(dir, &mut self.pvd)?;
                    }
                }
                if let Some(comm) = self.comm.filter(|_| !f.collective) {
                    // Other processes may be waiting in a collective this one will not reach.
                    comm.abort(&format!("step {}: {}", f.step, f.message), 1);
                }
                let checkpoint = dir.join("checkpoint.bin");
                let kept = if checkpoint.exists() {
                    format!("the last checkpoint is kept in {}", checkpoint.display())
                } else {
                    "no checkpoint was written".to_string()
                };
                self.failure = Some(format!(
                    "step {} (t = {:.6e} s): {}; {kept}",
                    f.step, f.time, f.message
                ));
            }
        }
        Ok(())
    }

    /// Writes a frame of the current state now (collective), outside the schedule.
    pub fn write_frame(&mut self, sim: &mut dyn Simulation) -> Result<(), RunError> {
        sim.sync();
        match sim.is_root() {
            true => sim.write_frame(&self.opts.out, &mut self.pvd),
            false => Ok(()),
        }
    }

    /// Writes the tables and `checkpoint.bin` of the current state now (collective), outside
    /// the schedule: a later `--resume` starts from here.
    pub fn write_checkpoint(&mut self, sim: &mut dyn Simulation) -> Result<(), RunError> {
        sim.sync();
        match sim.is_root() {
            true => write_checkpoint(sim, &self.opts.out, &self.scene),
            false => Ok(()),
        }
    }

    /// Ends the run: per-process summaries, `--compare-serial`, the last checkpoint (after a
    /// failure, the tables alone), `summary.json`, plots and the closing line; returns the
    /// summary (`null` on the processes that do not write), or the failure.
    pub fn finish(self, sim: &mut dyn Simulation) -> Result<serde_json::Value, RunError> {
        let Run {
            opts,
            quiet,
            scene,
            bar,
            started,
            first_step,
            stepping,
            failure,
            ..
        } = self;
        let root = sim.is_root();
        let dir = opts.out.as_path();
        bar.finish_and_clear();
        let wall = started.elapsed().as_secs_f64();
        if failure.is_none() {
            sim.sync();
        }
        let ranks = sim.rank_summaries(wall);
        let comparison = match failure {
            None => sim.compare_serial(stepping)?,
            Some(_) => None,
        };
        if !root {
            return match failure {
                Some(message) => Err(RunError::Runtime(message)),
                None => Ok(serde_json::Value::Null),
            };
        }
        if failure.is_none() {
            write_checkpoint(sim, dir, &scene)?;
        } else {
            write_tables(sim, dir)?;
        }
        let facts = RunFacts {
            scene_file: &opts.scene,
            status: run_status(failure.is_some(), sim.is_complete()),
            message: failure.clone().unwrap_or_default(),
            first_step,
            wall,
            ranks,
            comparison,
        };
        let summary = sim.write_summary(dir, &facts)?;
        if !quiet {
            eprintln!("{}", sim.closing_line(&facts, dir));
        }
        match failure {
            Some(message) => Err(RunError::Runtime(message)),
            None => Ok(summary),
        }
    }
}
