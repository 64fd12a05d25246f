//! Dynamic fracture of a meshed specimen (every element its own body, a frictional cohesive
//! zone between every pair of neighbouring elements): the [`Simulation`] of a scene with a
//! `[mesh]` section, on this process ([`stepping::SerialFracture`]) or over a communicator
//! ([`stepping::DistributedFractureRun`]).

pub mod build;
pub mod checkpoint;
pub mod crack;
pub mod frames;
pub mod outputs;
pub mod state;
pub mod stepping;

use crate::comparison::SerialComparison;
use crate::outputs::{io_err, write_vtu_parts};
use crate::ranks::RankSummary;
use crate::simulation::RunOptions;
use crate::simulation::{RunFacts, Simulation, StepFailure};
use crate::RunError;
use checkpoint::Checkpoint;
use frames::{elements_grid, interfaces_grid};
use outputs::{
    series_columns, series_row, summary, write_crack_pattern, write_force_displacement,
    write_series_plot, write_stress_strain,
};
use std::path::Path;
use stepping::{DistributedFractureRun, FractureRun, SerialFracture};
use xper_domain::Communicator;
use xper_fracture::{FractureModel, FractureStepError};
use xper_io::{write_json_atomic, PvdCollection, SeriesTable};
use xper_scene::FractureScene;

/// A fracture scene being run.
pub struct FractureSimulation<'c> {
    runner: Box<dyn FractureRun + 'c>,
    /// The whole model on the writing process: its step, time and energy after every step,
    /// its full state after a sync.
    model: FractureModel,
    scene: FractureScene,
    scene_hash: u64,
    series: SeriesTable,
    compare_from: Option<FractureModel>,
    /// Broken points and sweeps of the last step, for the progress bar.
    last: (usize, u32),
}

impl<'c> FractureSimulation<'c> {
    /// The run of `scene` (whose files hash to `scene_hash`) at time 0 or, with
    /// `opts.resume`, from the checkpoint in `opts.out`; over `comm` when given.
    pub fn new(
        scene: FractureScene,
        scene_hash: u64,
        opts: &RunOptions,
        comm: Option<&'c dyn Communicator>,
    ) -> Result<Self, RunError> {
        let (mut model, _) = build::build_model(&scene, &opts.scene)?;
        if opts.resume {
            Checkpoint::read(&opts.out)?.restore(&mut model, &opts.out.join("checkpoint.bin"))?;
        }
        let names: Vec<String> = model.spec.loads.iter().map(|l| l.name.clone()).collect();
        let columns = series_columns(&names, model.spec.periodic.is_some());
        let columns: Vec<&str> = columns.iter().map(String::as_str).collect();
        let runner: Box<dyn FractureRun + 'c> = match comm {
            Some(comm) => Box::new(DistributedFractureRun::new(comm, &model)),
            None => Box::<SerialFracture>::default(),
        };
        let compare_from =
            (opts.compare_serial && runner.is_root() && comm.is_some()).then(|| model.clone());
        Ok(FractureSimulation {
            runner,
            model,
            scene,
            scene_hash,
            series: SeriesTable::new(&columns),
            compare_from,
            last: (0, 0),
        })
    }

    /// The whole model (on the writing process; its full state after a sync).
    pub fn model(&self) -> &FractureModel {
        &self.model
    }
}

impl Simulation for FractureSimulation<'_> {
    fn step_index(&self) -> u64 {
        self.model.step
    }
    fn time(&self) -> f64 {
        self.model.time
    }
    fn is_complete(&self) -> bool {
        self.model.step >= self.scene.steps
    }
    fn progress(&self) -> (u64, u64) {
        (self.scene.steps, self.model.step)
    }
    fn status_line(&self) -> String {
        let (broken, sweeps) = self.last;
        format!(
            "t = {:.4e} s, {broken} broken points, {sweeps} sweeps",
            self.model.time
        )
    }
    fn is_root(&self) -> bool {
        self.runner.is_root()
    }
    fn processes(&self) -> usize {
        self.runner.processes()
    }
    fn step(&mut self) -> Result<f64, StepFailure> {
        match self.runner.step(&mut self.model) {
            Ok(report) => {
                self.series.push(series_row(&report));
                self.last = (report.broken_points, report.iterations);
                Ok(report.wall_time)
            }
            // Every process meets it together. The diverged state is shown, not checkpointed.
            Err(e @ FractureStepError::Diverging(_)) => Err(StepFailure {
                message: e.to_string(),
                step: self.model.step,
                time: self.model.step as f64 * self.model.spec.dt,
                collective: true,
                show_state: true,
            }),
            Err(e) => Err(StepFailure {
                message: e.to_string(),
                step: self.model.step + 1,
                time: (self.model.step + 1) as f64 * self.model.spec.dt,
                collective: false,
                show_state: false,
            }),
        }
    }
    fn sync(&mut self) {
        self.runner.sync(&mut self.model);
    }
    fn write_frame(&mut self, dir: &Path, pvd: &mut PvdCollection) -> Result<(), RunError> {
        let m = &self.model;
        pvd.truncate_after(m.time - 0.5 * m.spec.dt);
        let parts = [
            ("elements", elements_grid(m)),
            ("interfaces", interfaces_grid(m)),
        ];
        write_vtu_parts(dir, pvd, m.step, m.time, 0, &parts)?;
        pvd.write(&dir.join("result.pvd")).map_err(io_err)
    }
    fn scene_hash(&self) -> u64 {
        self.scene_hash
    }
    fn checkpoint(&self) -> Result<Vec<u8>, RunError> {
        bincode::serialize(&Checkpoint::of(&self.model, self.scene_hash))
            .map_err(|e| RunError::Runtime(e.to_string()))
    }
    fn tables(&self) -> Vec<(&'static str, &SeriesTable)> {
        vec![("series.csv", &self.series)]
    }
    fn tables_mut(&mut self) -> Vec<(&'static str, &mut SeriesTable)> {
        vec![("series.csv", &mut self.series)]
    }
    fn rank_summaries(&mut self, wall: f64) -> Vec<RankSummary> {
        self.runner.rank_summaries(wall)
    }
    fn arrays(&self) -> Vec<xper_run::state::ArrayInfo> {
        state::ARRAYS.to_vec()
    }
    fn array(&self, name: &str) -> Option<xper_run::state::StateArray> {
        state::array(&self.model, name)
    }
    fn compare_serial(&mut self, stepping: f64) -> Result<Option<SerialComparison>, RunError> {
        let Some(start) = self.compare_from.take() else {
            return Ok(None);
        };
        let processes = self.runner.processes();
        stepping::compare_serial(start, &self.model, stepping, processes).map(Some)
    }
    fn write_summary(&self, dir: &Path, facts: &RunFacts) -> Result<serde_json::Value, RunError> {
        let mut s = summary(
            &self.model,
            &self.series,
            (&self.scene.name, facts.scene_file),
            facts.status,
            facts.message.clone(),
        );
        s.processes = self.runner.processes();
        s.ranks = facts.ranks.clone();
        s.serial_comparison = facts.comparison.clone();
        let (m, name) = (&self.model, &self.scene.name);
        write_json_atomic(&dir.join("summary.json"), &s).map_err(io_err)?;
        write_series_plot(&self.series, &dir.join("series.png"), name).map_err(io_err)?;
        if !m.spec.loads.is_empty() {
            let fd = dir.join("force_displacement.png");
            write_force_displacement(m, &self.series, &fd, name).map_err(io_err)?;
        }
        if m.spec.periodic.is_some() {
            let ss = dir.join("stress_strain.png");
            write_stress_strain(&self.series, &ss, name).map_err(io_err)?;
        }
        write_crack_pattern(m, &dir.join("crack_pattern.png"), name).map_err(io_err)?;
        serde_json::to_value(&s).map_err(|e| RunError::Runtime(e.to_string()))
    }
    fn closing_line(&self, facts: &RunFacts, dir: &Path) -> String {
        format!(
            "{}: {} of {} steps in {:.2} s on {} process(es), {} broken points, outputs in {}",
            facts.status,
            self.model.step,
            self.scene.steps,
            facts.wall,
            self.runner.processes(),
            self.model.broken_points(),
            dir.display()
        )
    }
}
