//! A scene file turned into a run: read once, its memory estimate checked, its simulation
//! built (or restored on `--resume`), then stepped by the one time loop ([`xper_run::drive`]).

use crate::resources;
use crate::scene::LoadedScene;
use xper_parallel::Communicator;
use xper_run::{drive, resume, OutputSchedule, RunError, RunOptions, SceneFile, Simulation};

/// A scene made ready to run: its simulation (at time 0, or restored on `opts.resume`), the
/// schedule of its outputs and what the driver keeps of its file.
pub struct Prepared<'c> {
    /// The simulation.
    pub simulation: Box<dyn Simulation + 'c>,
    /// Frames and checkpoints.
    pub schedule: OutputSchedule,
    /// The scene file's text and notes, and the checkpoint resumed.
    pub file: SceneFile,
}

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
    let distributed = comm.filter(|c| c.size() > 1);
    let Prepared {
        mut simulation,
        schedule,
        file,
    } = prepare(opts, distributed)?;
    drive(
        simulation.as_mut(),
        schedule,
        opts,
        quiet,
        distributed,
        file,
    )
}

/// The scene of `opts` read once, its memory estimate checked (on `--resume`, the scene
/// compared with the checkpoint's) and its simulation built, over `comm` when it has more
/// than one process: everything [`drive`] (or a script stepping it) starts from.
pub fn prepare<'c>(
    opts: &RunOptions,
    comm: Option<&'c dyn Communicator>,
) -> Result<Prepared<'c>, RunError> {
    let (scene, text) = LoadedScene::read_with_text(&opts.scene)?;
    let distributed = comm.filter(|c| c.size() > 1);
    let processes = distributed.map_or(1, |c| c.size());
    let fits = resources::ensure_fits(
        &resources::estimate(&scene),
        opts.max_memory,
        processes,
        &opts.scene,
    );
    if let (Err(e), Some(comm)) = (&fits, distributed) {
        comm.abort(&e.to_string(), 2);
    }
    fits?;
    let schedule = scene.output_schedule();
    let (resumed, notes) = match opts.resume {
        true => {
            let (header, notes) = resume::check_resume(&opts.out, scene.hash(), &text)?;
            (Some(header), notes)
        }
        false => (None, Vec::new()),
    };
    let simulation = scene.into_simulation(opts, distributed)?;
    let file = SceneFile {
        text,
        notes,
        resumed,
    };
    Ok(Prepared {
        simulation,
        schedule,
        file,
    })
}
