//! `xper bench` on fracture scenes: the figures of `../shared/bench/notched-tension.md` and of
//! issue 4's benchmark (elements, interfaces, wall time per step, NLGS sweeps, ns per
//! interface point update, peak memory), plus when and where the specimen breaks.

use std::path::Path;
use std::time::Instant;

use serde::{Deserialize, Serialize};
use xper_fracture::{FractureModel, FractureStepper, InterfaceLaw};
use xper_scene::MeshSource;

use crate::stats::median;
use xper_simulation::fracture::crack::{mesh_centre, midpoint};
use xper_simulation::RunError;

/// Prefix of the JSON files of fracture results in the results directory.
pub const FILE_PREFIX: &str = "fracture-";

/// Figures of one fracture benchmark run.
#[derive(Serialize, Deserialize)]
pub struct FractureBenchResult {
    /// Scene name.
    pub scene: String,
    /// CPU and threads.
    pub machine: String,
    /// Triangles (deformable bodies).
    pub elements: usize,
    /// Cohesive or contact interfaces (interior edges).
    pub interfaces: usize,
    /// Contact points in the solve at the first step.
    pub points: usize,
    /// Steps run.
    pub steps: u64,
    /// Time step (s).
    pub dt: f64,
    /// Simulated time (s).
    pub simulated_time_s: f64,
    /// Wall time of the steps, model building excluded (s).
    pub wall_time_s: f64,
    /// Wall time of building the model: meshing, element matrices, interfaces (s).
    pub build_time_s: f64,
    /// Median wall time per step (ms).
    pub median_step_ms: f64,
    /// Median and largest NLGS sweeps per step.
    pub median_sweeps: f64,
    /// Largest NLGS sweeps of a step.
    pub max_sweeps: f64,
    /// All NLGS sweeps of the run.
    pub total_sweeps: f64,
    /// Solve time over point updates (points x sweeps), whole run (ns).
    pub ns_per_point_update: f64,
    /// Steps whose NLGS stopped at its sweep limit.
    pub non_converged_steps: usize,
    /// Peak resident memory of the process (bytes).
    pub peak_memory_bytes: u64,
    /// First time an interface breaks (intensity 0) left and right of the vertical mid-line
    /// of the mesh (s); none if none did.
    pub first_break_s: [Option<f64>; 2],
    /// First time the first load's force falls below 1 % of its peak after the peak (s).
    pub ruin_s: Option<f64>,
    /// Peak |force| on the first load (N).
    pub peak_force_n: f64,
    /// Energy dissipated by damage (J).
    pub cohesive_dissipated_j: f64,
    /// `cohesive_dissipated / (w x ligament x thickness)` for a double-edge-notched mesh
    /// (ligament = side - 2 notch depth) with one cohesive law.
    pub dissipation_ratio: Option<f64>,
    /// Energy balance error over the run, relative (see `FractureEnergy::error`).
    pub energy_error: f64,
}

/// Side of each interface: 0 left of the vertical mid-line of the mesh, 1 right of it.
fn interface_sides(m: &FractureModel) -> Vec<usize> {
    let centre = mesh_centre(m);
    (m.interfaces.iter())
        .map(|i| usize::from(midpoint(m, i)[0] > centre[0]))
        .collect()
}

/// `w x ligament x thickness` of a double-edge-notched specimen with one cohesive law.
fn ideal_dissipation(scene: &xper_scene::FractureScene, m: &FractureModel) -> Option<f64> {
    let MeshSource::DoubleEdgeNotched(spec) = &scene.mesh.source else {
        return None;
    };
    let [InterfaceLaw::Cohesive(zone)] = m.laws.as_slice() else {
        return None;
    };
    let ligament = spec.side - 2.0 * spec.notch_depth;
    Some(zone.fracture_energy * ligament * m.spec.thickness)
}

/// Runs one fracture scene in this process, without outputs.
pub fn bench_one(
    path: &Path,
    steps: Option<u64>,
    machine: String,
) -> Result<FractureBenchResult, RunError> {
    let built = Instant::now();
    let (scene, mut model) = xper_simulation::fracture::build::load_model(path)?;
    let build_time_s = built.elapsed().as_secs_f64();
    let steps = steps.map_or(scene.steps, |s| s.min(scene.steps));
    let sides = interface_sides(&model);
    let broken_at_start: Vec<bool> = (model.interfaces.iter())
        .map(|i| i.points.iter().any(|p| p.intensity == 0.0))
        .collect();
    let mut first_break = [None; 2];
    let mut stepper = FractureStepper::new();
    let (mut step_ms, mut sweeps) = (vec![], vec![]);
    let (mut updates, mut solve_s) = (0.0, 0.0);
    let (mut points, mut non_converged, mut broken) = (0, 0, model.broken_points());
    let (mut peak_force, mut ruin) = (0.0_f64, None);
    let started = Instant::now();
    for _ in 0..steps {
        let r = stepper
            .step(&mut model)
            .map_err(|e| RunError::Runtime(format!("{}: {e}", path.display())))?;
        if r.step == 1 {
            points = r.contacts;
        }
        step_ms.push(r.wall_time * 1e3);
        sweeps.push(r.iterations as f64);
        updates += r.iterations as f64 * r.contacts as f64;
        solve_s += r.solve_time;
        non_converged += usize::from(!r.converged);
        if r.broken_points != broken {
            broken = r.broken_points;
            for (k, i) in model.interfaces.iter().enumerate() {
                let side = sides[k];
                if first_break[side].is_none()
                    && !broken_at_start[k]
                    && i.points.iter().any(|p| p.intensity == 0.0)
                {
                    first_break[side] = Some(model.time);
                }
            }
        }
        if let Some(load) = r.loads.first() {
            let f = load.force[0].hypot(load.force[1]);
            peak_force = peak_force.max(f);
            if ruin.is_none() && peak_force > 0.0 && f < 0.01 * peak_force && broken > 0 {
                ruin = Some(model.time);
            }
        }
    }
    let wall_time_s = started.elapsed().as_secs_f64();
    let ideal = ideal_dissipation(&scene, &model);
    Ok(FractureBenchResult {
        scene: scene.name.clone(),
        machine,
        elements: model.elements.len(),
        interfaces: model.interfaces.len(),
        points,
        steps,
        dt: model.spec.dt,
        simulated_time_s: model.time,
        wall_time_s,
        build_time_s,
        median_step_ms: median(step_ms),
        median_sweeps: median(sweeps.clone()),
        max_sweeps: sweeps.iter().copied().fold(0.0, f64::max),
        total_sweeps: sweeps.iter().sum(),
        ns_per_point_update: if updates > 0.0 {
            solve_s / updates * 1e9
        } else {
            0.0
        },
        non_converged_steps: non_converged,
        peak_memory_bytes: xper_io::peak_memory_bytes().unwrap_or(0),
        first_break_s: first_break,
        ruin_s: ruin,
        peak_force_n: peak_force,
        cohesive_dissipated_j: model.energy.cohesive_dissipated,
        dissipation_ratio: ideal.map(|w| model.energy.cohesive_dissipated / w),
        energy_error: model.energy.error(),
    })
}

fn time_us(t: Option<f64>) -> String {
    t.map_or("-".into(), |t| format!("{:.0}", t * 1e6))
}

/// The Markdown section of BENCHMARKS.md for the fracture results.
pub fn markdown(results: &[FractureBenchResult]) -> String {
    let mut md = String::from(
        "\n## Fracture scenes (issue 4, `../shared/bench/notched-tension.md`)\n\n\
         Regenerated by `cargo run --release -p xper-cli -- bench --scene <fracture scene>`; one \
         thread, no outputs; NLGS with the tolerance of the scene. ns / update: solve time over \
         (contact points x sweeps) over the whole run.\n\n\
         | scene | elements | interfaces | points | dt (s) | steps | wall (s) | step (ms) | sweeps median / max | ns / update | non-converged | peak memory (MB) | first break left / right (us) | ruin (us) | dissipated / (w x ligament) | energy error |\n\
         |---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    for r in results {
        md.push_str(&format!(
            "| {} | {} | {} | {} | {:.1e} | {} | {:.1} | {:.1} | {} / {} | {:.1} | {} | {:.0} | {} / {} | {} | {} | {:.1e} |\n",
            r.scene,
            r.elements,
            r.interfaces,
            r.points,
            r.dt,
            r.steps,
            r.wall_time_s,
            r.median_step_ms,
            r.median_sweeps,
            r.max_sweeps,
            r.ns_per_point_update,
            r.non_converged_steps,
            r.peak_memory_bytes as f64 / 1e6,
            time_us(r.first_break_s[0]),
            time_us(r.first_break_s[1]),
            time_us(r.ruin_s),
            r.dissipation_ratio.map_or("-".into(), |x| format!("{x:.3}")),
            r.energy_error
        ));
    }
    md.push_str(
        "\nReference (`../shared/bench/notched-tension.md`, Akantu 5.0.7, explicit, one thread, \
         about 20,900 triangles and 31,100 cohesive edges, 600 us): 121 s with cohesive elements \
         everywhere (10,090 steps of 11.6 ms, 169 MB), 70 s with cohesive elements inserted on \
         demand (118 MB); dissipated energy 1.18 to 1.40 times w x ligament. Goal for xper: at \
         most half of Akantu's wall time and a ratio below 1.1.\n",
    );
    md
}
