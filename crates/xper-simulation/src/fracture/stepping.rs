//! The two ways `xper run` advances a fracture scene: on this process ([`SerialFracture`]) or
//! on the processes of a communicator ([`DistributedFractureRun`], under `mpirun`), behind one
//! trait so the run loop and its outputs are the same.

use xper_domain::{CommStats, Communicator, DistributedFracture};
use xper_fracture::{FractureModel, FractureStepError, FractureStepReport, FractureStepper};

use crate::comparison::SerialComparison;
use crate::ranks::{rank_summaries, RankSummary};
use crate::RunError;

/// A fracture run advanced step by step. `whole` is the model the outputs are written from:
/// on the writing process it holds the whole model's step, time and energy after every step
/// and its full state after [`FractureRun::sync`].
pub trait FractureRun {
    /// One step.
    fn step(&mut self, whole: &mut FractureModel) -> Result<FractureStepReport, FractureStepError>;
    /// Brings the full state into `whole` on the writing process (collective: every process
    /// calls it at the same steps).
    fn sync(&mut self, whole: &mut FractureModel);
    /// Whether this process writes the outputs.
    fn is_root(&self) -> bool;
    /// Number of processes.
    fn processes(&self) -> usize;
    /// Each process's load and communication over a run of `wall` seconds (collective; empty
    /// on one process).
    fn rank_summaries(&mut self, wall: f64) -> Vec<RankSummary>;
}

/// A run on this process.
#[derive(Default)]
pub struct SerialFracture {
    stepper: FractureStepper,
}

impl FractureRun for SerialFracture {
    fn step(&mut self, whole: &mut FractureModel) -> Result<FractureStepReport, FractureStepError> {
        self.stepper.step(whole)
    }
    fn sync(&mut self, _whole: &mut FractureModel) {}
    fn is_root(&self) -> bool {
        true
    }
    fn processes(&self) -> usize {
        1
    }
    fn rank_summaries(&mut self, _wall: f64) -> Vec<RankSummary> {
        Vec::new()
    }
}

/// A run on the processes of a communicator ([`DistributedFracture`]).
pub struct DistributedFractureRun<'c> {
    run: DistributedFracture<'c, dyn Communicator + 'c>,
    comm: &'c dyn Communicator,
    /// The communication before the first step (distribution), left out of the summary.
    setup: CommStats,
}

impl<'c> DistributedFractureRun<'c> {
    /// Distributes `whole` (the same fresh or restored model on every process).
    pub fn new(comm: &'c dyn Communicator, whole: &FractureModel) -> Self {
        let run = DistributedFracture::new(comm, whole);
        DistributedFractureRun {
            run,
            comm,
            setup: comm.stats(),
        }
    }
}

impl FractureRun for DistributedFractureRun<'_> {
    fn step(&mut self, whole: &mut FractureModel) -> Result<FractureStepReport, FractureStepError> {
        let report = self.run.step()?;
        whole.step = report.step;
        whole.time = report.time;
        whole.energy = report.energy;
        Ok(report)
    }
    fn sync(&mut self, whole: &mut FractureModel) {
        self.run.gather(whole);
    }
    fn is_root(&self) -> bool {
        self.comm.rank() == 0
    }
    fn processes(&self) -> usize {
        self.comm.size()
    }
    fn rank_summaries(&mut self, wall: f64) -> Vec<RankSummary> {
        rank_summaries(self.comm, self.run.load(), &self.setup, wall)
    }
}

/// Runs `start` on this process up to `end`'s step and compares (`--compare-serial`): the
/// largest difference of a nodal displacement stands for the position difference.
pub fn compare_serial(
    start: FractureModel,
    end: &FractureModel,
    distributed_wall: f64,
    processes: usize,
) -> Result<SerialComparison, RunError> {
    let mut stepper = FractureStepper::new();
    SerialComparison::rerun(
        start,
        end.step,
        |m: &FractureModel| m.step,
        |m| stepper.step(m).map(drop),
        |m| m.largest_displacement_difference(end),
        (distributed_wall, processes),
    )
}
