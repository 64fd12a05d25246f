//! The run driver: one time loop for every physics, on one process or on the processes of a
//! communicator.
//!
//! ```text
//! read the scene once -> build its simulation (or restore it from checkpoint.bin)
//! first frame (or, on --resume, the tables and result.pvd read back)
//! while the scene is not at its end (and not at --stop-at-step):
//!     step                                    (collective)
//!     every frame_every steps: sync, frame     (the last step too)
//!     every checkpoint_every steps: sync, checkpoint.bin, then the tables beside it
//! sync; per-process summaries; --compare-serial
//! checkpoint.bin (or, after a failure, the tables alone), summary.json, plots
//! ```
//!
//! Outputs are events of this loop; what a frame, a checkpoint, a table or a summary holds is
//! the simulation's (see [`Simulation`]).

use crate::outputs::{create_output_dir, io_err, progress_bar};
use crate::scene::LoadedScene;
use crate::simulation::{run_status, OutputSchedule, RunFacts, RunOptions, Simulation};
use crate::RunError;
use std::path::Path;
use std::time::Instant;
use xper_domain::Communicator;
use xper_io::{write_atomic, PvdCollection, SeriesTable};

/// Runs a scene of any kind on this process; returns what `summary.json` holds.
pub fn run(opts: &RunOptions, quiet: bool) -> Result<serde_json::Value, RunError> {
    run_on(opts, quiet, None)
}

/// [`run`] on the processes of `comm` when it has more than one (every process calls it;
/// rank 0 writes the outputs and returns the summary, the others `null`), on this process
/// otherwise.
pub fn run_on(
    opts: &RunOptions,
    quiet: bool,
    comm: Option<&dyn Communicator>,
) -> Result<serde_json::Value, RunError> {
    let scene = LoadedScene::read(&opts.scene)?;
    let distributed = comm.filter(|c| c.size() > 1);
    let schedule = scene.output_schedule();
    let mut simulation = scene.into_simulation(opts, distributed)?;
    drive(simulation.as_mut(), schedule, opts, quiet, distributed)
}

/// Writes `checkpoint.bin`, then the tables beside it.
fn write_checkpoint(sim: &dyn Simulation, dir: &Path) -> Result<(), RunError> {
    write_atomic(&dir.join("checkpoint.bin"), &sim.checkpoint()?).map_err(io_err)?;
    write_tables(sim, dir)
}

fn write_tables(sim: &dyn Simulation, dir: &Path) -> Result<(), RunError> {
    for (name, table) in sim.tables() {
        table.write_csv(&dir.join(name)).map_err(io_err)?;
    }
    Ok(())
}

/// Reads back the tables and `result.pvd` of the run being resumed, cut at its checkpoint.
fn read_back(
    sim: &mut dyn Simulation,
    dir: &Path,
    pvd: &mut PvdCollection,
) -> Result<(), RunError> {
    let step = sim.step_index() as f64;
    for (name, table) in sim.tables_mut() {
        *table = SeriesTable::read_csv(&dir.join(name))
            .map_err(|e| RunError::BadInput(e.to_string()))?;
        table.truncate_rows_where_first_column_greater_than(step);
    }
    *pvd = PvdCollection::read(&dir.join("result.pvd"))
        .map_err(|e| RunError::BadInput(e.to_string()))?;
    Ok(())
}

/// The time loop of a built simulation with its outputs (see the module's documentation).
pub fn drive(
    sim: &mut dyn Simulation,
    schedule: OutputSchedule,
    opts: &RunOptions,
    quiet: bool,
    comm: Option<&dyn Communicator>,
) -> Result<serde_json::Value, RunError> {
    let root = sim.is_root();
    let dir = opts.out.as_path();
    if root {
        create_output_dir(&dir.join("frames"))?;
        if !quiet {
            for note in sim.notes() {
                eprintln!("xper: note: {note}");
            }
        }
    }
    let mut pvd = PvdCollection::default();
    if opts.resume {
        read_back(sim, dir, &mut pvd)?;
    } else {
        sim.sync();
        if root {
            // A checkpoint of an earlier run in the same directory is not this run's.
            let _ = std::fs::remove_file(dir.join("checkpoint.bin"));
            sim.write_frame(dir, &mut pvd)?;
        }
    }
    let (steps, position) = sim.progress();
    let bar = progress_bar(quiet || !root, steps, position);
    sim.begin();
    let started = Instant::now();
    let first_step = sim.step_index();
    let mut stepping = 0.0;
    let mut failure = None;
    while !sim.is_complete() && opts.stop_at_step.is_none_or(|s| sim.step_index() < s) {
        match sim.step() {
            Ok(wall) => {
                stepping += wall;
                let step = sim.step_index();
                let frame = step % schedule.frame_every == 0 || sim.is_complete();
                let checkpoint = step % schedule.checkpoint_every == 0;
                if frame || checkpoint {
                    sim.sync();
                }
                if frame && root {
                    sim.write_frame(dir, &mut pvd)?;
                }
                if checkpoint && root {
                    write_checkpoint(sim, dir)?;
                }
                if step % 10 == 0 || sim.is_complete() {
                    bar.set_position(sim.progress().1);
                    bar.set_message(sim.status_line());
                }
            }
            Err(f) => {
                if f.show_state {
                    sim.sync();
                    if root {
                        sim.write_frame(dir, &mut pvd)?;
                    }
                }
                if let Some(comm) = comm.filter(|_| !f.collective) {
                    // Other processes may be waiting in a collective this one will not reach.
                    comm.abort(&format!("step {}: {}", f.step, f.message), 1);
                }
                let checkpoint = dir.join("checkpoint.bin");
                let kept = if checkpoint.exists() {
                    format!("the last checkpoint is kept in {}", checkpoint.display())
                } else {
                    "no checkpoint was written".to_string()
                };
                failure = Some(format!(
                    "step {} (t = {:.6e} s): {}; {kept}",
                    f.step, f.time, f.message
                ));
                break;
            }
        }
    }
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
        write_checkpoint(sim, dir)?;
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
