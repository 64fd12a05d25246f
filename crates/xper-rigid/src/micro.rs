//! The micromechanical measures of a rigid run (`[output] micro`): one row of `micro.csv` per
//! frame, and `xper post` on a checkpoint (the measures, the normal-force distribution and the
//! force chains of that state). The measures are `xper_nscd::micro`'s.

use crate::run_outputs::io_err;
use crate::RunError;
use std::path::Path;
use xper_io::SeriesTable;
use xper_math::{Real, AXIS_NAMES, DIM};
use xper_nscd::micro::{measure, normalised_normal_forces, Micro, VolumeSource};
use xper_nscd::World;

/// The volume source of a scene's setting.
pub fn volume_source(v: xper_scene::MicroVolume) -> VolumeSource {
    match v {
        xper_scene::MicroVolume::Walls => VolumeSource::Walls,
        xper_scene::MicroVolume::Grains => VolumeSource::Grains,
        xper_scene::MicroVolume::Cell => VolumeSource::Cell,
    }
}

/// The columns of `micro.csv`: step, time, the volume and the extents of its box (m), then
/// the measures (tensor components `stress_xy` for `sigma_xy`, Pa; `fabric_xy`).
pub fn columns() -> Vec<String> {
    let mut c: Vec<String> = ["step", "time", "volume"].map(String::from).to_vec();
    c.extend(AXIS_NAMES.iter().map(|a| format!("extent_{a}")));
    let tensor = |name: &str, c: &mut Vec<String>| {
        for a in &AXIS_NAMES {
            for b in &AXIS_NAMES {
                c.push(format!("{name}_{a}{b}"));
            }
        }
    };
    tensor("stress", &mut c);
    c.extend(["pressure", "deviator", "stress_ratio"].map(String::from));
    tensor("fabric", &mut c);
    c.extend(
        [
            "anisotropy",
            "solid_fraction",
            "grains",
            "grain_contacts",
            "boundary_contacts",
            "coordination",
            "coordination_without_rattlers",
            "rattler_fraction",
            "mean_normal_force",
            "strong_fraction",
            "strong_share",
        ]
        .map(String::from),
    );
    c
}

/// An empty `micro.csv` table.
pub fn table() -> SeriesTable {
    let names = columns();
    SeriesTable::new(&names.iter().map(String::as_str).collect::<Vec<_>>())
}

/// The row of `world`'s measures.
pub fn row(world: &World, m: &Micro) -> Vec<Real> {
    let mut r = vec![world.step as Real, world.time, m.volume];
    r.extend(m.extent.iter());
    r.extend(m.stress.transpose().iter());
    r.extend([m.pressure, m.deviator, m.stress_ratio()]);
    r.extend(m.fabric.transpose().iter());
    r.extend([
        m.anisotropy,
        m.solid_fraction,
        m.grains as Real,
        m.grain_contacts as Real,
        m.boundary_contacts as Real,
        m.coordination,
        m.coordination_without_rattlers,
        m.rattler_fraction,
        m.mean_normal_force,
        m.strong_fraction,
        m.strong_share,
    ]);
    r
}

/// The measures of `world`, as a run error naming `scene` when they cannot be taken.
pub fn measures(world: &World, source: VolumeSource, scene: &Path) -> Result<Micro, RunError> {
    measure(world, source)
        .map_err(|e| RunError::BadInput(format!("{}: [output] micro: {e}", scene.display())))
}

/// Bins of the normal-force distribution per unit of `f_n / <f_n>`.
const BINS_PER_MEAN: usize = 10;

/// The probability density of `f_n / <f_n>` over bins of width 0.1 from 0 to the largest
/// value: rows `(bin centre, density, count)`.
pub fn force_distribution(world: &World) -> Vec<[Real; 3]> {
    let forces = normalised_normal_forces(world);
    let largest = forces.iter().copied().fold(0.0, Real::max);
    let per = BINS_PER_MEAN as Real;
    let bins = ((largest * per).floor() as usize + 1).min(100 * BINS_PER_MEAN);
    let mut count = vec![0usize; bins];
    for f in &forces {
        count[((f * per) as usize).min(bins - 1)] += 1;
    }
    let total = forces.len().max(1) as Real;
    (count.iter().enumerate())
        .map(|(k, &c)| {
            let centre = (2 * k + 1) as Real / (2.0 * per);
            [centre, c as Real / total * per, c as Real]
        })
        .collect()
}

/// `xper post` on the payload of a rigid run's checkpoint (`label` names it in errors): the
/// measures of its world written to `out` ([`post`]); returns the line to print.
pub fn post_checkpoint(
    payload: &[u8],
    source: VolumeSource,
    out: &Path,
    label: &Path,
) -> Result<String, RunError> {
    let world = World::from_bytes(payload)
        .map_err(|e| RunError::BadInput(format!("{}: {e}", label.display())))?;
    let m = post(&world, source, out, label)?;
    Ok(format!(
        "step {}: p {:.6e} Pa, q/p {:.4}, solid fraction {:.4}, z {:.4}, z* {:.4}",
        world.step,
        m.pressure,
        m.stress_ratio(),
        m.solid_fraction,
        m.coordination,
        m.coordination_without_rattlers
    ))
}

/// `xper post`: the measures of `world` written to `out` as `micro.json`, `forces.csv` (the
/// distribution) and `force_chains.vtu`; returns the measures.
pub fn post(
    world: &World,
    source: VolumeSource,
    out: &Path,
    scene: &Path,
) -> Result<Micro, RunError> {
    let m = measures(world, source, scene)?;
    crate::run_outputs::create_output_dir(out)?;
    let mut json = serde_json::Map::new();
    for (name, value) in columns().into_iter().zip(row(world, &m)) {
        json.insert(name, serde_json::json!(value));
    }
    xper_io::write_json_atomic(&out.join("micro.json"), &serde_json::Value::Object(json))
        .map_err(io_err)?;
    let mut text = String::from("normal_force_over_mean,probability_density,contacts\n");
    for [f, p, c] in force_distribution(world) {
        text.push_str(&format!("{f},{p},{c}\n"));
    }
    xper_io::write_atomic(&out.join("forces.csv"), text.as_bytes()).map_err(io_err)?;
    let chains = crate::frames::contacts_grid(world, true);
    xper_io::write_vtu(&out.join("force_chains.vtu"), &chains).map_err(io_err)?;
    Ok(m)
}

/// A row's strains: axial `(L0 - L) / L0`, volumetric `(V - V0) / V0` (dilation positive),
/// and the row's index in `micro.csv`.
pub type Strains = (Real, Real, usize);

/// Strains of the rows of `micro.csv` from the first row at or after `start` (s; the last
/// stage's beginning): the axial axis is the one that shortened most by the last row;
/// returns the axis and the strains of each row from `start` on.
pub fn strains(table: &SeriesTable, start: Real) -> Option<(usize, Vec<Strains>)> {
    let time = table.column("time")?;
    let first = time.iter().position(|&t| t >= start - 1e-12)?;
    let volume = table.column("volume")?;
    let extents: Vec<Vec<Real>> = (AXIS_NAMES.iter())
        .map(|a| table.column(&format!("extent_{a}")))
        .collect::<Option<_>>()?;
    let last = time.len() - 1;
    let shortening = |e: &Vec<Real>| (e[first] - e[last]) / e[first];
    let axis =
        (0..DIM).max_by(|&a, &b| shortening(&extents[a]).total_cmp(&shortening(&extents[b])))?;
    let e = &extents[axis];
    let rows = (first..=last)
        .map(|k| {
            let axial = (e[first] - e[k]) / e[first];
            (axial, (volume[k] - volume[first]) / volume[first], k)
        })
        .collect();
    Some((axis, rows))
}

/// `micro.png`: the stress ratio `q/p`, the volumetric strain and `z*` against the axial strain
/// of the last stage (the biaxial or triaxial test's curves), from the rows of `micro.csv`
/// from `start` (s) on.
pub fn write_plot(
    table: &SeriesTable,
    start: Real,
    path: &Path,
    title: &str,
) -> Result<(), RunError> {
    let Some((axis, rows)) = strains(table, start) else {
        return Ok(());
    };
    let column = |name: &str| table.column(name).unwrap_or_default();
    let (ratio, z) = (
        column("stress_ratio"),
        column("coordination_without_rattlers"),
    );
    let curve = |label: &str, y: &dyn Fn(&Strains) -> Real| xper_io::Curve {
        label: label.into(),
        points: rows.iter().map(|r| (r.0, y(r))).collect(),
    };
    let x = format!("axial strain (L0 - L) / L0 along {}", AXIS_NAMES[axis]);
    let panels = [
        crate::run_outputs::panel(
            "Stress ratio",
            &x,
            "q / p",
            vec![curve("q/p", &|r| ratio[r.2])],
            false,
        ),
        crate::run_outputs::panel(
            "Volumetric strain",
            &x,
            "(V - V0) / V0 (dilation > 0)",
            vec![curve("volumetric strain", &|r| r.1)],
            false,
        ),
        crate::run_outputs::panel(
            "Coordination",
            &x,
            "z*",
            vec![curve("z* (no rattlers)", &|r| z[r.2])],
            false,
        ),
    ];
    xper_io::plot_panels(path, title, &panels, 900, 300).map_err(io_err)
}
