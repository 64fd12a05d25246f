//! The [`Simulation`] every physics implements, so that one run driver
//! ([`crate::drive`]) steps them all, on one process or on the processes of a
//! communicator, with the same schedule of series, frames and checkpoints.
//!
//! A simulation holds its whole state on the process that writes outputs (rank 0, or the only
//! process) and, in a distributed run, its share of the work on every process. Collective
//! calls ([`Simulation::step`], [`Simulation::sync`], [`Simulation::rank_summaries`]) are made
//! by every process at the same steps; the writing calls only by the writing process.

use crate::comparison::SerialComparison;
use crate::ranks::RankSummary;
use crate::state::{ArrayInfo, StateArray, StateView};
use crate::RunError;
use std::path::{Path, PathBuf};
use xper_io::{PvdCollection, SeriesTable};

/// Options of a run (`xper run`).
#[derive(Clone, Debug)]
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
    /// Largest memory the run may need by its estimate (bytes,
    /// `xper_simulation::resources::estimate`); the memory available now when `None`.
    pub max_memory: Option<f64>,
}

/// How often a run writes its outputs (steps).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct OutputSchedule {
    /// Steps between frames (the last step has one too).
    pub frame_every: u64,
    /// Steps between checkpoints (the end has one too).
    pub checkpoint_every: u64,
}

/// A step that could not be done.
#[derive(Debug)]
pub struct StepFailure {
    /// What went wrong.
    pub message: String,
    /// The step the failure is reported at (usually the one attempted).
    pub step: u64,
    /// Simulated time reported with it (s).
    pub time: f64,
    /// Whether every process met it at the same step (a distributed run then ends normally);
    /// otherwise the driver aborts the other processes, which would wait for this one.
    pub collective: bool,
    /// Whether the failed state is shown in a last frame (it is never checkpointed).
    pub show_state: bool,
}

/// What the summary and the closing message of a run need of its end.
pub struct RunFacts<'a> {
    /// The scene file as given.
    pub scene_file: &'a Path,
    /// `completed`, `stopped` or `failed` ([`run_status`]).
    pub status: &'static str,
    /// Why the run failed (empty otherwise).
    pub message: String,
    /// The step this invocation started from (0, or the checkpoint's on resume).
    pub first_step: u64,
    /// Wall time of this invocation (s).
    pub wall: f64,
    /// Each process's load and communication (empty on one process).
    pub ranks: Vec<RankSummary>,
    /// The same steps rerun on one process (`--compare-serial`).
    pub comparison: Option<SerialComparison>,
}

/// The status of a run in its summary: `failed`, `completed` (it reached its end) or `stopped`.
pub fn run_status(failed: bool, complete: bool) -> &'static str {
    match (failed, complete) {
        (true, _) => "failed",
        (false, true) => "completed",
        (false, false) => "stopped",
    }
}

/// One physics' state and stepping, as the run driver sees it.
pub trait Simulation {
    /// Steps done.
    fn step_index(&self) -> u64;
    /// Simulated time (s).
    fn time(&self) -> f64;
    /// Whether the run has reached the end the scene asks for.
    fn is_complete(&self) -> bool;
    /// Steps the scene asks for, and steps done so far as the progress bar counts them.
    fn progress(&self) -> (u64, u64);
    /// A short line for the progress bar about the last step.
    fn status_line(&self) -> String;
    /// Whether this process writes the outputs.
    fn is_root(&self) -> bool;
    /// Processes of the run.
    fn processes(&self) -> usize;
    /// Remarks to print before the run starts (on the writing process, unless quiet).
    fn notes(&self) -> Vec<String> {
        Vec::new()
    }
    /// Marks the start of stepping (collective): communication is counted from here.
    fn begin(&mut self) {}
    /// Advances one step (collective) and appends its rows to the tables; returns the step's
    /// wall time (s), outputs excluded.
    fn step(&mut self) -> Result<f64, StepFailure>;
    /// Brings the whole state to the writing process (collective; nothing on one process).
    fn sync(&mut self);
    /// Writes the frame of the current state under `dir/frames` and lists it in `pvd`.
    fn write_frame(&mut self, dir: &Path, pvd: &mut PvdCollection) -> Result<(), RunError>;
    /// The payload of `checkpoint.bin` for the current state (the driver seals it, see
    /// [`crate::checkpoint`]).
    fn checkpoint(&self) -> Result<Vec<u8>, RunError>;
    /// Hash of the scene files the simulation was built from ([`crate::checkpoint::fnv1a`]).
    fn scene_hash(&self) -> u64;
    /// The tables written beside the checkpoint (`series.csv`, ...), by file name.
    fn tables(&self) -> Vec<(&'static str, &SeriesTable)>;
    /// The same tables, to be replaced when a run resumes.
    fn tables_mut(&mut self) -> Vec<(&'static str, &mut SeriesTable)>;
    /// Each process's load and communication over a run of `wall` seconds (collective; empty
    /// on one process).
    fn rank_summaries(&mut self, wall: f64) -> Vec<RankSummary>;
    /// `--compare-serial` on the writing process: the steps of this distributed run, which
    /// took `stepping` seconds, rerun on one process (`None` when not asked for).
    fn compare_serial(&mut self, stepping: f64) -> Result<Option<SerialComparison>, RunError>;
    /// Writes `summary.json` and the plots into `dir`; returns the summary.
    fn write_summary(&self, dir: &Path, facts: &RunFacts) -> Result<serde_json::Value, RunError>;
    /// The line printed when the run ends (unless quiet).
    fn closing_line(&self, facts: &RunFacts, dir: &Path) -> String;
    /// The arrays of the state this physics offers to scripts ([`crate::state`]).
    fn arrays(&self) -> Vec<ArrayInfo> {
        Vec::new()
    }
    /// Names of the groups the `group` arrays index (empty when this physics has none).
    fn group_names(&self) -> Vec<String> {
        Vec::new()
    }
    /// The array `name` of the state on the writing process, as of the last
    /// [`Simulation::sync`] (`None` when this physics has no such array).
    fn array(&self, _name: &str) -> Option<StateArray> {
        None
    }
    /// The array `name` read in place, when the simulation keeps it as contiguous reals of
    /// [`Simulation::array`]'s layout in a run on one process (`None` otherwise). Its address
    /// holds across steps and [`Simulation::set_array`]; [`Simulation::add_bodies`] may move it.
    fn view(&self, _name: &str) -> Option<StateView> {
        None
    }
    /// Writes `values` (row-major, of shape `shape`, which must be the one
    /// [`Simulation::array`] gives) into the writable array `name` between steps (on one
    /// process); the error says why it was refused, and nothing is written then.
    fn set_array(&mut self, name: &str, _shape: &[usize], _values: &[f64]) -> Result<(), String> {
        Err(format!("{name}: not an array this simulation can set"))
    }
    /// Adds the bodies of `text`, a scene file holding only them and what they need, between
    /// steps (on one process); returns their indices in the bodies' arrays.
    fn add_bodies(&mut self, _text: &str) -> Result<Vec<usize>, String> {
        Err("this simulation cannot add bodies".into())
    }
}
