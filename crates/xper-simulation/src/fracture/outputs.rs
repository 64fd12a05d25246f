//! Outputs of a fracture run besides the frames: `series.csv` columns and rows,
//! `summary.json`, and the PNGs `series.png`, `force_displacement.png`, `crack_pattern.png`
//! and, for a periodic cell, `stress_strain.png`.

use std::path::Path;

use serde::{Deserialize, Serialize};
use xper_bodies::Drive;
use xper_fracture::{FractureEnergy, FractureModel, FractureStepReport, InterfaceLaw};
use xper_io::{plot_panels, plot_segments, SegmentLayer, SeriesTable};

use super::frames::{is_damaged, point_position};
use crate::outputs::{panel, series_curve};

/// Per-load columns of `series.csv`, after `step` and `time`: `<name>_fx`, `<name>_fy` (N),
/// `<name>_ux`, `<name>_uy` (m) for each load in scene order.
pub const LOAD_SUFFIXES: [&str; 4] = ["fx", "fy", "ux", "uy"];

/// Columns of `series.csv` after the load columns.
pub const FRACTURE_COLUMNS: [&str; 17] = [
    "kinetic",
    "elastic",
    "plastic",
    "cohesive_stored",
    "cohesive_dissipated",
    "contact_dissipated",
    "external_work",
    "initial_energy",
    "energy_error",
    "contacts",
    "broken_points",
    "iterations",
    "residual",
    "converged",
    "wall_time",
    "solve_time",
    "broken_interfaces",
];

/// Columns of `series.csv` of a periodic cell, after [`FRACTURE_COLUMNS`]: the macroscopic
/// strain (dimensionless, tensor shear), the stress as the volume average of the element
/// stresses and from the forces across the periodic sides (Pa), the largest difference of
/// the two (Pa), the work of the macroscopic loading (J), and the fractions of cohesive
/// interface points damaged (broken included) and broken.
pub const PERIODIC_COLUMNS: [&str; 13] = [
    "strain_xx",
    "strain_yy",
    "strain_xy",
    "stress_xx",
    "stress_yy",
    "stress_xy",
    "boundary_stress_xx",
    "boundary_stress_yy",
    "boundary_stress_xy",
    "stress_difference",
    "macro_work",
    "damaged_fraction",
    "broken_fraction",
];

/// The columns of `series.csv` for a model with these load names, with the
/// [`PERIODIC_COLUMNS`] for a periodic cell.
pub fn series_columns(loads: &[String], periodic: bool) -> Vec<String> {
    let mut c = vec!["step".to_string(), "time".to_string()];
    for name in loads {
        c.extend(LOAD_SUFFIXES.iter().map(|s| format!("{name}_{s}")));
    }
    c.extend(FRACTURE_COLUMNS.iter().map(|s| s.to_string()));
    if periodic {
        c.extend(PERIODIC_COLUMNS.iter().map(|s| s.to_string()));
    }
    c
}

/// The `series.csv` row of a step (energies in J, forces in N, displacements in m).
pub fn series_row(r: &FractureStepReport) -> Vec<f64> {
    let mut row = vec![r.step as f64, r.time];
    for l in &r.loads {
        row.extend([l.force[0], l.force[1], l.displacement[0], l.displacement[1]]);
    }
    let e: &FractureEnergy = &r.energy;
    row.extend([
        e.kinetic,
        e.elastic,
        e.plastic,
        e.cohesive_stored,
        e.cohesive_dissipated,
        e.contact_dissipated,
        e.external_work,
        e.initial,
        e.error(),
        r.contacts as f64,
        r.broken_points as f64,
        f64::from(r.iterations),
        r.residual,
        f64::from(u8::from(r.converged)),
        r.wall_time,
        r.solve_time,
        r.broken_interfaces as f64,
    ]);
    if let Some(c) = &r.cell {
        let difference = (0..3)
            .map(|k| (c.stress_volume[k] - c.stress_boundary[k]).abs())
            .fold(0.0, f64::max);
        let [damaged, all] = r.damaged_points.map(|n| n as f64);
        let fraction = |n: f64| if all > 0.0 { n / all } else { 0.0 };
        row.extend(c.strain);
        row.extend(c.stress_volume);
        row.extend(c.stress_boundary);
        row.extend([
            difference,
            c.work,
            fraction(damaged),
            fraction(r.broken_points as f64),
        ]);
    }
    row
}

/// `stress_strain.png` of a periodic cell: for each component of the macroscopic strain that
/// moves, the stress (volume average and boundary forces) against the strain.
pub fn write_stress_strain(series: &SeriesTable, path: &Path, title: &str) -> std::io::Result<()> {
    let mut panels = Vec::new();
    for c in ["xx", "yy", "xy"] {
        let strain = format!("strain_{c}");
        let moves = series
            .column(&strain)
            .is_some_and(|v| v.iter().any(|&x| x != 0.0));
        if !moves {
            continue;
        }
        panels.push(panel(
            &format!("{c} component"),
            &format!("macroscopic strain E_{c}"),
            &format!("macroscopic stress S_{c} (Pa)"),
            vec![
                series_curve(series, &strain, &format!("stress_{c}"), "volume average"),
                series_curve(
                    series,
                    &strain,
                    &format!("boundary_stress_{c}"),
                    "forces across the sides",
                ),
            ],
            false,
        ));
    }
    plot_panels(path, title, &panels, 900, 320)
}

/// `summary.json` of a fracture run.
#[derive(Serialize, Deserialize)]
pub struct FractureSummary {
    /// Scene name.
    pub scene: String,
    /// Scene file as given.
    pub scene_file: String,
    /// `completed`, `stopped` (by `--stop-at-step`) or `failed`.
    pub status: String,
    /// Why the run failed (empty otherwise).
    pub message: String,
    /// Triangles, i.e. element bodies.
    pub elements: usize,
    /// Interfaces (two contact points each).
    pub interfaces: usize,
    /// Mesh nodes.
    pub nodes: usize,
    /// Time step (s).
    pub dt: f64,
    /// Steps done.
    pub steps: u64,
    /// Simulated time (s).
    pub simulated_time: f64,
    /// Sum of the steps' wall times (s).
    pub wall_time_s: f64,
    /// Sum of the solve times (s).
    pub solve_time_s: f64,
    /// Solve time per interface-point update: solve time / sum of (points x sweeps) (ns).
    pub ns_per_point_update: f64,
    /// Median NLGS sweeps per step.
    pub median_iterations: f64,
    /// Largest NLGS sweeps in a step.
    pub max_iterations: f64,
    /// Steps whose NLGS did not converge.
    pub non_converged_steps: usize,
    /// Broken interface points at the end.
    pub final_broken_points: usize,
    /// Fully broken cohesive interfaces at the end.
    pub final_broken_interfaces: usize,
    /// The energy budget at the end (J).
    pub energy: FractureEnergy,
    /// `energy.error()` at the end (J).
    pub energy_error: f64,
    /// Measures of the crack pattern at the end.
    pub crack: super::crack::CrackMetrics,
    /// Peak resident memory of the process (bytes), where the platform reports it.
    pub peak_memory_bytes: Option<u64>,
    /// Version of xper.
    pub xper_version: String,
    /// Processes of the run (1 without mpirun).
    pub processes: usize,
    /// Each process's load and communication (empty on one process).
    pub ranks: Vec<crate::ranks::RankSummary>,
    /// The same steps on one process (`--compare-serial` under mpirun).
    pub serial_comparison: Option<crate::comparison::SerialComparison>,
    /// The macroscopic state of a periodic cell at the end (absent for a specimen).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cell: Option<xper_fracture::CellState>,
}

/// The summary of a run from its series and final model.
pub fn summary(
    m: &FractureModel,
    series: &SeriesTable,
    scene: (&str, &Path),
    status: &'static str,
    message: String,
) -> FractureSummary {
    let col = |name: &str| series.column(name).unwrap_or_default();
    let (iterations, contacts, solve) = (col("iterations"), col("contacts"), col("solve_time"));
    let updates: f64 = iterations.iter().zip(&contacts).map(|(i, c)| i * c).sum();
    let solve_time: f64 = solve.iter().sum();
    let mut sorted = iterations.clone();
    sorted.sort_by(f64::total_cmp);
    FractureSummary {
        scene: scene.0.to_string(),
        scene_file: scene.1.display().to_string(),
        status: status.to_string(),
        message,
        elements: m.elements.len(),
        interfaces: m.interfaces.len(),
        nodes: m.mesh.nodes.len(),
        dt: m.spec.dt,
        steps: m.step,
        simulated_time: m.time,
        wall_time_s: col("wall_time").iter().sum(),
        solve_time_s: solve_time,
        ns_per_point_update: if updates > 0.0 {
            solve_time / updates * 1e9
        } else {
            0.0
        },
        median_iterations: sorted.get(sorted.len() / 2).copied().unwrap_or(0.0),
        max_iterations: sorted.last().copied().unwrap_or(0.0),
        non_converged_steps: col("converged").iter().filter(|&&c| c == 0.0).count(),
        final_broken_points: m.broken_points(),
        final_broken_interfaces: m.broken_interfaces(),
        energy: m.energy,
        energy_error: m.energy.error(),
        crack: super::crack::crack_metrics(m),
        peak_memory_bytes: xper_io::peak_memory_bytes(),
        xper_version: env!("CARGO_PKG_VERSION").to_string(),
        processes: 1,
        ranks: Vec::new(),
        serial_comparison: None,
        cell: m.cell,
    }
}

/// `series.png`: energy budget, NLGS sweeps, residual and broken points against time.
pub fn write_series_plot(series: &SeriesTable, path: &Path, title: &str) -> std::io::Result<()> {
    let c = |y: &str, label: &str| series_curve(series, "time", y, label);
    let t = "time (s)";
    let panels = [
        panel(
            "Energy budget",
            t,
            "energy (J)",
            vec![
                c("kinetic", "kinetic"),
                c("elastic", "elastic"),
                c("plastic", "plastic work"),
                c("cohesive_stored", "cohesive stored"),
                c("cohesive_dissipated", "cohesive dissipated"),
                c("contact_dissipated", "contact dissipated"),
                c("external_work", "external work"),
                c("energy_error", "balance error"),
            ],
            false,
        ),
        panel(
            "Interface solver",
            t,
            "NLGS sweeps",
            vec![c("iterations", "sweeps per step")],
            false,
        ),
        panel(
            "Solver residual",
            t,
            "residual",
            vec![c("residual", "final residual")],
            true,
        ),
        panel(
            "Fracture",
            t,
            "count",
            vec![
                c("broken_points", "broken points"),
                c("broken_interfaces", "broken interfaces"),
            ],
            false,
        ),
    ];
    plot_panels(path, title, &panels, 1000, 300)
}

/// `force_displacement.png`: for each load component with an imposed velocity (or, when no
/// load imposes one, with an imposed force), |force| along it against the mean displacement
/// of the load's nodes along it.
pub fn write_force_displacement(
    m: &FractureModel,
    series: &SeriesTable,
    path: &Path,
    title: &str,
) -> std::io::Result<()> {
    let any_velocity =
        (m.spec.loads.iter()).any(|l| l.drives.iter().any(Drive::is_imposed_velocity));
    let mut panels = Vec::new();
    for l in &m.spec.loads {
        for (d, axis) in ["x", "y"].iter().enumerate() {
            let keep = if any_velocity {
                l.drives[d].is_imposed_velocity()
            } else {
                matches!(l.drives[d], Drive::Force(_))
            };
            if !keep {
                continue;
            }
            let mut c = series_curve(
                series,
                &format!("{}_u{axis}", l.name),
                &format!("{}_f{axis}", l.name),
                "",
            );
            c.points.iter_mut().for_each(|p| p.1 = p.1.abs());
            panels.push(panel(
                &format!("load `{}`, {axis} component", l.name),
                &format!("mean displacement u{axis} (m)"),
                &format!("|force f{axis}| (N)"),
                vec![c],
                false,
            ));
        }
    }
    plot_panels(path, title, &panels, 900, 320)
}

/// Intensity below which a damaged interface is drawn as strongly damaged.
pub const STRONG_DAMAGE: f64 = 0.5;

/// `crack_pattern.png`: the mesh outline and region boundaries at the current state;
/// damaged cohesive interfaces (smallest point intensity below beta0) in light orange,
/// strongly damaged ones (below [`STRONG_DAMAGE`]) in orange, broken ones in thick black. An
/// interface across the sides of a periodic cell is drawn on both sides, so that a crack
/// leaving the cell is seen re-entering on the opposite side.
pub fn write_crack_pattern(m: &FractureModel, path: &Path, title: &str) -> std::io::Result<()> {
    let mut layers: [Vec<[[f64; 2]; 2]>; 5] = Default::default();
    if let Ok(topology) = m.mesh.neighbours() {
        for edge in &topology.boundary {
            let t = edge.triangle as usize;
            let j = edge.local_edge as usize;
            let p = super::frames::node_position(m, t, j);
            let q = super::frames::node_position(m, t, (j + 1) % 3);
            layers[0].push([p, q]);
        }
    }
    for i in &m.interfaces {
        let seg = [point_position(m, i, 0), point_position(m, i, 1)];
        let image = if i.period == [0.0; 2] {
            None
        } else {
            let t = super::frames::deformed_period(m, i);
            Some(seg.map(|p| [p[0] + t[0], p[1] + t[1]]))
        };
        let [a, b] = i.elements.map(|e| m.elements[e as usize].region);
        let beta = i.points[0].intensity.min(i.points[1].intensity);
        let k = if m.is_broken(i) {
            4
        } else if is_damaged(m, i) && beta < STRONG_DAMAGE {
            3
        } else if is_damaged(m, i) {
            2
        } else if a != b || matches!(m.laws[i.law as usize], InterfaceLaw::Contact { .. }) {
            1
        } else {
            continue;
        };
        layers[k].push(seg);
        layers[k].extend(image);
    }
    let [outline, regions, light, strong, broken] = layers;
    let (n_light, n_strong, n_broken) = (light.len(), strong.len(), broken.len());
    let layer = |label: String, color, width, segments| SegmentLayer {
        label,
        color,
        width,
        segments,
    };
    let layers = [
        layer("outline".into(), [120, 120, 120], 1, outline),
        layer(
            "region boundaries, contact interfaces".into(),
            [110, 150, 200],
            1,
            regions,
        ),
        layer(
            format!("damaged, beta < beta0: {n_light}"),
            [250, 215, 160],
            1,
            light,
        ),
        layer(
            format!("strongly damaged, beta < {STRONG_DAMAGE}: {n_strong}"),
            [235, 120, 20],
            2,
            strong,
        ),
        layer(format!("broken: {n_broken}"), [20, 20, 20], 3, broken),
    ];
    let title = format!("{title}: step {}, t = {:.4e} s", m.step, m.time);
    plot_segments(path, &title, "x (m)", "y (m)", &layers, 1000)
}
