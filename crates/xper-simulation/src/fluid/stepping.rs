//! The two ways `xper run` advances a scene with a fluid: on this process ([`SerialFluid`]) or
//! on the processes of a communicator ([`DistributedFluidRun`], under `mpirun`: the grid cut
//! into blocks of rows), behind one trait so the run loop and its outputs are the same.

use xper_domain::{CommStats, Communicator, DistributedFluid};
use xper_fluid::{CoupledError, CoupledReport, CoupledState, CoupledStepper, FluidParams};

use crate::comparison::SerialComparison;
use crate::ranks::{rank_summaries, RankSummary};
use crate::RunError;

/// A run with a fluid advanced step by step. `whole` is the state the outputs are written
/// from: on the writing process it holds the grains and the fluid's time after every step and
/// the whole fluid after [`FluidRun::sync`].
pub trait FluidRun {
    /// One step.
    fn step(&mut self, whole: &mut CoupledState) -> Result<CoupledReport, CoupledError>;
    /// Brings the whole fluid into `whole` on the writing process (collective: every process
    /// calls it at the same steps).
    fn sync(&mut self, whole: &mut CoupledState);
    /// Whether this process writes the outputs.
    fn is_root(&self) -> bool;
    /// Number of processes.
    fn processes(&self) -> usize;
    /// Body indices of the immersed disks.
    fn immersed(&self) -> &[usize];
    /// Marks the start of stepping (collective): the processes wait for each other (for the
    /// writing process's first frame), and communication is counted from here.
    fn begin(&mut self) {}
    /// Each process's load and communication over a run of `wall` seconds (collective; empty
    /// on one process).
    fn rank_summaries(&mut self, wall: f64) -> Vec<RankSummary>;
    /// Cells of the pressure solve's coarsest grid that this process relaxes whole (`None` on
    /// one process).
    fn pressure_gathered_cells(&self) -> Option<usize> {
        None
    }
}

/// A run on this process.
pub struct SerialFluid {
    params: FluidParams,
    stepper: CoupledStepper,
}

impl SerialFluid {
    /// The stepper of `state`.
    pub fn new(params: &FluidParams, state: &CoupledState) -> Result<Self, xper_fluid::FluidError> {
        Ok(SerialFluid {
            params: params.clone(),
            stepper: CoupledStepper::new(params, state)?,
        })
    }
}

impl FluidRun for SerialFluid {
    fn step(&mut self, whole: &mut CoupledState) -> Result<CoupledReport, CoupledError> {
        self.stepper.step(&self.params, whole)
    }
    fn sync(&mut self, _whole: &mut CoupledState) {}
    fn is_root(&self) -> bool {
        true
    }
    fn processes(&self) -> usize {
        1
    }
    fn immersed(&self) -> &[usize] {
        self.stepper.immersed()
    }
    fn rank_summaries(&mut self, _wall: f64) -> Vec<RankSummary> {
        Vec::new()
    }
}

/// A run on the processes of a communicator ([`DistributedFluid`]).
pub struct DistributedFluidRun<'c> {
    run: DistributedFluid<'c, dyn Communicator + 'c>,
    comm: &'c dyn Communicator,
    /// The communication before the first step (distribution, waiting for the first frame),
    /// left out of the summary.
    setup: CommStats,
}

impl<'c> DistributedFluidRun<'c> {
    /// Distributes `whole` (the same fresh or restored state on every process).
    pub fn new(
        comm: &'c dyn Communicator,
        params: &FluidParams,
        whole: &CoupledState,
    ) -> Result<Self, xper_fluid::FluidError> {
        let run = DistributedFluid::new(comm, params, whole)?;
        Ok(DistributedFluidRun {
            run,
            comm,
            setup: comm.stats(),
        })
    }
}

impl FluidRun for DistributedFluidRun<'_> {
    fn step(&mut self, whole: &mut CoupledState) -> Result<CoupledReport, CoupledError> {
        let report = self.run.step()?;
        let block = self.run.state();
        whole.world.clone_from(&block.world);
        whole.fluid.time = block.fluid.time;
        whole.fluid.step = block.fluid.step;
        Ok(report)
    }
    fn sync(&mut self, whole: &mut CoupledState) {
        self.run.gather(whole);
    }
    fn is_root(&self) -> bool {
        self.comm.rank() == 0
    }
    fn processes(&self) -> usize {
        self.comm.size()
    }
    fn immersed(&self) -> &[usize] {
        self.run.immersed()
    }
    fn begin(&mut self) {
        self.comm.all_reduce_max(&mut [0.0]);
        self.setup = self.comm.stats();
    }
    fn rank_summaries(&mut self, wall: f64) -> Vec<RankSummary> {
        rank_summaries(self.comm, self.run.load(), &self.setup, wall)
    }
    fn pressure_gathered_cells(&self) -> Option<usize> {
        Some(self.run.pressure_gathered_cells())
    }
}

/// Runs `start` on this process up to `end`'s step and compares (`--compare-serial`): the
/// largest distance between a grain's positions at the end of the two runs.
pub fn compare_serial(
    params: &FluidParams,
    start: CoupledState,
    end: &CoupledState,
    distributed_wall: f64,
    processes: usize,
) -> Result<SerialComparison, RunError> {
    let mut stepper = CoupledStepper::new(params, &start)
        .map_err(|e| RunError::Runtime(format!("--compare-serial: serial run: {e}")))?;
    SerialComparison::rerun(
        start,
        end.world.step,
        |s: &CoupledState| s.world.step,
        |s| stepper.step(params, s).map(drop),
        |s| crate::rigid::stepping::largest_position_difference(&s.world, &end.world),
        (distributed_wall, processes),
    )
}
