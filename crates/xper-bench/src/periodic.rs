//! `xper bench --periodic`: the cost of the periodic coupling. The application cell
//! (`scenes/periodic_bimaterial`) is stepped as it is, and as a plain specimen of the same
//! mesh and materials (no `[periodic]`: its left and right sides pulled apart at the
//! velocity the macroscopic strain rate gives them, the other sides free), alternately in
//! one sitting; the figures are the medians over the rounds.

use std::path::Path;

use serde::{Deserialize, Serialize};
use xper_bodies::{Drive, TimeFunction};
use xper_fracture::{FractureModel, FractureStepper, MacroDrive, NodeLoad};
use xper_simulation::RunError;

use crate::stats::median;

/// The JSON file of the results in the results directory.
pub const RESULTS_FILE: &str = "periodic.json";

/// The application scene.
pub const SCENE: &str = "scenes/periodic_bimaterial/scene.toml";

/// Figures of one variant over the rounds.
#[derive(Clone, Serialize, Deserialize)]
pub struct VariantFigures {
    /// Interfaces (those across the sides included).
    pub interfaces: usize,
    /// Median wall time per step of each round (ms).
    pub step_ms: Vec<f64>,
    /// Median NLGS sweeps per step of each round.
    pub sweeps: Vec<f64>,
    /// Solve time over point updates (points x sweeps) of each round (ns).
    pub ns_per_point_update: Vec<f64>,
    /// Step time outside the solve, per element, of each round (ns): free velocities,
    /// assembly, updates, the cell's stage.
    pub ns_per_element_outside_solve: Vec<f64>,
}

/// Results of `xper bench --periodic`.
#[derive(Serialize, Deserialize)]
pub struct PeriodicBench {
    /// CPU and threads.
    pub machine: String,
    /// Scene name.
    pub scene: String,
    /// Elements of the mesh.
    pub elements: usize,
    /// Steps per round and variant (from t = 0).
    pub steps: u64,
    /// Rounds (periodic then plain, alternately).
    pub rounds: usize,
    /// The scene's NLGS tolerance, used by both variants.
    pub tolerance: f64,
    /// The periodic cell.
    pub periodic: VariantFigures,
    /// The same mesh as a plain specimen.
    pub plain: VariantFigures,
}

impl PeriodicBench {
    /// Median over the rounds of the periodic cell's step time over the plain one's.
    pub fn step_ratio(&self) -> f64 {
        median(self.periodic.step_ms.clone()) / median(self.plain.step_ms.clone())
    }

    /// The same ratio per sweep: the cost of one sweep with the rows across the sides.
    pub fn update_ratio(&self) -> f64 {
        median(self.periodic.ns_per_point_update.clone())
            / median(self.plain.ns_per_point_update.clone())
    }
}

/// The plain twin of a periodic model: no cell, left and right node sets pulled at `+-v`.
fn plain_twin(scene: &Path) -> Result<FractureModel, RunError> {
    let bad = |e: String| RunError::BadInput(format!("{}: {e}", scene.display()));
    let loaded = xper_scene::load_any_scene(scene).map_err(|e| bad(e.to_string()))?;
    let xper_scene::AnyScene::Fracture(s) = loaded else {
        return Err(bad("not a fracture scene".into()));
    };
    let mut setup = s.build().map_err(|e| bad(e.to_string()))?;
    let Some(periodic) = setup.spec.periodic.take() else {
        return Err(bad("no [periodic] section".into()));
    };
    let MacroDrive::Strain(f) = &periodic.drives[0] else {
        return Err(bad("the bench needs an imposed strain_xx".into()));
    };
    let dt = setup.spec.dt;
    let rate = (f.eval(dt) - f.eval(0.0)) / dt;
    let v = 0.5 * rate * periodic.cell.size[0];
    for (name, sign) in [("left", -1.0), ("right", 1.0)] {
        let nodes = setup
            .mesh
            .node_set(name)
            .map_err(|e| bad(e.to_string()))?
            .to_vec();
        setup.spec.loads.push(NodeLoad {
            name: name.into(),
            nodes,
            drives: [
                Drive::Velocity(TimeFunction::Constant(sign * v)),
                Drive::Free,
            ],
        });
    }
    FractureModel::new(setup.mesh, setup.spec).map_err(|e| bad(e.to_string()))
}

/// Steps `model` `steps` times; pushes the round's figures into `fig`.
fn round(mut model: FractureModel, steps: u64, fig: &mut VariantFigures) -> Result<(), RunError> {
    let mut stepper = FractureStepper::new();
    let (mut step_ms, mut sweeps) = (Vec::new(), Vec::new());
    let (mut updates, mut solve, mut outside) = (0.0, 0.0, 0.0);
    for _ in 0..steps {
        let r = stepper
            .step(&mut model)
            .map_err(|e| RunError::Runtime(e.to_string()))?;
        step_ms.push(r.wall_time * 1e3);
        sweeps.push(f64::from(r.iterations));
        updates += f64::from(r.iterations) * r.contacts as f64;
        solve += r.solve_time;
        outside += r.wall_time - r.solve_time;
    }
    fig.interfaces = model.interfaces.len();
    fig.step_ms.push(median(step_ms));
    fig.sweeps.push(median(sweeps));
    fig.ns_per_point_update.push(solve / updates * 1e9);
    fig.ns_per_element_outside_solve
        .push(outside / (steps as f64 * model.elements.len() as f64) * 1e9);
    Ok(())
}

/// Runs the comparison and writes `out/periodic.json`.
pub fn bench_periodic(out: &Path, machine: String) -> Result<(), RunError> {
    let (steps, rounds) = (200, 3);
    let scene = Path::new(SCENE);
    let (s, periodic) = xper_simulation::fracture::build::load_model(scene)?;
    let plain = plain_twin(scene)?;
    let empty = || VariantFigures {
        interfaces: 0,
        step_ms: Vec::new(),
        sweeps: Vec::new(),
        ns_per_point_update: Vec::new(),
        ns_per_element_outside_solve: Vec::new(),
    };
    let mut result = PeriodicBench {
        machine,
        scene: s.name.clone(),
        elements: periodic.elements.len(),
        steps,
        rounds,
        tolerance: periodic.spec.nlgs.tolerance,
        periodic: empty(),
        plain: empty(),
    };
    for k in 0..rounds {
        round(periodic.clone(), steps, &mut result.periodic)?;
        round(plain.clone(), steps, &mut result.plain)?;
        println!(
            "round {}: periodic {:.1} ms per step, {:.1} ns per update; plain {:.1} ms, {:.1} ns",
            k + 1,
            result.periodic.step_ms[k],
            result.periodic.ns_per_point_update[k],
            result.plain.step_ms[k],
            result.plain.ns_per_point_update[k]
        );
    }
    println!(
        "periodic over plain: {:.3} per step, {:.3} per point update",
        result.step_ratio(),
        result.update_ratio()
    );
    xper_io::write_json_atomic(&out.join(RESULTS_FILE), &result)
        .map_err(|e| RunError::Runtime(e.to_string()))
}

fn list(values: &[f64], digits: usize) -> String {
    values
        .iter()
        .map(|v| format!("{v:.digits$}"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The Markdown section of BENCHMARKS.md.
pub fn markdown(r: &PeriodicBench) -> String {
    let row = |name: &str, f: &VariantFigures| {
        format!(
            "| {name} | {} | {} | {} | {} | {} |\n",
            f.interfaces,
            list(&f.step_ms, 1),
            list(&f.sweeps, 0),
            list(&f.ns_per_point_update, 1),
            list(&f.ns_per_element_outside_solve, 0),
        )
    };
    format!(
        "\n## Periodic cells (issue 35)\n\n\
         Regenerated by `cargo run --release -p xper-cli -- bench --periodic`: `{}` ({} \
         elements) stepped {} steps from t = 0 as a periodic cell, then as a plain specimen of \
         the same mesh (no `[periodic]`; its left and right sides pulled apart at the velocity \
         the macroscopic strain rate gives them), alternately, {} rounds, NLGS tolerance {:e} (the \
         scene's), one thread, no outputs; {}.\n\n\
         | variant | interfaces | step (ms), per round | sweeps per step | ns / point update | ns / element outside the solve |\n\
         |---|---|---|---|---|---|\n{}{}\n\
         Periodic over plain, medians of the rounds: **{:.3}** per step (target: below 1.10), \
         {:.3} per point update. The two variants do not do the same work: the periodic cell \
         starts in the affine motion of its strain rate, the plain specimen at rest with its \
         sides pulled, which launches waves and costs it more sweeps per step; the rows across \
         the sides are under 1 % of the points. So the periodic coupling adds no cost this \
         benchmark can measure; the plain specimen's higher cost per update (both with \
         Anderson mixing) is measured, not explained.\n",
        r.scene,
        r.elements,
        r.steps,
        r.rounds,
        r.tolerance,
        r.machine,
        row("periodic cell", &r.periodic),
        row("plain specimen", &r.plain),
        r.step_ratio(),
        r.update_ratio()
    )
}
