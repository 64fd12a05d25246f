//! The two ways `xper run` advances a rigid scene: on this process ([`SerialRun`]) or on the
//! processes of a communicator ([`DistributedRun`], e.g. under `mpirun`), behind one trait so
//! the run loop and its outputs are the same.

use crate::comparison::SerialComparison;
use crate::ranks::{rank_summaries, RankSummary};
use crate::RunError;
use std::path::{Path, PathBuf};
use xper_decomposition::rigid::stepper::{DistributedParams, DistributedStepper};
use xper_nscd::{MoreauJean, StepError, StepReport, World};
use xper_parallel::{CommStats, Communicator};

/// A rigid run advanced step by step.
pub trait RigidRun {
    /// One step: the outer error is the run's own (an output that could not be written), the
    /// inner one the step's.
    fn step(&mut self) -> Result<Result<StepReport, StepError>, RunError>;
    /// The world, when this process holds it whole (a run on one process).
    fn whole(&self) -> Option<&World>;
    /// [`RigidRun::whole`], to change between steps.
    fn whole_mut(&mut self) -> Option<&mut World>;
    /// The whole world gathered on the process that writes outputs, `None` on the others and
    /// on one process (collective: every process calls it at the same steps).
    fn gather(&mut self) -> Option<World>;
    /// Steps done.
    fn step_index(&self) -> u64;
    /// Simulated time (s).
    fn time(&self) -> f64;
    /// Bodies of the whole world.
    fn body_count(&self) -> usize;
    /// Each process's load and communication over a run of `wall` seconds (collective; empty
    /// on one process).
    fn rank_summaries(&mut self, wall: f64) -> Vec<RankSummary>;
    /// Marks the start of stepping: communication is counted from here.
    fn begin(&mut self) {}
}

/// Refuses, before anything runs, what a distributed run cannot do.
pub fn check_distributable(
    scene: &crate::build::RigidScene,
    file: &Path,
    distributed: bool,
) -> Result<(), RunError> {
    if !distributed {
        return Ok(());
    }
    if scene.solver.kind != xper_scene::VelocitySolverKind::Nlgs {
        return Err(RunError::BadInput(format!(
            "{}: [solver] kind: a distributed run solves by NLGS only (the assembled solvers are \
             not distributed)",
            file.display()
        )));
    }
    if crate::build::scene_has_cell(scene) {
        return Err(RunError::BadInput(format!(
            "{}: [cell]: a periodic cell runs on one process only for now",
            file.display()
        )));
    }
    if crate::build::scene_has_events(scene) {
        return Err(RunError::BadInput(format!(
            "{}: [[events]] run on one process only for now",
            file.display()
        )));
    }
    let pressure = |d: &xper_scene::Drive| matches!(d, xper_scene::Drive::Pressure(_));
    if let Some(k) = (scene.bodies.iter()).position(|b| b.drives.iter().any(pressure)) {
        return Err(RunError::BadInput(format!(
            "{}: body {k} is driven by a pressure, which runs on one process only for now (its \
             loaded length or area follows bodies another process may hold)",
            file.display()
        )));
    }
    if !scene.output.dump_problems.is_empty() {
        return Err(RunError::BadInput(format!(
            "{}: [output] dump_problems: problems are dumped by runs on one process only",
            file.display()
        )));
    }
    Ok(())
}

/// A run on this process, writing the problems of the steps listed in `dumps`.
pub struct SerialRun {
    world: World,
    stepper: MoreauJean,
    dumps: Vec<u64>,
    out: PathBuf,
}

impl SerialRun {
    /// A run of `world` writing dumped problems under `out/problems`.
    pub fn new(world: World, dumps: Vec<u64>, out: PathBuf) -> Self {
        SerialRun {
            world,
            stepper: MoreauJean::new(),
            dumps,
            out,
        }
    }
}

impl RigidRun for SerialRun {
    fn step(&mut self) -> Result<Result<StepReport, StepError>, RunError> {
        if self.dumps.binary_search(&(self.world.step + 1)).is_ok() {
            self.stepper.capture_next_problem();
        }
        let result = self.stepper.step(&mut self.world);
        if let Some(problem) = self.stepper.take_problem() {
            // Written also when the step then failed: the problem it could not solve.
            let step = self.world.step + u64::from(result.is_err());
            super::outputs::write_problem(&self.out, step, &problem)?;
        }
        Ok(result)
    }
    fn whole(&self) -> Option<&World> {
        Some(&self.world)
    }
    fn whole_mut(&mut self) -> Option<&mut World> {
        Some(&mut self.world)
    }
    fn gather(&mut self) -> Option<World> {
        None
    }
    fn step_index(&self) -> u64 {
        self.world.step
    }
    fn time(&self) -> f64 {
        self.world.time
    }
    fn body_count(&self) -> usize {
        self.world.bodies.len()
    }
    fn rank_summaries(&mut self, _wall: f64) -> Vec<RankSummary> {
        Vec::new()
    }
}

/// A run on the processes of a communicator ([`DistributedStepper`]).
pub struct DistributedRun<'c> {
    stepper: DistributedStepper<'c, dyn Communicator + 'c>,
    comm: &'c dyn Communicator,
    /// The communication before the first step (distribution), left out of the summary.
    setup: CommStats,
}

impl<'c> DistributedRun<'c> {
    /// Distributes `world`. Space is re-partitioned every `gcd(checkpoint_every, 50)` steps, so
    /// at every checkpoint: a run resumed on the same number of processes then continues
    /// exactly as the uninterrupted one.
    pub fn new(comm: &'c dyn Communicator, world: World, checkpoint_every: u64) -> Self {
        let params = DistributedParams {
            rebalance_every: gcd(checkpoint_every.max(1), 50),
            ..Default::default()
        };
        let stepper = DistributedStepper::new(comm, world, params);
        DistributedRun {
            stepper,
            comm,
            setup: comm.stats(),
        }
    }
}

fn gcd(a: u64, b: u64) -> u64 {
    if b == 0 {
        a
    } else {
        gcd(b, a % b)
    }
}

impl RigidRun for DistributedRun<'_> {
    fn step(&mut self) -> Result<Result<StepReport, StepError>, RunError> {
        Ok(self.stepper.step())
    }
    fn whole(&self) -> Option<&World> {
        None
    }
    fn whole_mut(&mut self) -> Option<&mut World> {
        None
    }
    fn gather(&mut self) -> Option<World> {
        self.stepper.gather()
    }
    fn step_index(&self) -> u64 {
        self.stepper.world().step
    }
    fn time(&self) -> f64 {
        self.stepper.world().time
    }
    fn body_count(&self) -> usize {
        self.stepper.world().bodies.len()
    }
    fn rank_summaries(&mut self, wall: f64) -> Vec<RankSummary> {
        rank_summaries(self.comm, self.stepper.load(), &self.setup, wall)
    }
    fn begin(&mut self) {
        self.setup = self.comm.stats();
    }
}

/// Runs `start` on this process up to `end`'s step and compares (`--compare-serial`).
pub fn compare_serial(
    start: World,
    end: &World,
    distributed_wall: f64,
    processes: usize,
) -> Result<SerialComparison, RunError> {
    let mut stepper = MoreauJean::new();
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
