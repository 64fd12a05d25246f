//! Rigid grains in an incompressible viscous fluid (MAC Navier-Stokes, direct-forcing
//! immersed boundary, NSCD between grains): the [`Simulation`] of a scene with `[fluid]`,
//! on this process ([`stepping::SerialFluid`]) or with the grid cut into blocks of rows, one
//! per process ([`stepping::DistributedFluidRun`]).
//!
//! Outputs: one fluid frame (`.vti`: velocity, pressure, vorticity, solid fraction) and the
//! bodies and contacts (`.vtu`) per output step, `series.csv` (one row per step),
//! `particles.csv` (each immersed disk at each step: position, velocity, hydrodynamic force),
//! `series.png`, `particles.png`, `summary.json` and checkpoints.

pub mod build;
pub mod outputs;
pub mod state;
pub mod stepping;

use crate::checkpoint::{checkpoint_bytes, read_checkpoint};
use crate::comparison::SerialComparison;
use crate::outputs::{io_err, write_vtu_parts};
use crate::ranks::RankSummary;
use crate::rigid::frames::{bodies_grid, contacts_grid};
use crate::simulation::RunOptions;
use crate::simulation::{RunFacts, Simulation, StepFailure};
use crate::RunError;
use build::{coupled_state, fluid_params};
use outputs::{fluid_image, FLUID_SERIES_COLUMNS, PARTICLE_COLUMNS};
use std::path::Path;
use stepping::{DistributedFluidRun, FluidRun, SerialFluid};
use xper_domain::Communicator;
use xper_fluid::{CoupledReport, CoupledState, FluidParams};
use xper_io::{write_json_atomic, write_vti, PvdCollection, SeriesTable};
use xper_math::Real;
use xper_scene::Scene;

/// A scene with a fluid being run.
pub struct FluidSimulation<'c> {
    runner: Box<dyn FluidRun + 'c>,
    /// The whole state on the writing process: the grains and the fluid's time after every
    /// step, the whole fluid after a sync.
    state: CoupledState,
    params: FluidParams,
    immersed: Vec<usize>,
    scene: Scene,
    scene_hash: u64,
    series: SeriesTable,
    particles: SeriesTable,
    compare_from: Option<CoupledState>,
    /// Pressure cycles, contacts and the time step of the last step, for the progress bar.
    last: (u32, usize, f64),
}

impl<'c> FluidSimulation<'c> {
    /// The run of `scene` (whose file hashes to `scene_hash`) at time 0 or, with
    /// `opts.resume`, from the checkpoint in `opts.out`; over `comm` when given.
    pub fn new(
        scene: Scene,
        scene_hash: u64,
        opts: &RunOptions,
        comm: Option<&'c dyn Communicator>,
    ) -> Result<Self, RunError> {
        let desc = scene
            .fluid
            .as_ref()
            .ok_or_else(|| RunError::BadInput("not a fluid scene".into()))?;
        let params = fluid_params(desc, scene.dt);
        let state = if opts.resume {
            let mut state: CoupledState =
                read_checkpoint(&opts.out, "a checkpoint of a fluid scene")?;
            crate::rigid::build::take_solver_limits(&mut state.world, &scene);
            same_layout(&state, &coupled_state(&scene, desc, &params)).map_err(|why| {
                let file = opts.out.join("checkpoint.bin");
                RunError::BadInput(format!("{}: {why}", file.display()))
            })?;
            state
        } else {
            coupled_state(&scene, desc, &params)
        };
        let setup = |e: xper_fluid::FluidError| {
            RunError::BadInput(format!("{}: {e}", opts.scene.display()))
        };
        let runner: Box<dyn FluidRun + 'c> = match comm {
            Some(comm) => Box::new(DistributedFluidRun::new(comm, &params, &state).map_err(setup)?),
            None => Box::new(SerialFluid::new(&params, &state).map_err(setup)?),
        };
        let immersed = runner.immersed().to_vec();
        let compare_from =
            (opts.compare_serial && runner.is_root() && comm.is_some()).then(|| state.clone());
        Ok(FluidSimulation {
            runner,
            state,
            params,
            immersed,
            scene,
            scene_hash,
            series: SeriesTable::new(&FLUID_SERIES_COLUMNS),
            particles: SeriesTable::new(&PARTICLE_COLUMNS),
            compare_from,
            last: (0, 0, 0.0),
        })
    }

    /// The whole state (on the writing process; the whole fluid after a sync).
    pub fn state(&self) -> &CoupledState {
        &self.state
    }

    fn duration(&self) -> Real {
        self.scene.steps as Real * self.scene.dt
    }

    fn push(&mut self, r: &CoupledReport) {
        let (f, g) = (&r.fluid, &r.grains);
        self.series.push(vec![
            g.step as f64,
            f.time,
            f.dt,
            g.kinetic,
            f.kinetic_energy,
            f.max_speed,
            f.pressure.cycles as f64,
            f.pressure.relative_residual,
            f.divergence[1],
            g.contacts as f64,
            g.active as f64,
            g.iterations as f64,
            g.converged as u8 as f64,
            f.times[3] + g.times.total,
            f.times[3],
            g.times.total,
        ]);
        let bodies = &self.state.world.bodies;
        for (&b, force) in self.immersed.iter().zip(&f.forces) {
            let (x, v) = (bodies.position[b], bodies.velocity[b]);
            self.particles.push(vec![
                g.step as f64,
                f.time,
                b as f64,
                x.x,
                x.y,
                bodies.rotation[b],
                v.x,
                v.y,
                bodies.angular_velocity[b],
                force.force.x,
                force.force.y,
                force.torque,
            ]);
        }
    }
}

impl Simulation for FluidSimulation<'_> {
    fn step_index(&self) -> u64 {
        self.state.world.step
    }
    fn time(&self) -> f64 {
        self.state.world.time
    }
    fn is_complete(&self) -> bool {
        self.state.world.time >= self.duration() * (1.0 - 1e-12)
    }
    /// Steps done, and the steps of the whole run at the last step's length (the fluid's time
    /// step varies: the total is re-estimated as the run goes).
    fn progress(&self) -> (u64, u64) {
        let done = self.state.world.step;
        let dt = if self.last.2 > 0.0 {
            self.last.2
        } else {
            self.scene.dt
        };
        let left = ((self.duration() - self.state.world.time) / dt)
            .ceil()
            .max(0.0);
        (done + left as u64, done)
    }
    fn status_line(&self) -> String {
        let (cycles, contacts, dt) = self.last;
        format!(
            "t = {:.4e} s, dt {dt:.2e} s, {cycles} pressure cycles, {contacts} contacts",
            self.state.world.time
        )
    }
    fn is_root(&self) -> bool {
        self.runner.is_root()
    }
    fn processes(&self) -> usize {
        self.runner.processes()
    }
    fn notes(&self) -> Vec<String> {
        let processes = self.runner.processes();
        let share = self.state.fluid.grid.num_cells() / processes;
        match self.runner.pressure_gathered_cells() {
            Some(cells) if 10 * cells > share => vec![format!(
                "the pressure multigrid's coarsest grid of {cells} cells is relaxed whole by \
                 each process holding it, {:.0} % of a process's {share} cells: on {processes} \
                 processes the blocks are so small that the coarse work, repeated instead of \
                 divided, is a large part of the pressure solve (fewer processes avoid it; see \
                 BENCHMARKS.md)",
                100.0 * cells as f64 / share as f64,
            )],
            _ => Vec::new(),
        }
    }
    fn begin(&mut self) {
        self.runner.begin();
    }
    fn step(&mut self) -> Result<f64, StepFailure> {
        match self.runner.step(&mut self.state) {
            Ok(report) => {
                self.push(&report);
                self.last = (
                    report.fluid.pressure.cycles,
                    report.grains.contacts,
                    report.fluid.dt,
                );
                Ok(report.fluid.times[3] + report.grains.times.total)
            }
            // Every process meets a failure at the same step: the forces, norms and time
            // step are the whole grid's and the grains are stepped alike everywhere.
            Err(e) => Err(StepFailure {
                message: e.to_string(),
                step: self.state.world.step + 1,
                time: self.state.world.time,
                collective: true,
                show_state: false,
            }),
        }
    }
    fn sync(&mut self) {
        self.runner.sync(&mut self.state);
    }
    fn write_frame(&mut self, dir: &Path, pvd: &mut PvdCollection) -> Result<(), RunError> {
        let (world, step) = (&self.state.world, self.state.world.step);
        pvd.truncate_after(world.time - 1e-9 * world.time.max(1e-300));
        let fluid = fluid_image(&self.state, &self.params, &self.immersed);
        let file = format!("frames/fluid_{step:08}.vti");
        write_vti(&dir.join(&file), &fluid).map_err(io_err)?;
        pvd.push(world.time, 0, file);
        let parts = [
            ("bodies", bodies_grid(world)),
            ("contacts", contacts_grid(world, false)),
        ];
        write_vtu_parts(dir, pvd, step, world.time, 1, &parts)?;
        pvd.write(&dir.join("result.pvd")).map_err(io_err)
    }
    fn scene_hash(&self) -> u64 {
        self.scene_hash
    }
    fn checkpoint(&self) -> Result<Vec<u8>, RunError> {
        checkpoint_bytes(self.scene_hash, &self.state)
    }
    fn tables(&self) -> Vec<(&'static str, &SeriesTable)> {
        vec![
            ("series.csv", &self.series),
            ("particles.csv", &self.particles),
        ]
    }
    fn tables_mut(&mut self) -> Vec<(&'static str, &mut SeriesTable)> {
        vec![
            ("series.csv", &mut self.series),
            ("particles.csv", &mut self.particles),
        ]
    }
    fn rank_summaries(&mut self, wall: f64) -> Vec<RankSummary> {
        self.runner.rank_summaries(wall)
    }
    fn arrays(&self) -> Vec<xper_run::state::ArrayInfo> {
        state::arrays()
    }
    fn group_names(&self) -> Vec<String> {
        self.scene.groups.clone()
    }
    fn array(&self, name: &str) -> Option<xper_run::state::StateArray> {
        state::array(&self.state, name)
    }
    fn view(&self, name: &str) -> Option<xper_run::state::StateView> {
        // The fluid's fields are computed from the grid (copies); the grains are read in place.
        match self.runner.processes() {
            1 => crate::rigid::state::view(&self.state.world, name),
            _ => None,
        }
    }
    fn set_array(&mut self, name: &str, shape: &[usize], values: &[f64]) -> Result<(), String> {
        if self.runner.processes() > 1 {
            return Err("arrays are set only in a run on one process".into());
        }
        crate::rigid::state::set_array(&mut self.state.world, name, shape, values)
    }
    fn compare_serial(&mut self, stepping: f64) -> Result<Option<SerialComparison>, RunError> {
        let Some(start) = self.compare_from.take() else {
            return Ok(None);
        };
        let processes = self.runner.processes();
        stepping::compare_serial(&self.params, start, &self.state, stepping, processes).map(Some)
    }
    fn write_summary(&self, dir: &Path, facts: &RunFacts) -> Result<serde_json::Value, RunError> {
        let mut summary = outputs::summary(
            &self.series,
            &self.scene,
            &self.state,
            self.immersed.len(),
            facts.status,
            facts.message.clone(),
            facts.scene_file,
        );
        summary.processes = self.runner.processes();
        summary.ranks = facts.ranks.clone();
        summary.serial_comparison = facts.comparison.clone();
        summary.pressure_gathered_cells = self.runner.pressure_gathered_cells();
        write_json_atomic(&dir.join("summary.json"), &summary).map_err(io_err)?;
        outputs::write_plots(&self.series, &self.particles, dir, &self.scene.name)?;
        serde_json::to_value(&summary).map_err(|e| RunError::Runtime(e.to_string()))
    }
    fn closing_line(&self, facts: &RunFacts, dir: &Path) -> String {
        format!(
            "{}: {} steps to t = {:.4e} s in {:.2} s on {} process(es), outputs in {}",
            facts.status,
            self.state.world.step,
            self.state.world.time,
            facts.wall,
            self.runner.processes(),
            dir.display()
        )
    }
}

/// Whether a restored state has the grid, the array sizes and the bodies of the scene's own
/// (`fresh`): a checkpoint that passed its checksum but disagrees is refused, not indexed.
fn same_layout(restored: &CoupledState, fresh: &CoupledState) -> Result<(), String> {
    let (r, f) = (&restored.fluid, &fresh.fluid);
    let sizes = |s: &xper_fluid::FluidState| {
        let mut v: Vec<usize> = s.velocity.iter().map(Vec::len).collect();
        v.extend([s.pressure.len(), s.increment.len()]);
        v
    };
    if r.grid != f.grid || sizes(r) != sizes(f) {
        return Err(format!(
            "the checkpoint holds a fluid grid of {} x {} cells of {} m (arrays {:?}), the scene \
             {} x {} of {} m (arrays {:?})",
            r.grid.nx,
            r.grid.ny,
            r.grid.h,
            sizes(r),
            f.grid.nx,
            f.grid.ny,
            f.grid.h,
            sizes(f)
        ));
    }
    let (rb, fb) = (restored.world.bodies.len(), fresh.world.bodies.len());
    if rb != fb {
        return Err(format!("the checkpoint holds {rb} bodies, the scene {fb}"));
    }
    Ok(())
}
