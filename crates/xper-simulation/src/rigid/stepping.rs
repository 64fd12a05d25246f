//! The two ways `xper run` advances a rigid scene: on this process ([`SerialRun`]) or on the
//! processes of a communicator ([`DistributedRun`], e.g. under `mpirun`), behind one trait so
//! the run loop and its outputs are the same.

use crate::CliError;
use serde::Serialize;
use std::borrow::Cow;
use std::path::{Path, PathBuf};
use xper_domain::{CommStats, Communicator, DistributedParams, DistributedStepper, RankLoad};
use xper_nscd::{MoreauJean, StepError, StepReport, World};

/// A rigid run advanced step by step.
pub trait RigidRun {
    /// One step: the outer error is the run's own (an output that could not be written), the
    /// inner one the step's.
    fn step(&mut self) -> Result<Result<StepReport, StepError>, CliError>;
    /// The whole world on the process that writes outputs, `None` on the others; collective in
    /// a distributed run (every process calls it at the same steps).
    fn snapshot(&mut self) -> Option<Cow<'_, World>>;
    /// Steps done.
    fn step_index(&self) -> u64;
    /// Simulated time (s).
    fn time(&self) -> f64;
    /// Bodies of the whole world.
    fn body_count(&self) -> usize;
    /// Each process's load and communication over a run of `wall` seconds (collective; empty
    /// on one process).
    fn rank_summaries(&mut self, wall: f64) -> Vec<RankSummary>;
}

/// A process's share of a distributed run, in `summary.json`.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct RankSummary {
    /// Process rank.
    pub rank: usize,
    /// Movable bodies (fracture: elements) owned at the end.
    pub bodies: usize,
    /// Shadow copies held at the end.
    pub shadows: usize,
    /// Contacts (fracture: interface points) owned at the last step.
    pub contacts: usize,
    /// Bodies shared with other processes in the last solve.
    pub interface_bodies: usize,
    /// Bodies received by migration during the run.
    pub migrated_in: u64,
    /// Fluid cells held (runs with a fluid).
    pub cells: usize,
    /// Times the fluid's blocks of rows were cut again as the grains moved (runs with a
    /// fluid; the time it took is in the step times).
    pub recuts: u64,
    /// Messages sent from the first step on (the initial distribution is left out; the
    /// gathers of outputs are in).
    pub messages: u64,
    /// Bytes sent, counted as `messages`.
    pub bytes: u64,
    /// Seconds inside communication calls from the first step on, waiting included.
    pub communication_s: f64,
    /// Share of the run's wall time spent communicating.
    pub communication_share: f64,
}

/// Refuses, before anything runs, what a distributed run cannot do.
pub fn check_distributable(
    scene: &xper_scene::Scene,
    file: &Path,
    distributed: bool,
) -> Result<(), CliError> {
    if !distributed {
        return Ok(());
    }
    if scene.solver.kind != xper_scene::SolverKind::Nlgs {
        return Err(CliError::BadInput(format!(
            "{}: [solver] kind: a distributed run solves by NLGS only (the assembled solvers are \
             not distributed)",
            file.display()
        )));
    }
    if !scene.output.dump_problems.is_empty() {
        return Err(CliError::BadInput(format!(
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
    fn step(&mut self) -> Result<Result<StepReport, StepError>, CliError> {
        if self.dumps.binary_search(&(self.world.step + 1)).is_ok() {
            self.stepper.capture_next_problem();
        }
        let result = self.stepper.step(&mut self.world);
        if let Some(problem) = self.stepper.take_problem() {
            // Written also when the step then failed: the problem it could not solve.
            let step = self.world.step + u64::from(result.is_err());
            crate::run::write_problem(&self.out, step, &problem)?;
        }
        Ok(result)
    }
    fn snapshot(&mut self) -> Option<Cow<'_, World>> {
        Some(Cow::Borrowed(&self.world))
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
    fn step(&mut self) -> Result<Result<StepReport, StepError>, CliError> {
        Ok(self.stepper.step())
    }
    fn snapshot(&mut self) -> Option<Cow<'_, World>> {
        self.stepper.gather().map(Cow::Owned)
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
}

/// Every process's `load` and communication since `setup` (the stats when the run was
/// distributed) over a run of `wall` seconds (collective).
pub fn rank_summaries(
    comm: &dyn Communicator,
    load: RankLoad,
    setup: &CommStats,
    wall: f64,
) -> Vec<RankSummary> {
    let stats = comm.stats().since(setup);
    let mine = [
        load.bodies as f64,
        load.shadows as f64,
        load.contacts as f64,
        load.interface_bodies as f64,
        load.migrated_in as f64,
        stats.messages as f64,
        stats.bytes as f64,
        stats.time.as_secs_f64(),
        load.cells as f64,
        load.recuts as f64,
    ];
    (comm.all_gather(&mine).iter().enumerate())
        .map(|(rank, v)| RankSummary {
            rank,
            bodies: v[0] as usize,
            shadows: v[1] as usize,
            contacts: v[2] as usize,
            interface_bodies: v[3] as usize,
            migrated_in: v[4] as u64,
            cells: v[8] as usize,
            recuts: v[9] as u64,
            messages: v[5] as u64,
            bytes: v[6] as u64,
            communication_s: v[7],
            communication_share: if wall > 0.0 { v[7] / wall } else { 0.0 },
        })
        .collect()
}
