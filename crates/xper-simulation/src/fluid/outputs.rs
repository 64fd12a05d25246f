//! Outputs of a run with a fluid besides the bodies' frames: the fluid image, `series.csv`
//! and `particles.csv` columns, `summary.json`, `series.png` and `particles.png`.

use crate::comparison::SerialComparison;
use crate::outputs::{self, io_err, mean, series_curve};
use crate::ranks::RankSummary;
use crate::RunError;
use serde::Serialize;
use std::path::Path;
use xper_fluid::immersed::ImmersedForcing;
use xper_fluid::{CoupledState, FluidParams, ImmersedDisk};
use xper_io::{plot_panels, Curve, ImageGrid, SeriesTable};
use xper_scene::Scene;

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

#[derive(Serialize)]
/// Summary of a run with a fluid (`summary.json`).
pub struct FluidSummary {
    pub scene: String,
    pub scene_file: String,
    pub status: &'static str,
    pub message: String,
    pub cells: [usize; 2],
    pub cell_size: f64,
    pub immersed_disks: usize,
    pub bodies: usize,
    pub steps: u64,
    pub simulated_time: f64,
    pub wall_time_s: f64,
    pub average_dt: f64,
    pub average_pressure_cycles: f64,
    pub max_pressure_cycles: f64,
    pub fluid_cells_per_second: f64,
    pub non_converged_contact_steps: usize,
    pub peak_memory_bytes: Option<u64>,
    pub xper_version: &'static str,
    pub processes: usize,
    pub ranks: Vec<RankSummary>,
    /// Cells of the pressure solve's coarsest grid that rank 0, as each process holding it,
    /// relaxes whole (runs on several processes).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pressure_gathered_cells: Option<usize>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub serial_comparison: Option<SerialComparison>,
}

/// The solid fraction of every face for the immersed disks where they are now.
pub fn solid_fraction(
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
pub fn fluid_image(state: &CoupledState, params: &FluidParams, immersed: &[usize]) -> ImageGrid {
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

pub fn summary(
    series: &SeriesTable,
    scene: &Scene,
    state: &CoupledState,
    immersed_disks: usize,
    status: &'static str,
    message: String,
    file: &Path,
) -> FluidSummary {
    let col = |name: &str| series.column(name).unwrap_or_default();
    let (cycles, fluid_time) = (
        col("pressure_cycles"),
        col("fluid_time").iter().sum::<f64>(),
    );
    let grid = state.fluid.grid;
    FluidSummary {
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
        average_dt: mean(&col("dt")),
        average_pressure_cycles: mean(&cycles),
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
pub fn write_plots(
    series: &SeriesTable,
    particles: &SeriesTable,
    dir: &Path,
    title: &str,
) -> Result<(), RunError> {
    let curve = |name: &str, label: &str| series_curve(series, "time", name, label);
    let panel = |title: &str, y: &str, curves: Vec<Curve>, log_y: bool| {
        outputs::panel(title, "time (s)", y, curves, log_y)
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
        panel("Time step", "s", vec![curve("dt", "dt")], false),
    ];
    plot_panels(&dir.join("series.png"), title, &panels, 1000, 300).map_err(io_err)?;

    let p = particles;
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
