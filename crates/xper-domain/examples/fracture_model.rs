//! The distributed fracture solve on many processes, from the partition it would use and the
//! measured cost of a point update: for each process count `P`, the elements are partitioned
//! by `xper_domain::fracture::element_owners`, as `DistributedFracture` does (an interface
//! belongs to the owner of its first element, an element is held by its owner and by the
//! owners of its interfaces), and each process's interface points, neighbours and shared
//! elements are counted. Per NLGS sweep (Visseq et al., Comput. Mech. 49 (2012) 709: local
//! sweeps, the shared elements' velocities exchanged with the neighbours after each, a global
//! check every 5 sweeps):
//!
//! ```text
//! T_P = max_p (edge_p t_u + max(inner_p t_u, neighbours_p alpha + bytes_p / beta))
//!     + log2(P) alpha / 5
//! efficiency = points t_u / (P T_P)
//! ```
//!
//! `edge_p` the points of process `p` whose interface touches a shared element, swept first,
//! `inner_p` the others, swept while the shared elements' velocities travel
//! (`xper_domain::distributed_nlgs`); without that overlap, the exchange adds to the whole
//! sweep (the `no overlap` column).
//! `t_u` the measured ns per point update of the scene's whole serial run
//! (`bench-results/fracture-<scene>.json`, `xper bench --fracture`), `bytes_p` the 6 nodal
//! velocities (8 B each) of every element shared with each neighbour, `alpha` = 2 us, `beta`
//! = 5 GB/s (InfiniBand, as the rigid model). More sweeps with more interfaces (the
//! decomposition's Jacobi coupling) are not in the model: 3 % on box10k at 2 processes.
//!
//! `cargo run -p xper-domain --release --example fracture_model [-- SCENE_DIR ...] [--json FILE]`

mod common;

use common::{arguments, write_json, ALPHA, BETA};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use xper_domain::fracture::element_owners;
use xper_fracture::FractureModel;

const PROCESSES: [usize; 4] = [2, 48, 256, 1024];

fn model_of(scene: &Path) -> Result<FractureModel, String> {
    let file = scene.join("scene.toml");
    let parsed = xper_scene::load_any_scene(&file).map_err(|e| e.to_string())?;
    let xper_scene::AnyScene::Fracture(fracture) = parsed else {
        return Err(format!("{}: not a fracture scene", file.display()));
    };
    let setup = fracture.build().map_err(|e| e.to_string())?;
    FractureModel::new(setup.mesh, setup.spec).map_err(|e| format!("{}: {e}", file.display()))
}

/// The measured ns per point update of the scene's benchmark run.
fn point_update_seconds(scene: &Path, results: &Path) -> Result<f64, String> {
    let name = scene
        .file_name()
        .and_then(|n| n.to_str())
        .ok_or_else(|| format!("{}: no scene name", scene.display()))?;
    let file = results.join(format!("fracture-{name}.json"));
    let text = std::fs::read_to_string(&file).map_err(|e| format!("{}: {e}", file.display()))?;
    let figures: serde_json::Value =
        serde_json::from_str(&text).map_err(|e| format!("{}: {e}", file.display()))?;
    (figures["ns_per_point_update"].as_f64())
        .map(|ns| ns * 1e-9)
        .ok_or_else(|| format!("{}: no ns_per_point_update", file.display()))
}

/// What one process holds and sends per sweep.
struct Load {
    /// Interface points.
    points: usize,
    /// Those of them whose interface touches a shared element.
    edge: usize,
    /// Processes it shares elements with.
    neighbours: usize,
    /// Velocity values it sends.
    values: usize,
}

/// Each process's load.
fn loads(model: &FractureModel, processes: usize) -> Vec<Load> {
    let owners = element_owners(model, processes);
    let mut holders: Vec<Vec<u32>> = owners.iter().map(|&o| vec![o]).collect();
    let mut points = vec![0; processes];
    for interface in &model.interfaces {
        let owner = owners[interface.elements[0] as usize];
        points[owner as usize] += 2;
        for e in interface.elements {
            let held = &mut holders[e as usize];
            if !held.contains(&owner) {
                held.push(owner);
            }
        }
    }
    // Elements each pair of processes both hold.
    let mut pairs: BTreeMap<(u32, u32), usize> = BTreeMap::new();
    for held in holders.iter().filter(|h| h.len() > 1) {
        for &a in held {
            for &b in held.iter().filter(|&&b| b != a) {
                *pairs.entry((a, b)).or_default() += 1;
            }
        }
    }
    let mut edge = vec![0; processes];
    for interface in &model.interfaces {
        if interface
            .elements
            .iter()
            .any(|&e| holders[e as usize].len() > 1)
        {
            edge[owners[interface.elements[0] as usize] as usize] += 2;
        }
    }
    let mut neighbours = vec![0; processes];
    let mut values = vec![0; processes];
    for (&(a, _), &shared) in &pairs {
        neighbours[a as usize] += 1;
        values[a as usize] += 6 * shared;
    }
    (0..processes)
        .map(|p| Load {
            points: points[p],
            edge: edge[p],
            neighbours: neighbours[p],
            values: values[p],
        })
        .collect()
}

fn main() {
    let (arguments, json) = arguments("fracture_model");
    let mut scenes: Vec<PathBuf> = arguments.into_iter().map(PathBuf::from).collect();
    if scenes.is_empty() {
        scenes = vec![
            "scenes/nooru_mohamed".into(),
            "scenes/nooru_mohamed_100k".into(),
        ];
    }
    let fail = |e: String| -> ! {
        eprintln!("fracture_model: {e}");
        std::process::exit(1)
    };
    println!(
        "{:<24} {:>5} {:>9} {:>12} {:>10} {:>8} {:>11} {:>10} {:>12} {:>14} {:>10} {:>10}",
        "scene",
        "P",
        "points",
        "points / P",
        "busiest",
        "edge",
        "neighbours",
        "kB sent",
        "compute (us)",
        "exposed (us)",
        "no overlap",
        "efficiency"
    );
    let mut figures = Vec::new();
    for scene in scenes {
        let model = model_of(&scene).unwrap_or_else(|e| fail(e));
        let t_u =
            point_update_seconds(&scene, Path::new("bench-results")).unwrap_or_else(|e| fail(e));
        let name = scene.display().to_string();
        for processes in PROCESSES {
            let per_process = loads(&model, processes);
            let total: usize = per_process.iter().map(|l| l.points).sum();
            let most = |of: &dyn Fn(&Load) -> usize| per_process.iter().map(of).max().unwrap_or(0);
            let (busiest, neighbours, values) = (
                most(&|l| l.points),
                most(&|l| l.neighbours),
                most(&|l| l.values),
            );
            let edge = most(&|l| l.edge);
            let check = (processes as f64).log2().ceil() * ALPHA / 5.0;
            let message = |l: &Load| l.neighbours as f64 * ALPHA + 8.0 * l.values as f64 / BETA;
            let sweep = |l: &Load| {
                let inner = (l.points - l.edge) as f64 * t_u;
                l.edge as f64 * t_u + inner.max(message(l))
            };
            let overlapped = per_process.iter().map(sweep).fold(0.0, f64::max) + check;
            let plain = (per_process.iter())
                .map(|l| l.points as f64 * t_u + message(l))
                .fold(0.0, f64::max)
                + check;
            let compute = busiest as f64 * t_u;
            let exchange = overlapped - compute;
            let serial_share = total as f64 * t_u / processes as f64;
            let efficiency = serial_share / overlapped;
            let without_overlap = serial_share / plain;
            println!(
                "{:<24} {:>5} {:>9} {:>12.0} {:>10} {:>8} {:>11} {:>10.1} {:>12.1} {:>14.1} {:>10.2} {:>10.2}",
                name,
                processes,
                total,
                total as f64 / processes as f64,
                busiest,
                edge,
                neighbours,
                8.0 * values as f64 / 1e3,
                1e6 * compute,
                1e6 * exchange,
                without_overlap,
                efficiency
            );
            figures.push(serde_json::json!({
                "scene": name,
                "processes": processes,
                "points": total,
                "busiest_process_points": busiest,
                "most_edge_points": edge,
                "most_neighbours": neighbours,
                "most_bytes_per_sweep": 8 * values,
                "ns_per_point_update": 1e9 * t_u,
                "compute_us_per_sweep": 1e6 * compute,
                "exposed_communication_us_per_sweep": 1e6 * exchange,
                "alpha_s": ALPHA,
                "beta_bytes_per_s": BETA,
                "modelled_efficiency_without_overlap": without_overlap,
                "modelled_efficiency": efficiency,
            }));
        }
    }
    if let Some(path) = json {
        write_json("fracture_model", &path, &figures);
    }
}
