//! Rigid bodies in frictional contact (NSCD, Moreau-Jean): the [`Simulation`] of a scene
//! without `[mesh]` or `[fluid]`, stepped on this process ([`stepping::SerialRun`]) or over a
//! communicator ([`stepping::DistributedRun`], NSCDD).
//!
//! One source, two builds: `xper-rigid` (2D scenes) and `xper-rigid3d` (feature `dim3`,
//! `[scene] dimension = 3`); what differs is the scene's conversion to a world
//! (`bodies2d.rs`/`bodies3d.rs` of [`build`]) and the frames (`frames2d.rs`/`frames3d.rs`). `xper-simulation`
//! chooses between them by the scene's dimension.

pub mod bench;
pub mod build;
pub mod frames;
pub mod micro;
pub mod outputs;
pub mod state;
pub mod stepping;

use xper_run::{checkpoint, comparison, outputs as run_outputs, ranks, simulation, RunError};

use build::{release_body_descriptions, world_from_scene, RigidScene};
use checkpoint::{checkpoint_bytes, read_checkpoint};
use comparison::SerialComparison;
use frames::frame_parts;
use outputs::{series_row, solver_name, SeriesFigures, Summary, SERIES_COLUMNS};
use ranks::RankSummary;
use run_outputs::{create_output_dir, io_err, write_vtu_parts};
use simulation::RunOptions;
use simulation::{RunFacts, Simulation, StepFailure};
use std::path::Path;
use stepping::{check_distributable, DistributedRun, RigidRun, SerialRun};
use xper_io::{write_json_atomic, PvdCollection, SeriesTable};
use xper_nscd::World;
use xper_parallel::Communicator;

/// A rigid scene being run.
pub struct RigidSimulation<'c> {
    run: Box<dyn RigidRun + 'c>,
    /// The whole world gathered on the writing process of a distributed run at the last sync.
    gathered: Option<World>,
    root: bool,
    processes: usize,
    /// The scene, its body descriptions released once the world is built.
    scene: RigidScene,
    scene_hash: u64,
    series: SeriesTable,
    /// The start of a distributed run kept for `--compare-serial`.
    compare_from: Option<World>,
    /// Time, contacts and sweeps of the last step, for the progress bar.
    last: (f64, usize, u32),
    /// `micro.csv` and the volume of its measures, when `[output] micro` asks for them.
    micro: Option<(SeriesTable, xper_nscd::micro::VolumeSource)>,
    /// The scene file, for messages.
    scene_file: std::path::PathBuf,
}

impl<'c> RigidSimulation<'c> {
    /// The run of `scene` (whose files hash to `scene_hash`) at time 0 or, with
    /// `opts.resume`, from the checkpoint in `opts.out`; over `comm` when given.
    pub fn new(
        mut scene: RigidScene,
        scene_hash: u64,
        opts: &RunOptions,
        comm: Option<&'c dyn Communicator>,
    ) -> Result<Self, RunError> {
        let dumps = scene.output.dump_problems.clone();
        dumps_supported(&scene, &opts.scene)?;
        check_distributable(&scene, &opts.scene, comm.is_some())?;
        let root = comm.is_none_or(|c| c.rank() == 0);
        if !dumps.is_empty() && root {
            create_output_dir(&opts.out.join("problems"))?;
        }
        let world = if opts.resume {
            let bytes: Vec<u8> = read_checkpoint(&opts.out, "an xper checkpoint")?;
            let mut world = World::from_bytes(&bytes).map_err(|e| {
                RunError::BadInput(format!(
                    "{}: {e}",
                    opts.out.join("checkpoint.bin").display()
                ))
            })?;
            build::take_solver_limits(&mut world, &scene);
            world
        } else {
            world_from_scene(&scene)
        };
        release_body_descriptions(&mut scene);
        let compare_from = (opts.compare_serial && root && comm.is_some()).then(|| world.clone());
        let (run, processes): (Box<dyn RigidRun + 'c>, usize) = match comm {
            Some(comm) => (
                Box::new(DistributedRun::new(
                    comm,
                    world,
                    scene.output.checkpoint_every,
                )),
                comm.size(),
            ),
            None => (Box::new(SerialRun::new(world, dumps, opts.out.clone())), 1),
        };
        let micro = (scene.output.micro).map(|v| (micro::table(), micro::volume_source(v)));
        Ok(RigidSimulation {
            run,
            gathered: None,
            root,
            processes,
            scene,
            scene_hash,
            series: SeriesTable::new(&SERIES_COLUMNS),
            compare_from,
            last: (0.0, 0, 0),
            micro,
            scene_file: opts.scene.clone(),
        })
    }

    /// The whole world, on the writing process (after a sync in a distributed run).
    pub fn world(&self) -> Option<&World> {
        self.run.whole().or(self.gathered.as_ref())
    }

    fn whole(&self) -> Result<&World, RunError> {
        self.world()
            .ok_or_else(|| RunError::Runtime("the whole world is not held by this process".into()))
    }
}

impl Simulation for RigidSimulation<'_> {
    fn step_index(&self) -> u64 {
        self.run.step_index()
    }
    fn time(&self) -> f64 {
        self.run.time()
    }
    fn is_complete(&self) -> bool {
        self.run.step_index() >= self.scene.steps
    }
    fn progress(&self) -> (u64, u64) {
        (self.scene.steps, self.run.step_index())
    }
    fn status_line(&self) -> String {
        let (time, contacts, sweeps) = self.last;
        format!("t = {time:.4e} s, {contacts} contacts, {sweeps} sweeps")
    }
    fn is_root(&self) -> bool {
        self.root
    }
    fn processes(&self) -> usize {
        self.processes
    }
    fn begin(&mut self) {
        self.run.begin();
    }
    fn step(&mut self) -> Result<f64, StepFailure> {
        let failure = |message: String, run: &dyn RigidRun| StepFailure {
            message,
            step: run.step_index() + 1,
            time: run.time(),
            collective: false,
            show_state: false,
        };
        match self.run.step() {
            Ok(Ok(report)) => {
                self.series.push(series_row(&report));
                self.last = (report.time, report.contacts, report.iterations);
                Ok(report.times.total)
            }
            Ok(Err(e)) => Err(failure(e.to_string(), self.run.as_ref())),
            Err(e) => Err(failure(e.to_string(), self.run.as_ref())),
        }
    }
    fn sync(&mut self) {
        if let Some(world) = self.run.gather() {
            self.gathered = Some(world);
        }
    }
    fn write_frame(&mut self, dir: &Path, pvd: &mut PvdCollection) -> Result<(), RunError> {
        if let Some((_, source)) = self.micro {
            let world = self.whole()?;
            let row = micro::row(world, &micro::measures(world, source, &self.scene_file)?);
            if let Some((table, _)) = &mut self.micro {
                table.push(row);
            }
        }
        let world = self.whole()?;
        let parts = frame_parts(world);
        pvd.truncate_after(world.time - 0.5 * world.params.dt);
        write_vtu_parts(dir, pvd, world.step, world.time, 0, &parts)?;
        pvd.write(&dir.join("result.pvd")).map_err(io_err)
    }
    fn scene_hash(&self) -> u64 {
        self.scene_hash
    }
    fn checkpoint(&self) -> Result<Vec<u8>, RunError> {
        checkpoint_bytes(self.scene_hash, &self.whole()?.to_bytes())
    }
    fn tables(&self) -> Vec<(&'static str, &SeriesTable)> {
        let mut tables = vec![("series.csv", &self.series)];
        tables.extend(self.micro.as_ref().map(|(t, _)| ("micro.csv", t)));
        tables
    }
    fn tables_mut(&mut self) -> Vec<(&'static str, &mut SeriesTable)> {
        let mut tables = vec![("series.csv", &mut self.series)];
        tables.extend(self.micro.as_mut().map(|(t, _)| ("micro.csv", t)));
        tables
    }
    fn rank_summaries(&mut self, wall: f64) -> Vec<RankSummary> {
        self.run.rank_summaries(wall)
    }
    fn arrays(&self) -> Vec<xper_run::state::ArrayInfo> {
        self.world().map_or(state::ARRAYS.to_vec(), state::arrays)
    }
    fn group_names(&self) -> Vec<String> {
        self.scene.groups.clone()
    }
    fn array(&self, name: &str) -> Option<xper_run::state::StateArray> {
        state::array(self.world()?, name)
    }
    fn view(&self, name: &str) -> Option<xper_run::state::StateView> {
        // The world stepped on one process; a gathered copy is replaced at every output.
        state::view(self.run.whole()?, name)
    }
    fn set_array(&mut self, name: &str, shape: &[usize], values: &[f64]) -> Result<(), String> {
        let world = (self.run.whole_mut()).ok_or("arrays are set only in a run on one process")?;
        state::set_array(world, name, shape, values)
    }
    fn add_bodies(&mut self, text: &str) -> Result<Vec<usize>, String> {
        let world =
            (self.run.whole_mut()).ok_or("bodies are added only in a run on one process")?;
        let file = Path::new("added bodies");
        build::add_bodies(world, &self.scene.groups, text, file)
    }
    fn compare_serial(&mut self, stepping: f64) -> Result<Option<SerialComparison>, RunError> {
        let Some(start) = self.compare_from.take() else {
            return Ok(None);
        };
        let end = self.whole()?;
        stepping::compare_serial(start, end, stepping, self.processes).map(Some)
    }
    fn write_summary(&self, dir: &Path, facts: &RunFacts) -> Result<serde_json::Value, RunError> {
        let summary = Summary {
            scene: self.scene.name.clone(),
            scene_file: facts.scene_file.display().to_string(),
            solver: solver_name(self.scene.solver.kind),
            status: facts.status,
            message: facts.message.clone(),
            bodies: self.run.body_count(),
            dt: self.scene.dt,
            first_step: facts.first_step,
            steps: self.run.step_index(),
            simulated_time: self.run.time(),
            figures: SeriesFigures::of(&self.series),
            peak_memory_bytes: xper_io::peak_memory_bytes(),
            xper_version: env!("CARGO_PKG_VERSION"),
            processes: facts.ranks.len().max(1),
            ranks: facts.ranks.clone(),
            serial_comparison: facts.comparison.clone(),
        };
        write_json_atomic(&dir.join("summary.json"), &summary).map_err(io_err)?;
        outputs::write_plot(&self.series, &dir.join("series.png"), &self.scene.name)?;
        if let (Some((table, _)), Some(world)) = (&self.micro, self.world()) {
            let start = world.events.list.last().map_or(0.0, |e| e.time);
            micro::write_plot(table, start, &dir.join("micro.png"), &self.scene.name)?;
        }
        serde_json::to_value(&summary).map_err(|e| RunError::Runtime(e.to_string()))
    }
    fn closing_line(&self, facts: &RunFacts, dir: &Path) -> String {
        format!(
            "{}: {} of {} steps in {:.2} s, outputs in {}",
            facts.status,
            self.run.step_index(),
            self.scene.steps,
            facts.wall,
            dir.display()
        )
    }
}

/// `[output] dump_problems` needs the `hdf5` feature: without it the scene is refused (by
/// `xper check` too), never accepted and then failed at the first dump.
pub fn dumps_supported(scene: &RigidScene, path: &Path) -> Result<(), RunError> {
    if !scene.output.dump_problems.is_empty() && !cfg!(feature = "hdf5") {
        return Err(RunError::BadInput(format!(
            "{}: [output] dump_problems: built without HDF5 support: rebuild with --features hdf5",
            path.display()
        )));
    }
    Ok(())
}
