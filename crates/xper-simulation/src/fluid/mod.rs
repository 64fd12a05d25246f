//! `xper run` on a scene with `[fluid]`: grains in a viscous fluid. Writes `result.pvd` with
//! one fluid frame (`.vti`: velocity, pressure, vorticity, solid fraction) and the bodies and
//! contacts (`.vtu`) per output step, `series.csv` (one row per step), `particles.csv` (each
//! immersed disk at each step: position, velocity, hydrodynamic force), `series.png`,
//! `particles.png`, `summary.json` and checkpoints (`--resume`). Under `mpirun` the grid is cut
//! into blocks of rows, one per process ([`crate::run_fluid_distributed`]); rank 0 writes.

use crate::frames::{bodies_grid, contacts_grid};
use crate::run::{create_output_dir, progress_bar, read_checkpoint, run_status, RunOptions};
use crate::run_distributed::RankSummary;
use crate::run_fluid_distributed::{compare_serial, DistributedFluidRun, FluidRun, SerialFluid};
use crate::serial_comparison::SerialComparison;
use crate::world_from_scene::world_from_scene;
use crate::CliError;
use serde::Serialize;
use std::path::Path;
use std::time::Instant;
use xper_fluid::immersed::ImmersedForcing;
use xper_fluid::{
    CoupledReport, CoupledState, FluidBoundary, FluidParams, FluidState, ImmersedDisk,
    InflowProfile, MacGrid, SideCondition, SolidIndicator,
};
use xper_io::{
    plot_panels, write_atomic, write_json_atomic, write_vti, write_vtu, Curve, ImageGrid, Panel,
    PvdCollection, SeriesTable,
};
use xper_math::{Real, Vector};
use xper_scene::{FluidDesc, FluidSideDesc, Scene};

/// Columns of `series.csv` for a fluid scene.
pub const FLUID_SERIES_COLUMNS: [&str; 16] = [
    "step",
    "time",
    "dt",
    "grain_kinetic_energy",
    "fluid_kinetic_energy",
    "max_speed",
    "pressure_cycles",
    "pressure_residual",
    "divergence",
    "contacts",
    "active_contacts",
    "iterations",
    "converged",
    "wall_time",
    "fluid_time",
    "grains_time",
];

/// Columns of `particles.csv`.
pub const PARTICLE_COLUMNS: [&str; 12] = [
    "step",
    "time",
    "body",
    "x",
    "y",
    "angle",
    "vx",
    "vy",
    "angular_velocity",
    "fx",
    "fy",
    "torque",
];

/// The fluid parameters of a scene.
pub fn fluid_params(desc: &FluidDesc, dt: Real) -> FluidParams {
    let side = |s: FluidSideDesc| match s {
        FluidSideDesc::NoSlip => SideCondition::NoSlip,
        FluidSideDesc::MovingWall { velocity } => SideCondition::MovingWall { velocity },
        FluidSideDesc::Periodic => SideCondition::Periodic,
        FluidSideDesc::Outflow => SideCondition::Outflow,
        FluidSideDesc::Inflow { parabolic, speed } => SideCondition::Inflow {
            profile: if parabolic {
                InflowProfile::Parabolic { max_speed: speed }
            } else {
                InflowProfile::Uniform { speed }
            },
        },
    };
    let [left, right, bottom, top] = desc.boundary.map(side);
    FluidParams {
        body_force: Vector::new(desc.body_force[0], desc.body_force[1]),
        cfl: desc.cfl,
        viscous_safety: desc.viscous_safety,
        dt_max: dt,
        upwinding: desc.upwinding,
        indicator: if desc.sharp_indicator {
            SolidIndicator::Sharp
        } else {
            SolidIndicator::Smoothed
        },
        pressure_tolerance: desc.pressure_tolerance,
        pressure_max_cycles: desc.pressure_max_cycles,
        ..FluidParams::new(
            desc.density,
            desc.viscosity,
            FluidBoundary {
                left,
                right,
                bottom,
                top,
            },
        )
    }
}

/// The grid of a scene's fluid.
pub fn fluid_grid(desc: &FluidDesc) -> MacGrid {
    let h = desc.cell_size;
    let n = |d: usize| ((desc.upper[d] - desc.lower[d]) / h).round() as usize;
    MacGrid {
        nx: n(0),
        ny: n(1),
        h,
        origin: Vector::new(desc.lower[0], desc.lower[1]),
    }
}

/// The state of a fluid scene at time 0.
pub fn coupled_state(scene: &Scene, desc: &FluidDesc, params: &FluidParams) -> CoupledState {
    CoupledState {
        fluid: FluidState::at_rest(fluid_grid(desc), &params.boundary),
        world: world_from_scene(scene),
    }
}

#[derive(Serialize)]
struct Summary {
    scene: String,
    scene_file: String,
    status: &'static str,
    message: String,
    cells: [usize; 2],
    cell_size: f64,
    immersed_disks: usize,
    bodies: usize,
    steps: u64,
    simulated_time: f64,
    wall_time_s: f64,
    average_dt: f64,
    average_pressure_cycles: f64,
    max_pressure_cycles: f64,
    fluid_cells_per_second: f64,
    non_converged_contact_steps: usize,
    peak_memory_bytes: Option<u64>,
    xper_version: &'static str,
    processes: usize,
    ranks: Vec<RankSummary>,
    /// Cells of the pressure solve's coarsest grid that rank 0, as each process holding it,
    /// relaxes whole (runs on several processes).
    #[serde(skip_serializing_if = "Option::is_none")]
    pressure_gathered_cells: Option<usize>,
    #[serde(skip_serializing_if = "Option::is_none")]
    serial_comparison: Option<SerialComparison>,
}

struct Outputs<'a> {
    dir: &'a Path,
    series: SeriesTable,
    particles: SeriesTable,
    pvd: PvdCollection,
    scene_hash: u64,
}

fn io_err(e: std::io::Error) -> CliError {
    CliError::Runtime(e.to_string())
}

impl Outputs<'_> {
    fn write_frame(
        &mut self,
        state: &CoupledState,
        params: &FluidParams,
        immersed: &[usize],
    ) -> Result<(), CliError> {
        let (world, step) = (&state.world, state.world.step);
        self.pvd
            .truncate_after(world.time - 1e-9 * world.time.max(1e-300));
        let fluid = fluid_image(state, params, immersed);
        let file = format!("frames/fluid_{step:08}.vti");
        write_vti(&self.dir.join(&file), &fluid).map_err(io_err)?;
        self.pvd.push(world.time, 0, file);
        for (part, (name, grid)) in [
            ("bodies", bodies_grid(world)),
            ("contacts", contacts_grid(world, false)),
        ]
        .iter()
        .enumerate()
        {
            let file = format!("frames/{name}_{step:08}.vtu");
            write_vtu(&self.dir.join(&file), grid).map_err(io_err)?;
            self.pvd.push(world.time, part as u32 + 1, file);
        }
        self.pvd.write(&self.dir.join("result.pvd")).map_err(io_err)
    }

    fn write_checkpoint(&self, state: &CoupledState) -> Result<(), CliError> {
        let bytes = crate::run::checkpoint_bytes(self.scene_hash, state)?;
        write_atomic(&self.dir.join("checkpoint.bin"), &bytes).map_err(io_err)?;
        self.write_tables()
    }

    fn write_tables(&self) -> Result<(), CliError> {
        self.series
            .write_csv(&self.dir.join("series.csv"))
            .map_err(io_err)?;
        self.particles
            .write_csv(&self.dir.join("particles.csv"))
            .map_err(io_err)
    }

    fn push(&mut self, state: &CoupledState, immersed: &[usize], r: &CoupledReport) {
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
        let bodies = &state.world.bodies;
        for (&b, force) in immersed.iter().zip(&f.forces) {
            let (x, v) = (bodies.position[b], bodies.velocity[b]);
            self.particles.push(vec![
                g.step as f64,
                f.time,
                b as f64,
                x.x,
                x.y,
                bodies.angle[b],
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

/// The solid fraction of every face for the immersed disks where they are now.
fn solid_fraction(
    state: &CoupledState,
    params: &FluidParams,
    immersed: &[usize],
) -> ImmersedForcing {
    let bodies = &state.world.bodies;
    let disks: Vec<ImmersedDisk> = immersed
        .iter()
        .filter_map(|&b| match bodies.shape[b] {
            xper_bodies::Shape::Disk { radius } => Some(ImmersedDisk {
                centre: bodies.position[b],
                radius,
                velocity: bodies.velocity[b],
                angular_velocity: bodies.angular_velocity[b],
            }),
            _ => None,
        })
        .collect();
    let grid = state.fluid.grid;
    let mut forcing = ImmersedForcing::default();
    forcing.mark(&grid, &params.boundary, &disks, params.indicator);
    forcing
}

/// The fluid on its grid at cell centres: velocity, pressure, vorticity, solid fraction.
fn fluid_image(state: &CoupledState, params: &FluidParams, immersed: &[usize]) -> ImageGrid {
    let fluid = &state.fluid;
    let g = fluid.grid;
    let n = g.num_cells();
    let (mut velocity, mut pressure, mut vorticity, mut solid) = (
        Vec::with_capacity(3 * n),
        Vec::with_capacity(n),
        Vec::with_capacity(n),
        Vec::with_capacity(n),
    );
    let forcing = solid_fraction(state, params, immersed);
    let fraction = [forcing.fraction(&g, 0), forcing.fraction(&g, 1)];
    for j in 0..g.ny {
        for i in 0..g.nx {
            let v = fluid.cell_velocity(i, j);
            velocity.extend([v.x, v.y, 0.0]);
            pressure.push(fluid.cell_pressure(i, j));
            vorticity.push(fluid.cell_vorticity(i, j));
            let k = g.index(i as isize, j as isize);
            solid.push(
                0.25 * (fraction[0][k]
                    + fraction[0][k + 1]
                    + fraction[1][k]
                    + fraction[1][k + g.width()]),
            );
        }
    }
    ImageGrid {
        cells: [g.nx, g.ny],
        origin: [g.origin.x, g.origin.y],
        spacing: g.h,
        cell_data: vec![
            ("velocity".into(), 3, velocity),
            ("pressure".into(), 1, pressure),
            ("vorticity".into(), 1, vorticity),
            ("solid_fraction".into(), 1, solid),
        ],
    }
}

/// Runs a fluid scene (already loaded and validated) to `scene.steps x scene.dt` seconds, on
/// this process or, with `comm` of more than one process, on the blocks of a split grid.
pub fn run(
    opts: &RunOptions,
    scene: &Scene,
    scene_hash: u64,
    quiet: bool,
    comm: Option<&dyn xper_domain::Communicator>,
) -> Result<(), CliError> {
    let desc = scene
        .fluid
        .as_ref()
        .ok_or_else(|| CliError::BadInput("not a fluid scene".into()))?;
    let params = fluid_params(desc, scene.dt);
    let distributed = comm.filter(|c| c.size() > 1);
    let root = distributed.is_none_or(|c| c.rank() == 0);
    if root {
        create_output_dir(&opts.out.join("frames"))?;
    }
    let mut out = Outputs {
        dir: &opts.out,
        series: SeriesTable::new(&FLUID_SERIES_COLUMNS),
        particles: SeriesTable::new(&PARTICLE_COLUMNS),
        pvd: PvdCollection::default(),
        scene_hash,
    };
    let mut state = if opts.resume {
        let state: CoupledState =
            read_checkpoint(&opts.out, scene_hash, "a checkpoint of a fluid scene")?;
        let read = |name: &str| {
            let mut t = SeriesTable::read_csv(&opts.out.join(name))
                .map_err(|e| CliError::BadInput(e.to_string()))?;
            t.truncate_rows_where_first_column_greater_than(state.world.step as f64);
            Ok::<_, CliError>(t)
        };
        out.series = read("series.csv")?;
        out.particles = read("particles.csv")?;
        out.pvd = PvdCollection::read(&opts.out.join("result.pvd"))
            .map_err(|e| CliError::BadInput(e.to_string()))?;
        state
    } else {
        coupled_state(scene, desc, &params)
    };
    let setup =
        |e: xper_fluid::FluidError| CliError::BadInput(format!("{}: {e}", opts.scene.display()));
    let mut runner: Box<dyn FluidRun + '_> = match distributed {
        Some(comm) => Box::new(DistributedFluidRun::new(comm, &params, &state).map_err(setup)?),
        None => Box::new(SerialFluid::new(&params, &state).map_err(setup)?),
    };
    let immersed = runner.immersed().to_vec();
    let gathered = runner.pressure_gathered_cells();
    let share = state.fluid.grid.num_cells() / runner.processes();
    if let Some(cells) = gathered.filter(|&cells| root && !quiet && 10 * cells > share) {
        eprintln!(
            "xper: note: the pressure multigrid's coarsest grid of {cells} cells is relaxed whole \
             by each process holding it, {:.0} % of a process's {share} cells: on {} processes \
             the blocks are so small that the coarse work, repeated instead of divided, is a \
             large part of the pressure solve (fewer processes avoid it; see BENCHMARKS.md)",
            100.0 * cells as f64 / share as f64,
            runner.processes()
        );
    }
    if !opts.resume && root {
        out.write_frame(&state, &params, &immersed)?;
    }
    let compare_from =
        (opts.compare_serial && root && distributed.is_some()).then(|| state.clone());
    let duration = scene.steps as Real * scene.dt;
    let end_reached = |time: Real| time >= duration * (1.0 - 1e-12);
    let bar = progress_bar(
        quiet || !root,
        scene.steps,
        (state.world.time / scene.dt) as u64,
    );
    runner.begin();
    let started = Instant::now();
    let mut stepping = 0.0;
    let mut failure = None;
    while !end_reached(state.world.time) && opts.stop_at_step.is_none_or(|s| state.world.step < s) {
        match runner.step(&mut state) {
            Ok(report) => {
                stepping += report.fluid.times[3] + report.grains.times.total;
                out.push(&state, &immersed, &report);
                let step = state.world.step;
                let frame = step % scene.output.frame_every == 0 || end_reached(state.world.time);
                let checkpoint = step % scene.output.checkpoint_every == 0;
                if frame || checkpoint {
                    runner.sync(&mut state);
                }
                if frame && root {
                    out.write_frame(&state, &params, &immersed)?;
                }
                if checkpoint && root {
                    out.write_checkpoint(&state)?;
                }
                if step % 10 == 0 {
                    bar.set_position((state.world.time / scene.dt) as u64);
                    bar.set_message(format!(
                        "t = {:.4e} s, dt {:.2e} s, {} pressure cycles, {} contacts",
                        state.world.time,
                        report.fluid.dt,
                        report.fluid.pressure.cycles,
                        report.grains.contacts
                    ));
                }
            }
            Err(e) => {
                // Every process meets a failure at the same step: the forces, norms and time
                // step are the whole grid's and the grains are stepped alike everywhere.
                failure = Some(format!(
                    "step {} (t = {:.6e} s): {e}; the last checkpoint is kept in {}",
                    state.world.step + 1,
                    state.world.time,
                    opts.out.join("checkpoint.bin").display()
                ));
                break;
            }
        }
    }
    bar.finish_and_clear();
    let wall = started.elapsed().as_secs_f64();
    if failure.is_none() {
        runner.sync(&mut state);
    }
    let ranks = runner.rank_summaries(wall);
    let processes = runner.processes();
    let comparison = match compare_from.filter(|_| failure.is_none()) {
        Some(start) => Some(compare_serial(&params, start, &state, stepping, processes)?),
        None => None,
    };
    if !root {
        return match failure {
            Some(message) => Err(CliError::Runtime(message)),
            None => Ok(()),
        };
    }
    if failure.is_none() {
        out.write_checkpoint(&state)?;
    } else {
        out.write_tables()?;
    }
    let status = run_status(failure.is_some(), end_reached(state.world.time));
    let mut summary = summary(
        &out,
        scene,
        &state,
        immersed.len(),
        status,
        failure.clone().unwrap_or_default(),
        &opts.scene,
    );
    (summary.processes, summary.ranks, summary.serial_comparison) = (processes, ranks, comparison);
    summary.pressure_gathered_cells = gathered;
    write_json_atomic(&out.dir.join("summary.json"), &summary).map_err(io_err)?;
    write_plots(&out, &opts.out, &scene.name)?;
    if !quiet {
        eprintln!(
            "{status}: {} steps to t = {:.4e} s in {wall:.2} s on {processes} process(es), outputs in {}",
            state.world.step,
            state.world.time,
            opts.out.display()
        );
    }
    match failure {
        Some(message) => Err(CliError::Runtime(message)),
        None => Ok(()),
    }
}

fn summary(
    out: &Outputs,
    scene: &Scene,
    state: &CoupledState,
    immersed_disks: usize,
    status: &'static str,
    message: String,
    file: &Path,
) -> Summary {
    let col = |name: &str| out.series.column(name).unwrap_or_default();
    let (cycles, fluid_time) = (
        col("pressure_cycles"),
        col("fluid_time").iter().sum::<f64>(),
    );
    let grid = state.fluid.grid;
    Summary {
        scene: scene.name.clone(),
        scene_file: file.display().to_string(),
        status,
        message,
        cells: [grid.nx, grid.ny],
        cell_size: grid.h,
        immersed_disks,
        bodies: state.world.bodies.len(),
        steps: state.world.step,
        simulated_time: state.world.time,
        wall_time_s: col("wall_time").iter().sum(),
        average_dt: crate::bench::mean(&col("dt")),
        average_pressure_cycles: crate::bench::mean(&cycles),
        max_pressure_cycles: cycles.iter().copied().fold(0.0, f64::max),
        fluid_cells_per_second: grid.num_cells() as f64 * cycles.len() as f64
            / fluid_time.max(1e-300),
        non_converged_contact_steps: col("converged").iter().filter(|&&c| c == 0.0).count(),
        peak_memory_bytes: xper_io::peak_memory_bytes(),
        xper_version: env!("CARGO_PKG_VERSION"),
        processes: 1,
        ranks: Vec::new(),
        pressure_gathered_cells: None,
        serial_comparison: None,
    }
}

/// `series.png` (energies, pressure solve, divergence, time step) and `particles.png`
/// (positions and velocities of up to eight immersed disks against time).
fn write_plots(out: &Outputs, dir: &Path, title: &str) -> Result<(), CliError> {
    let time = out.series.column("time").unwrap_or_default();
    let curve = |name: &str, label: &str| Curve {
        label: label.into(),
        points: time
            .iter()
            .copied()
            .zip(out.series.column(name).unwrap_or_default())
            .collect(),
    };
    let panel = |title: &str, y: &str, curves: Vec<Curve>, log_y: bool| Panel {
        title: title.into(),
        x_label: "time (s)".into(),
        y_label: y.into(),
        curves,
        log_y,
    };
    let panels = [
        panel(
            "Kinetic energy",
            "J/m",
            vec![
                curve("fluid_kinetic_energy", "fluid"),
                curve("grain_kinetic_energy", "grains"),
            ],
            false,
        ),
        panel(
            "Pressure solve",
            "multigrid cycles",
            vec![curve("pressure_cycles", "cycles per step")],
            false,
        ),
        panel(
            "Divergence after projection",
            "|div u| (1/s)",
            vec![curve("divergence", "L2 norm")],
            true,
        ),
        panel("Time step", "s", vec![curve("dt", "dt")], true),
    ];
    plot_panels(&dir.join("series.png"), title, &panels, 1000, 300).map_err(io_err)?;

    let p = &out.particles;
    let (t, body) = (
        p.column("time").unwrap_or_default(),
        p.column("body").unwrap_or_default(),
    );
    let mut ids: Vec<f64> = body.clone();
    ids.sort_by(f64::total_cmp);
    ids.dedup();
    ids.truncate(8);
    let track = |name: &str, what: &str| -> Vec<Curve> {
        let values = p.column(name).unwrap_or_default();
        ids.iter()
            .map(|&id| Curve {
                label: format!("{what}, body {id}"),
                points: (0..t.len())
                    .filter(|&k| body[k] == id)
                    .map(|k| (t[k], values[k]))
                    .collect(),
            })
            .collect()
    };
    let panels = [
        panel("Horizontal position", "x (m)", track("x", "x"), false),
        panel("Vertical position", "y (m)", track("y", "y"), false),
        panel("Horizontal velocity", "m/s", track("vx", "vx"), false),
        panel("Vertical velocity", "m/s", track("vy", "vy"), false),
    ];
    plot_panels(&dir.join("particles.png"), title, &panels, 1000, 300).map_err(io_err)
}
